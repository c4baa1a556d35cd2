// Standard racks (8-ball triangle, 9-ball diamond) and the break strike.
#include "pool/rack.h"

#include <math.h>

static pool_ball_state at_rest(int32_t id, double x, double y, double R) {
	pool_ball_state b = {0};
	b.id = id;
	b.motion = POOL_MOTION_STATIONARY;
	b.pos.x = x;
	b.pos.y = y;
	b.pos.z = R;
	return b;
}

// The 15 reds behind the pink and the six colours on their spots (WPBSA rules, "The table"),
// at the table's scale; the cue ball in the D, between the brown and green spots.
static int rack_snooker(const pool_table_def *table, const pool_params *params, double gap, pool_ball_state *balls,
                        int capacity) {
	if (capacity < 22)
		return POOL_ERR_INVALID_ARGUMENT;
	const double R = params->ball_radius, L = table->length, W = table->width;
	const double sx = L / 3.569, sy = W / 1.778, cy = 0.5 * W;
	const double baulk = 0.737 * sx, d = 0.292 * sy, pink = 0.75 * L;
	const double Rg = R + 0.5 * gap;
	int n = 0;
	balls[n++] = at_rest(0, baulk, cy + 0.5 * d, R);
	for (int row = 0, id = 1; row < 5; ++row) {
		const double x = pink + 2.0 * R + gap + row * sqrt(3.0) * Rg;
		for (int j = 0; j <= row; ++j)
			balls[n++] = at_rest(id++, x, cy + (2.0 * j - row) * Rg, R);
	}
	balls[n++] = at_rest(22, baulk, cy - d, R);           // yellow: right of the D from the baulk end
	balls[n++] = at_rest(23, baulk, cy + d, R);           // green
	balls[n++] = at_rest(24, baulk, cy, R);               // brown
	balls[n++] = at_rest(25, 0.5 * L, cy, R);             // blue: the centre spot
	balls[n++] = at_rest(26, pink, cy, R);                // pink: the pyramid spot
	balls[n++] = at_rest(27, L - 0.324 * sx, cy, R);      // black: the spot
	return n;
}

// Carom's start (UMB): red on the foot spot, yellow on the head spot, the cue ball on the head
// string 6 in (0.1524 m) from it.
static int rack_carom(const pool_table_def *table, const pool_params *params, pool_ball_state *balls, int capacity) {
	if (capacity < 3)
		return POOL_ERR_INVALID_ARGUMENT;
	const double R = params->ball_radius, L = table->length, W = table->width;
	balls[0] = at_rest(0, 0.25 * L, 0.5 * W - 0.1524, R);
	balls[1] = at_rest(2, 0.75 * L, 0.5 * W, R);
	balls[2] = at_rest(1, 0.25 * L, 0.5 * W, R);
	return 3;
}

pool_strike pool_rack_break_strike(const pool_ball_state *balls, int count, double speed) {
	pool_strike s = pool_break_strike(speed);
	if (balls && count >= 2)
		s.phi = atan2(balls[1].pos.y - balls[0].pos.y, balls[1].pos.x - balls[0].pos.x);
	return s;
}

int pool_rack(pool_rack_kind kind, const pool_table_def *table, const pool_params *params,
              double gap, pool_ball_state *balls, int capacity) {
	// Row layouts from the apex towards +x; ids listed row by row, lowest y first.
	static const int rows8[] = {1, 2, 3, 4, 5};
	static const int ids8[] = {1, 2, 3, 4, 8, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15};
	static const int rows9[] = {1, 2, 3, 2, 1};
	static const int ids9[] = {1, 2, 3, 4, 9, 5, 6, 7, 8};
	if (!table || !params || !balls || !isfinite(gap) || gap < 0.0)
		return POOL_ERR_INVALID_ARGUMENT;
	if (kind == POOL_RACK_SNOOKER)
		return rack_snooker(table, params, gap, balls, capacity);
	if (kind == POOL_RACK_CAROM)
		return rack_carom(table, params, balls, capacity);
	const int *rows, *ids;
	int count;
	if (kind == POOL_RACK_8BALL) {
		rows = rows8;
		ids = ids8;
		count = 15;
	} else if (kind == POOL_RACK_9BALL) {
		rows = rows9;
		ids = ids9;
		count = 9;
	} else {
		return POOL_ERR_INVALID_ARGUMENT;
	}
	if (capacity < count + 1)
		return POOL_ERR_INVALID_ARGUMENT;
	const double R = params->ball_radius, L = table->length, W = table->width;
	const double Rg = R + 0.5 * gap; // neighbours' centres are 2 Rg apart
	int n = 0;
	balls[n++] = at_rest(0, 0.25 * L, 0.5 * W, R);
	for (int row = 0, k = 0; row < 5; ++row) {
		const double x = 0.75 * L + row * sqrt(3.0) * Rg;
		for (int j = 0; j < rows[row]; ++j, ++k)
			balls[n++] = at_rest(ids[k], x, 0.5 * W + (2.0 * j - (rows[row] - 1)) * Rg, R);
	}
	return n;
}

pool_strike pool_break_strike(double speed) {
	pool_strike s = {speed, 0.0, 0.0, 0.0, 0.0};
	return s;
}
