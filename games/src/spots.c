// Putting balls on the table: the spot of a ball the rules return (WPA 1.4, UMB art. 28) and a
// game's opening position (pool_rack's racks, UMB art. 23 for three cushion).
#include <math.h>
#include <stdlib.h>

#include "pool/game.h"
#include "rules.h"

// Room between a spotted ball and its neighbours, so that rounding in the contact distance never
// makes the simulation refuse it as an overlap (it accepts touching within POOL_TOUCH_TOLERANCE).
#define POOL_GAME_SPOT_CLEARANCE 1e-9

static bool free_at(double x, double y, double radius, const pool_ball_state *balls, int count, int32_t id) {
	const double d2 = (2.0 * radius + POOL_GAME_SPOT_CLEARANCE) * (2.0 * radius + POOL_GAME_SPOT_CLEARANCE);
	for (int i = 0; i < count; ++i) {
		if (balls[i].id == id || balls[i].motion == POOL_MOTION_POCKETED || balls[i].motion == POOL_MOTION_OFF_TABLE)
			continue;
		const double dx = balls[i].pos.x - x, dy = balls[i].pos.y - y;
		if (dx * dx + dy * dy < d2 * (1.0 - 1e-15))
			return false;
	}
	return true;
}

static int compare_double(const void *a, const void *b) {
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

// WPA 1.4: on the long string as near to the foot spot as possible between it and the foot rail,
// touching the ball in the way when it is not free; else in front of the foot spot, nearest to it.
static pool_result spot_on_long_string(const pool_table_def *table, double radius, const pool_ball_state *balls,
                                       int count, int32_t id, pool_vec3 *pos) {
	const double y = 0.5 * table->width, foot = 0.75 * table->length;
	const double reach = pool_table_contact_distance(table, radius);
	const double x_min = reach, x_max = table->length - reach;
	// Candidates: the foot spot and every x where the ball touches a ball near the long string.
	double *xs = malloc(((size_t)count * 2 + 1) * sizeof *xs);
	if (!xs)
		return POOL_ERR_OUT_OF_MEMORY;
	int n = 0;
	xs[n++] = foot;
	const double touch = 2.0 * radius + 2.0 * POOL_GAME_SPOT_CLEARANCE;
	for (int i = 0; i < count; ++i) {
		const double dy = balls[i].pos.y - y;
		if (balls[i].id == id || fabs(dy) >= touch)
			continue;
		const double dx = sqrt(touch * touch - dy * dy);
		xs[n++] = balls[i].pos.x + dx;
		xs[n++] = balls[i].pos.x - dx;
	}
	qsort(xs, (size_t)n, sizeof *xs, compare_double);
	pool_result r = POOL_ERR_INVALID_ARGUMENT;
	for (int i = 0; i < n && r != POOL_OK; ++i) // behind the foot spot, nearest first
		if (xs[i] >= foot && xs[i] <= x_max && free_at(xs[i], y, radius, balls, count, id))
			*pos = (pool_vec3){xs[i], y, radius}, r = POOL_OK;
	for (int i = n - 1; i >= 0 && r != POOL_OK; --i) // in front of it, nearest first
		if (xs[i] < foot && xs[i] >= x_min && free_at(xs[i], y, radius, balls, count, id))
			*pos = (pool_vec3){xs[i], y, radius}, r = POOL_OK;
	free(xs);
	return r;
}

pool_result pool_game_spot_position(const pool_game_state *state, int32_t id, const pool_table_def *table,
                                    double ball_radius, const pool_ball_state *balls, int count, pool_vec3 *pos) {
	if (!state || !table || !pos || (count > 0 && !balls) || count < 0 || !(ball_radius > 0.0))
		return POOL_ERR_INVALID_ARGUMENT;
	if (state->rules != POOL_GAME_THREE_CUSHION)
		return spot_on_long_string(table, ball_radius, balls, count, id, pos);
	// UMB art. 28: the red to the foot spot, the first player's ball to the head spot, the other
	// cue ball to the centre spot; a ball whose spot is taken goes to the next free one.
	const double y = 0.5 * table->width;
	const double spots[3] = {0.75 * table->length, 0.25 * table->length, 0.5 * table->length};
	const int32_t first = state->player == 0 ? state->cue_ball : state->opponent_cue_ball;
	const int32_t second = state->player == 0 ? state->opponent_cue_ball : state->cue_ball;
	const int own = id == first ? 1 : id == second ? 2 : 0;
	for (int k = 0; k < 3; ++k) {
		const double x = spots[(own + k) % 3];
		if (free_at(x, y, ball_radius, balls, count, id)) {
			*pos = (pool_vec3){x, y, ball_radius};
			return POOL_OK;
		}
	}
	return POOL_ERR_INVALID_ARGUMENT;
}

// UMB art. 23: the breaker's ball on the starting line this far beside the opponent's ball.
#define POOL_GAME_CAROM_START_OFFSET 0.182

int pool_game_rack(pool_game_rules rules, const pool_table_def *table, const pool_params *params, double gap,
                   pool_ball_state *balls, int capacity) {
	if (!table || !params || (capacity > 0 && !balls))
		return POOL_ERR_INVALID_ARGUMENT;
	if (rules == POOL_GAME_8BALL || rules == POOL_GAME_9BALL)
		return pool_rack(rules == POOL_GAME_8BALL ? POOL_RACK_8BALL : POOL_RACK_9BALL, table, params, gap, balls,
		                 capacity);
	if (rules != POOL_GAME_THREE_CUSHION)
		return POOL_ERR_INVALID_ARGUMENT;
	if (capacity < 3)
		return POOL_ERR_INVALID_ARGUMENT;
	const double R = params->ball_radius, y = 0.5 * table->width;
	const pool_vec3 at[3] = {{0.25 * table->length, y - POOL_GAME_CAROM_START_OFFSET, R},
	                         {0.25 * table->length, y, R},
	                         {0.75 * table->length, y, R}};
	for (int i = 0; i < 3; ++i)
		balls[i] = (pool_ball_state){.id = i, .motion = POOL_MOTION_STATIONARY, .pos = at[i]};
	return 3;
}
