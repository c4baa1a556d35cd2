// Test fixtures shared by the unit tests that drive a whole pool_sim: create one, add balls,
// failing the cmocka test with the library's message on an error. Include after <cmocka.h>.
#ifndef POOL_TEST_SIM_FIXTURE_H
#define POOL_TEST_SIM_FIXTURE_H

#include "pool/pool.h"

/// The default def with the "thesis" model set: for the tests whose oracles are the 2012 work's
/// laws (Petit's cushion impulse, a constant mu_ball; docs/validation.md).
static inline pool_sim_def thesis_sim_def(void) {
	pool_sim_def def = pool_default_sim_def();
	def.models = pool_thesis_models();
	return def;
}

static inline pool_sim *make_sim(const pool_sim_def *def) {
	pool_sim *sim = NULL;
	pool_error err;
	if (pool_sim_create(def, &sim, &err) != POOL_OK)
		fail_msg("create: %s", err.message);
	return sim;
}

static inline void add_ball(pool_sim *sim, const pool_ball_state *b) {
	pool_error err;
	if (pool_sim_add_ball(sim, b, &err) != POOL_OK)
		fail_msg("add ball %d: %s", (int)b->id, err.message);
}

/// Index in s[0..n) of the ball with this id (an event's ball among a shot's), -1 when there is
/// none.
static inline int find_ball(const pool_ball_state *s, int n, int32_t id) {
	for (int i = 0; i < n; ++i)
		if (s[i].id == id)
			return i;
	return -1;
}

/// find_ball for a ball that must be there: fails the test when there is none.
static inline int ball_index(const pool_ball_state *s, int n, int32_t id) {
	const int i = find_ball(s, n, id);
	if (i < 0)
		fail_msg("no ball with id %d", (int)id);
	return i;
}

#endif
