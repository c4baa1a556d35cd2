// Shots for the rule tests: a table with the 2012 laws pinned (the rules must not move with the
// default physics), balls placed along lines to pockets, a shot run and judged.
#ifndef POOL_TEST_GAME_FIXTURE_H
#define POOL_TEST_GAME_FIXTURE_H

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "pool/game.h"
#include "recount.h"

#define FIX_PI 3.14159265358979323846
#define FIX_DEG (FIX_PI / 180.0)

/// A pool table (WPA 9 ft) with the laws of the 2012 work pinned (Petit cushion, constant ball
/// friction, no squirt), so a change of default models does not move these shots.
static inline pool_sim_def fix_pool_def(void) {
	pool_sim_def def = pool_default_sim_def();
	def.models.cushion = POOL_CUSHION_PETIT;
	def.models.ball_ball_friction = POOL_BALL_FRICTION_CONSTANT;
	def.models.squirt = POOL_SQUIRT_NONE;
	return def;
}

/// The carom table three cushion is played on: the "carom" preset (UMB: 2.84 x 1.42 m, nose 37 mm,
/// pockets "none") with its balls (61.5 mm, 210 g), as pool-game and Python's carom_sim_def set it.
static inline pool_sim_def fix_carom_def(void) {
	pool_sim_def def = fix_pool_def();
	if (pool_table_preset("carom", &def.table) != POOL_OK || pool_params_preset("carom", &def.params) != POOL_OK)
		abort();
	return def;
}

typedef struct fix_shot {
	pool_sim_def def;
	pool_sim *sim;
	int n;
	pool_ball_state balls[POOL_GAME_MAX_BALLS];
} fix_shot;

static inline void fix_begin(fix_shot *s, const pool_sim_def *def) {
	s->def = *def;
	s->sim = NULL;
	s->n = 0;
}

static inline void fix_ball(fix_shot *s, int32_t id, double x, double y) {
	s->balls[s->n++] = (pool_ball_state){.id = id, .motion = POOL_MOTION_STATIONARY,
	                                     .pos = {x, y, s->def.params.ball_radius}};
}

/// The point at distance d from p towards q.
static inline pool_vec3 fix_toward(pool_vec3 p, pool_vec3 q, double d) {
	const double dx = q.x - p.x, dy = q.y - p.y, n = hypot(dx, dy);
	return (pool_vec3){p.x + d * dx / n, p.y + d * dy / n, p.z};
}

/// A pocket's aiming point: the corner of the table, or the middle of a side rail.
static inline pool_vec3 fix_pocket(const pool_sim_def *def, pool_pocket pocket) {
	const double L = def->table.length, W = def->table.width, R = def->params.ball_radius;
	switch (pocket) {
	case POOL_POCKET_SW: return (pool_vec3){0, 0, R};
	case POOL_POCKET_SE: return (pool_vec3){L, 0, R};
	case POOL_POCKET_NW: return (pool_vec3){0, W, R};
	case POOL_POCKET_NE: return (pool_vec3){L, W, R};
	case POOL_POCKET_S: return (pool_vec3){L / 2, 0, R};
	case POOL_POCKET_N: return (pool_vec3){L / 2, W, R};
	default: return (pool_vec3){0, 0, R};
	}
}

/// Runs the shot: struck ball id, cue speed (m/s), aim at `to`, tip offset b (m, + above centre).
static inline void fix_run(fix_shot *s, int32_t struck, double speed, pool_vec3 to, double b) {
	pool_error err;
	assert_int_equal(pool_sim_create(&s->def, &s->sim, &err), POOL_OK);
	pool_vec3 from = {0, 0, 0};
	for (int i = 0; i < s->n; ++i) {
		assert_int_equal(pool_sim_add_ball(s->sim, &s->balls[i], &err), POOL_OK);
		if (s->balls[i].id == struck)
			from = s->balls[i].pos;
	}
	pool_strike strike = {.speed = speed, .phi = atan2(to.y - from.y, to.x - from.x), .b = b};
	assert_int_equal(pool_sim_strike(s->sim, struck, &strike, &err), POOL_OK);
	assert_int_equal(pool_sim_run(s->sim), POOL_OK);
	assert_int_equal(pool_sim_stop_reason(s->sim), POOL_STOP_REST);
}

/// Judges the shot run by fix_run under state.
static inline pool_game_result fix_judge(const fix_shot *s, const pool_game_state *state) {
	pool_game_shot shot = pool_game_shot_of_sim(s->sim);
	pool_game_result r;
	pool_error err;
	const pool_result code = pool_game_judge(state, &shot, &s->def.table, &r, &err);
	if (code != POOL_OK)
		fail_msg("pool_game_judge: %s", err.message);
	return r;
}

static inline void fix_end(fix_shot *s) {
	pool_sim_destroy(s->sim);
	s->sim = NULL;
}

/// Whether ball id fell into a pocket (pocket = NULL: any) in the shot, by the recount.
static inline bool fix_pocketed(const fix_shot *s, int32_t id, pool_pocket *pocket) {
	int32_t ids[64];
	pool_pocket where[64];
	const int n = recount_gone(s->sim, POOL_EVENT_POCKET, ids, where, 64);
	for (int i = 0; i < n; ++i)
		if (ids[i] == id) {
			if (pocket)
				*pocket = where[i];
			return true;
		}
	return false;
}

/// A mid-game state of `rules` (no break, nothing in hand), player 0.
static inline pool_game_state fix_state(pool_game_rules rules) {
	pool_game_state st = pool_game_default_state(rules);
	st.break_shot = false;
	st.ball_in_hand = false;
	st.behind_head_string = false;
	return st;
}

#endif
