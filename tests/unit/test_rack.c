// Racks: exact triangle / diamond geometry, ids, gaps, and that they are valid sim input.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "pool/pool.h"

static double dist(const pool_ball_state *a, const pool_ball_state *b) {
	return hypot(a->pos.x - b->pos.x, a->pos.y - b->pos.y);
}

static void check(pool_rack_kind kind, int count, int centre_id, double gap) {
	pool_table_def t = pool_default_table_def();
	pool_params p = pool_default_params();
	const double R = p.ball_radius, Rg = R + gap / 2;
	pool_ball_state b[20];
	assert_int_equal(pool_rack(kind, &t, &p, gap, b, 20), count + 1);
	assert_int_equal(b[0].id, 0);
	assert_true(b[0].pos.x == t.length / 4 && b[0].pos.y == t.width / 2 && b[0].pos.z == R);
	assert_int_equal(b[1].id, 1);
	assert_true(b[1].pos.x == 3 * t.length / 4 && b[1].pos.y == t.width / 2);
	// Every object ball has neighbours exactly 2 Rg away and none closer; ids unique.
	int seen[16] = {0};
	for (int i = 1; i <= count; ++i) {
		assert_true(b[i].id >= 1 && b[i].id <= count && !seen[b[i].id]);
		seen[b[i].id] = 1;
		assert_true(b[i].pos.x >= b[1].pos.x);
		int neighbours = 0;
		for (int j = 1; j <= count; ++j)
			if (j != i) {
				double d = dist(&b[i], &b[j]);
				assert_true(d >= 2 * Rg - 1e-13);
				neighbours += fabs(d - 2 * Rg) <= 1e-13;
			}
		assert_true(neighbours >= 2);
	}
	// The centre ball: centre row on y = W/2, at x = apex + 2 sqrt(3) Rg.
	for (int i = 1; i <= count; ++i)
		if (b[i].id == centre_id) {
			assert_true(fabs(b[i].pos.y - t.width / 2) <= 1e-15);
			assert_true(fabs(b[i].pos.x - (b[1].pos.x + 2 * sqrt(3.0) * Rg)) <= 1e-15);
		}
	// Valid input for a simulation (frozen neighbours touch within the tolerance).
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim;
	assert_int_equal(pool_sim_create(&def, &sim, NULL), POOL_OK);
	for (int i = 0; i <= count; ++i)
		assert_int_equal(pool_sim_add_ball(sim, &b[i], NULL), POOL_OK);
	pool_sim_destroy(sim);
}

static void test_racks(void **state) {
	(void)state;
	check(POOL_RACK_8BALL, 15, 8, 0.0);
	check(POOL_RACK_8BALL, 15, 8, 5e-4);
	check(POOL_RACK_9BALL, 9, 9, 0.0);
	check(POOL_RACK_9BALL, 9, 9, 1e-3);
	pool_table_def t = pool_default_table_def();
	pool_params p = pool_default_params();
	pool_ball_state b[20];
	assert_true(pool_rack(POOL_RACK_8BALL, &t, &p, 0.0, b, 15) < 0);
	assert_true(pool_rack(POOL_RACK_8BALL, &t, &p, -1.0, b, 20) < 0);
	pool_strike s = pool_break_strike(7.5);
	assert_true(s.speed == 7.5 && s.phi == 0.0 && s.theta == 0.0 && s.a == 0.0 && s.b == 0.0);
}

int main(void) {
	const struct CMUnitTest tests[] = {cmocka_unit_test(test_racks)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
