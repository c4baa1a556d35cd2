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

int pool_rack(pool_rack_kind kind, const pool_table_def *table, const pool_params *params,
              double gap, pool_ball_state *balls, int capacity) {
	// Row layouts from the apex towards +x; ids listed row by row, lowest y first.
	static const int rows8[] = {1, 2, 3, 4, 5};
	static const int ids8[] = {1, 2, 3, 4, 8, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15};
	static const int rows9[] = {1, 2, 3, 2, 1};
	static const int ids9[] = {1, 2, 3, 4, 9, 5, 6, 7, 8};
	if (!table || !params || !balls || !isfinite(gap) || gap < 0.0)
		return POOL_ERR_INVALID_ARGUMENT;
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
