// Scenes at scale (scale_scene.h).
#include "scale_scene.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define RACK_GAP 1e-4          // m between racked neighbours (pool-bench-shot's gap break)
#define CUE_TO_APEX 1.27       // m, head spot to foot spot of the standard table
#define CUE_OFFSET 5e-3        // m, the cue ball's line beside the rack's axis
#define BREAK_SPEED 6.0        // m/s of the cue, as compare/scenarios/break.json
#define GAS_GAP 3e-3           // m between gas balls: a 1 mm move never makes two touch
#define GAS_RAIL_MARGIN 0.01   // m, gas balls start this far inside R of the rail lines
#define GAS_SPEED_MIN 0.5      // m/s, the rolling quarter of the gas
#define GAS_SPEED_MAX 2.0

// splitmix64: a fixed generator, so the scenes are the same on every platform.
static double uniform(uint64_t *state, double lo, double hi) {
	uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	z ^= z >> 31;
	return lo + (hi - lo) * (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

static pool_ball_state at_rest(int id, double x, double y, double radius) {
	pool_ball_state s;
	memset(&s, 0, sizeof s);
	s.id = id;
	s.pos = (pool_vec3){x, y, radius};
	return s;
}

static void rack(int balls, const pool_table_def *t, double radius, pool_ball_state *out, pool_strike *strike) {
	const double apex_x = 0.75 * t->length, apex_y = 0.5 * t->width, pitch = 2.0 * radius + RACK_GAP;
	const double cue_back = CUE_TO_APEX < 0.5 * t->length ? CUE_TO_APEX : 0.5 * t->length;
	out[0] = at_rest(0, apex_x - cue_back, apex_y + CUE_OFFSET, radius);
	int id = 1;
	for (int row = 0; id < balls; ++row) {
		// A partial last row takes the middle sites of its full row: the lattice keeps every
		// neighbour RACK_GAP away (centred off the sites, balls would overlap the row before).
		const int in_row = row + 1 < balls - id ? row + 1 : balls - id, first = (row + 1 - in_row) / 2;
		const double x = apex_x + row * pitch * sqrt(3.0) / 2.0;
		for (int k = first; k < first + in_row; ++k, ++id)
			out[id] = at_rest(id, x, apex_y + (k - 0.5 * row) * pitch, radius);
	}
	*strike = (pool_strike){BREAK_SPEED, 0.0, 0.0, 0.0, 0.0};
}

static void gas(int balls, const pool_table_def *t, double radius, pool_ball_state *out) {
	uint64_t state = 0x9A5000ull + (uint64_t)balls;
	const double margin = radius + GAS_RAIL_MARGIN, min_distance = 2.0 * radius + GAS_GAP;
	for (int placed = 0; placed < balls;) {
		const double x = uniform(&state, margin, t->length - margin), y = uniform(&state, margin, t->width - margin);
		int clear = 1;
		for (int k = 0; k < placed && clear; ++k)
			clear = hypot(x - out[k].pos.x, y - out[k].pos.y) >= min_distance;
		if (!clear)
			continue;
		out[placed] = at_rest(placed, x, y, radius);
		if (placed < balls / 4) {
			// Rolling: no slip at the contact, v + R k x w = 0.
			const double speed = uniform(&state, GAS_SPEED_MIN, GAS_SPEED_MAX);
			const double angle = uniform(&state, 0.0, 2.0 * 3.14159265358979323846);
			const double vx = speed * cos(angle), vy = speed * sin(angle);
			out[placed].vel = (pool_vec3){vx, vy, 0.0};
			out[placed].omega = (pool_vec3){-vy / radius, vx / radius, 0.0};
		}
		++placed;
	}
}

int pool_scale_scene(const char *family, int balls, const pool_params *params, pool_table_def *table,
                     pool_ball_state *out, bool *has_strike, pool_strike *strike, char *err, size_t err_size) {
	const int is_break = family && strcmp(family, "break") == 0, is_gas = family && strcmp(family, "gas") == 0;
	if (!is_break && !is_gas) {
		snprintf(err, err_size, "unknown scale family '%s' (break, gas)", family ? family : "");
		return -1;
	}
	if (balls < 2 || balls > POOL_SCALE_MAX_BALLS) {
		snprintf(err, err_size, "scale ball count %d is outside [2, %d]", balls, POOL_SCALE_MAX_BALLS);
		return -1;
	}
	const pool_table_def standard = pool_default_table_def();
	const double scale = sqrt((double)balls / POOL_SCALE_BALLS_PER_TABLE);
	*table = standard;
	table->length = standard.length * scale;
	table->width = standard.width * scale;
	table->corner_mouth = table->side_mouth = 0.0;
	*has_strike = is_break;
	memset(strike, 0, sizeof *strike);
	if (is_break)
		rack(balls, table, params->ball_radius, out, strike);
	else
		gas(balls, table, params->ball_radius, out);
	return 0;
}
