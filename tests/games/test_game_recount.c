// 10,000 random shots: what the rules report they read (first_hit, rails_after_contact, pocketed
// with pockets, off_table) equals the independent recount from the raw event list (recount.h).
// Breaks of the 8-ball and 9-ball racks, scattered tables of 16 balls, and airborne shots (jumps
// that send balls off the table), all from one seeded generator.
#include "game_fixture.h"

#include <stdio.h>

#define SHOTS 10000

static uint64_t next_u64(uint64_t *s) {
	uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

static double uniform(uint64_t *s, double lo, double hi) {
	return lo + (hi - lo) * (double)(next_u64(s) >> 11) * (1.0 / 9007199254740992.0);
}

/// Up to 16 balls (ids 0..15) at random places on the table, none overlapping.
static int scatter(uint64_t *rng, const pool_sim_def *def, pool_ball_state *balls) {
	const double R = def->params.ball_radius, L = def->table.length, W = def->table.width;
	const double m = pool_table_contact_distance(&def->table, R) + 0.02;
	int n = 0;
	for (int tries = 0; n < 16 && tries < 1000; ++tries) {
		const double x = uniform(rng, m, L - m), y = uniform(rng, m, W - m);
		bool clear = true;
		for (int j = 0; j < n && clear; ++j)
			clear = hypot(balls[j].pos.x - x, balls[j].pos.y - y) > 2.0 * R + 1e-4;
		if (clear)
			balls[n] = (pool_ball_state){.id = n, .pos = {x, y, R}}, ++n;
	}
	return n;
}

static void test_rules_read_what_the_events_say(void **state) {
	(void)state;
	uint64_t rng = 22;
	pool_sim *sim = NULL;
	pool_error err;
	int links = 0, pockets = 0, off = 0, no_hit = 0, linked_first = 0;
	for (int shot = 0; shot < SHOTS; ++shot) {
		const int kind = (int)(next_u64(&rng) % 5); // 0, 1: racks; 2, 3: scattered; 4: airborne
		pool_sim_def def = fix_pool_def();
		def.airborne = kind == 4;
		pool_ball_state balls[16];
		int n;
		pool_strike strike = {.speed = uniform(&rng, 0.5, 9.0), .phi = uniform(&rng, -FIX_PI, FIX_PI),
		                      .a = uniform(&rng, -0.5, 0.5) * def.params.ball_radius,
		                      .b = uniform(&rng, -0.5, 0.5) * def.params.ball_radius};
		if (kind <= 1) {
			n = pool_rack(kind == 0 ? POOL_RACK_8BALL : POOL_RACK_9BALL, &def.table, &def.params,
			              uniform(&rng, 0.0, 1e-3), balls, 16);
			strike.phi = uniform(&rng, -3.0, 3.0) * FIX_DEG; // at the rack
		} else {
			n = scatter(&rng, &def, balls);
		}
		if (kind == 4)
			strike.theta = uniform(&rng, 0.0, 60.0) * FIX_DEG;
		assert_int_equal(sim ? pool_sim_reset(sim, &def, &err) : pool_sim_create(&def, &sim, &err), POOL_OK);
		for (int i = 0; i < n; ++i)
			assert_int_equal(pool_sim_add_ball(sim, &balls[i], &err), POOL_OK);
		if (pool_sim_strike(sim, 0, &strike, &err) != POOL_OK)
			continue; // a jump the strike law refuses (the cue would pass through the cloth)
		assert_int_equal(pool_sim_run(sim), POOL_OK);

		pool_game_state st = fix_state(n == 16 ? POOL_GAME_8BALL : POOL_GAME_9BALL);
		if (n != 16 && n != 10) {
			st = fix_state(POOL_GAME_8BALL); // a scattered table of fewer balls: 8-ball ids fit
		}
		pool_game_shot gs = pool_game_shot_of_sim(sim);
		pool_game_result r;
		assert_int_equal(pool_game_judge(&st, &gs, &def.table, &r, &err), POOL_OK);

		int at;
		const int32_t first = recount_first_hit(sim, &at);
		if (first != r.first_hit)
			fail_msg("shot %d: first_hit %d, the recount says %d", shot, r.first_hit, first);
		const int rails = recount_rails_after_contact(sim);
		if (rails != r.rails_after_contact)
			fail_msg("shot %d: rails_after_contact %d, the recount says %d", shot, r.rails_after_contact, rails);
		int32_t ids[64];
		pool_pocket where[64];
		const int p = recount_gone(sim, POOL_EVENT_POCKET, ids, where, 64);
		assert_int_equal(p, r.pocketed_count);
		for (int i = 0; i < p; ++i) {
			assert_int_equal(ids[i], r.pocketed[i]);
			assert_int_equal(where[i], r.pocketed_in[i]);
		}
		const int o = recount_gone(sim, POOL_EVENT_OFF_TABLE, ids, NULL, 64);
		assert_int_equal(o, r.off_table_count);
		for (int i = 0; i < o; ++i)
			assert_int_equal(ids[i], r.off_table[i]);
		int count = 0;
		const pool_event *ev = pool_sim_events(sim, &count);
		for (int k = 0; k < count; ++k)
			links += ev[k].type == POOL_EVENT_LINK_BEGIN;
		linked_first += at > 0 && ev[at].type != POOL_EVENT_BALL_BALL;
		pockets += p;
		off += o;
		no_hit += first == RECOUNT_NONE;
	}
	pool_sim_destroy(sim);
	print_message("%d shots: %d balls pocketed, %d off the table, %d shots hitting no ball, %d LINK clusters, "
	              "%d first contacts inside a cluster\n", SHOTS, pockets, off, no_hit, links, linked_first);
	// The sample must exercise what it compares.
	assert_true(pockets > 1000);
	assert_true(off > 10);
	assert_true(no_hit > 100);
	assert_true(links > 10);
}

int main(void) {
	const struct CMUnitTest tests[] = {cmocka_unit_test(test_rules_read_what_the_events_say)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
