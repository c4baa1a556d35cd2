// libpool planning (pool/aim.h) through its public API, as a user links it. Every shot it
// returns is simulated again here with libpool alone and judged here (or by libpool games'
// rules, called here), so the search is checked by what its shots do, not by its own bookkeeping.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "pool/aim.h"

#define R 0.028575
#define TOP 5

static pool_ball_state ball(int id, double x, double y) { return (pool_ball_state){.id = id, .pos = {x, y, R}}; }

/// Runs strike on the position with libpool, and says whether ball `id` dropped into `pocket`
/// with the cue ball (id 0) still on the table.
static bool pots(const pool_ball_state *balls, int n, const pool_strike *strike, int32_t id, pool_pocket pocket,
                 pool_sim **sim_out) {
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim = NULL;
	assert_int_equal(pool_sim_create(&def, &sim, NULL), POOL_OK);
	for (int k = 0; k < n; ++k)
		assert_int_equal(pool_sim_add_ball(sim, &balls[k], NULL), POOL_OK);
	assert_int_equal(pool_sim_strike(sim, 0, strike, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	bool potted = false;
	for (int e = 0; e < count; ++e)
		if (events[e].type == POOL_EVENT_POCKET && events[e].pocket == pocket &&
		    pool_sim_event_states(sim, &events[e])[0].id == id)
			potted = true;
	pool_motion cue = POOL_MOTION_STATIONARY;
	for (int k = 0; k < n; ++k)
		if (pool_sim_balls(sim)[k].id == 0)
			cue = pool_sim_balls(sim)[k].motion;
	if (sim_out)
		*sim_out = sim;
	else
		pool_sim_destroy(sim);
	return potted && cue != POOL_MOTION_POCKETED && cue != POOL_MOTION_OFF_TABLE;
}

static pool_aim_def def_of(const pool_ball_state *balls, int n) {
	pool_aim_def d = pool_default_aim_def();
	d.balls = balls;
	d.ball_count = n;
	d.samples = 200;
	d.top = TOP;
	return d;
}

static void test_names(void **state) {
	(void)state;
	for (int k = 0; k < POOL_AIM_KINDS; ++k)
		assert_int_equal(pool_aim_kind_from_name(pool_aim_kind_name((pool_aim_kind)k)), k);
	assert_null(pool_aim_kind_name((pool_aim_kind)POOL_AIM_KINDS));
	assert_int_equal(pool_aim_kind_from_name("massé"), -1);
	assert_int_equal(pool_aim_kind_from_name(NULL), -1);
	pool_aim_def d = pool_default_aim_def();
	assert_int_equal(d.ball, POOL_AIM_NO_BALL);
	assert_int_equal(d.pocket, POOL_POCKET_NONE);
	assert_int_equal(d.samples, 400);
	assert_true(fabs(d.noise.phi - 0.125 * M_PI / 180.0) < 1e-15); // fastfiz
}

/// A straight-in shot: ball 1 on the line to the se pocket, the cue ball behind it at a small cut.
static void test_straight_in(void **state) {
	(void)state;
	pool_ball_state balls[] = {ball(0, 1.0, 0.5), ball(1, 2.0, 0.3), ball(2, 0.5, 1.0)};
	pool_aim_def d = def_of(balls, 3);
	d.ball = 1;
	d.pocket = POOL_POCKET_SE;
	pool_aim_shot shots[TOP];
	pool_aim_stats stats;
	int count = 0;
	pool_error e;
	assert_int_equal(pool_aim_search(&d, shots, TOP, &count, &stats, &e), POOL_OK);
	assert_true(count >= 1);
	assert_true(stats.potting >= count);
	for (int k = 0; k < count; ++k) {
		assert_int_equal(shots[k].ball, 1);
		assert_int_equal(shots[k].pocket, POOL_POCKET_SE);
		assert_true(pots(balls, 3, &shots[k].strike, 1, POOL_POCKET_SE, NULL));
		assert_true(shots[k].ci_low <= shots[k].p_success && shots[k].p_success <= shots[k].ci_high);
		assert_int_equal(shots[k].samples, 200);
		if (k > 0) // best first
			assert_true(shots[k].p_success <= shots[k - 1].p_success);
	}
	assert_int_equal(shots[0].kind, POOL_AIM_STRAIGHT);
	// Without noise every repetition is the shot itself: p = 1 exactly, the interval [lower, 1].
	d.noise = (pool_noise){0};
	assert_int_equal(pool_aim_search(&d, shots, TOP, &count, NULL, &e), POOL_OK);
	assert_true(count >= 1);
	assert_true(shots[0].p_success == 1.0 && shots[0].ci_high == 1.0 && shots[0].ci_low > 0.95);
}

/// Every straight path to ball 1 blocked: a wall of balls between the cue ball and it. No shot
/// found is straight; the best pot it through a wall ball (combinations), and without those, round
/// the wall off a cushion.
static void test_blocked_finds_a_kick(void **state) {
	(void)state;
	pool_ball_state balls[16];
	int n = 0;
	balls[n++] = ball(0, 0.35, 0.635);
	balls[n++] = ball(1, 1.6, 0.635);
	for (double y = 0.3; y < 1.0; y += 2 * R + 0.004, ++n) // the wall, x = 0.9
		balls[n] = ball(n + 1, 0.9, y);
	pool_aim_def d = def_of(balls, n);
	d.ball = 1;
	pool_aim_shot shots[TOP];
	int count = 0;
	pool_error e;
	assert_int_equal(pool_aim_search(&d, shots, TOP, &count, NULL, &e), POOL_OK);
	assert_true(count >= 1);
	for (int k = 0; k < count; ++k) {
		assert_int_not_equal(shots[k].kind, POOL_AIM_STRAIGHT);
		assert_true(pots(balls, n, &shots[k].strike, 1, shots[k].pocket, NULL));
	}
	d.kinds = 1u << POOL_AIM_STRAIGHT | 1u << POOL_AIM_BANK | 1u << POOL_AIM_KICK;
	assert_int_equal(pool_aim_search(&d, shots, TOP, &count, NULL, &e), POOL_OK);
	assert_true(count >= 1);
	for (int k = 0; k < count; ++k) {
		assert_true(shots[k].kind == POOL_AIM_KICK || shots[k].kind == POOL_AIM_BANK);
		assert_true(pots(balls, n, &shots[k].strike, 1, shots[k].pocket, NULL));
	}
	// With straight shots alone there is nothing to find.
	d.kinds = 1u << POOL_AIM_STRAIGHT;
	assert_int_equal(pool_aim_search(&d, shots, TOP, &count, NULL, &e), POOL_OK);
	assert_int_equal(count, 0);
}

/// 9-ball: ball 2 sits in front of a pocket, ball 1 (the lowest) elsewhere; every shot found must
/// be legal under the rules, judged here with libpool games on the simulated shot.
static void test_nine_ball_rules(void **state) {
	(void)state;
	pool_ball_state balls[] = {ball(0, 0.8, 0.6), ball(1, 1.6, 0.9), ball(2, 2.3, 0.25), ball(9, 1.9, 0.5)};
	pool_game_state game = pool_game_default_state(POOL_GAME_9BALL);
	game.break_shot = false;
	game.ball_in_hand = false;
	game.push_out_available = false;
	game.behind_head_string = false;
	pool_aim_def d = def_of(balls, 4);
	d.game = &game;
	pool_aim_shot shots[TOP];
	int count = 0;
	pool_error e;
	if (pool_aim_search(&d, shots, TOP, &count, NULL, &e) != POOL_OK)
		fail_msg("%s", e.message);
	assert_true(count >= 1);
	for (int k = 0; k < count; ++k) {
		pool_sim *sim = NULL;
		pots(balls, 4, &shots[k].strike, shots[k].ball, shots[k].pocket, &sim);
		pool_game_shot shot = pool_game_shot_of_sim(sim);
		pool_game_result r;
		pool_error je;
		if (pool_game_judge(&game, &shot, &d.sim.table, &r, &je) != POOL_OK)
			fail_msg("%s", je.message);
		assert_true(r.legal);
		assert_int_equal(r.first_hit, 1);
		bool dropped = false;
		for (int j = 0; j < r.pocketed_count; ++j)
			dropped = dropped || (r.pocketed[j] == shots[k].ball && r.pocketed_in[j] == shots[k].pocket);
		assert_true(dropped);
		pool_sim_destroy(sim);
	}
}

/// distinct: the shots returned differ in ball, pocket, kind, second ball or cushion, and the best
/// is the best of the plain search (the best variant of the best shot).
static void test_distinct(void **state) {
	(void)state;
	pool_ball_state balls[] = {ball(0, 0.95, 0.42), ball(1, 1.78, 0.82), ball(2, 2.18, 0.33), ball(3, 0.52, 1.02),
	                           ball(9, 2.02, 1.12)};
	pool_aim_def d = def_of(balls, 5);
	pool_aim_shot plain[TOP], distinct[TOP];
	int n1 = 0, n2 = 0;
	assert_int_equal(pool_aim_search(&d, plain, TOP, &n1, NULL, NULL), POOL_OK);
	d.distinct = true;
	assert_int_equal(pool_aim_search(&d, distinct, TOP, &n2, NULL, NULL), POOL_OK);
	assert_true(n1 > 0 && n2 > 1);
	for (int i = 0; i < n2; ++i)
		for (int j = 0; j < i; ++j)
			assert_false(distinct[i].kind == distinct[j].kind && distinct[i].ball == distinct[j].ball &&
			             distinct[i].pocket == distinct[j].pocket && distinct[i].via == distinct[j].via &&
			             distinct[i].rail == distinct[j].rail);
	assert_true(distinct[0].ball == plain[0].ball && distinct[0].pocket == plain[0].pocket &&
	            distinct[0].kind == plain[0].kind);
}

/// Without a time budget the result depends on the input alone: 1 and 2 threads agree bit for bit.
static void test_threads_agree(void **state) {
	(void)state;
	pool_ball_state balls[] = {ball(0, 0.7, 0.4), ball(1, 1.5, 0.9), ball(2, 2.0, 0.35), ball(3, 1.1, 1.05),
	                           ball(4, 0.4, 1.0)};
	pool_aim_def d = def_of(balls, 5);
	pool_aim_shot one[TOP], two[TOP];
	int n1 = 0, n2 = 0;
	d.threads = 1;
	assert_int_equal(pool_aim_search(&d, one, TOP, &n1, NULL, NULL), POOL_OK);
	d.threads = 2;
	assert_int_equal(pool_aim_search(&d, two, TOP, &n2, NULL, NULL), POOL_OK);
	assert_int_equal(n1, n2);
	assert_true(n1 > 0);
	assert_memory_equal(one, two, (size_t)n1 * sizeof one[0]);
}

/// A budget stops the search and still answers.
static void test_time_budget(void **state) {
	(void)state;
	pool_ball_state balls[16];
	int n = 0;
	for (int i = 0; i < 4; ++i)
		for (int j = 0; j < 4; ++j)
			balls[n] = ball(n, 0.3 + 0.6 * i + 0.05 * j, 0.2 + 0.28 * j + 0.03 * i), ++n;
	pool_aim_def d = def_of(balls, n);
	d.time_budget = 1e-3;
	pool_aim_shot shots[TOP];
	pool_aim_stats stats;
	int count = -1;
	assert_int_equal(pool_aim_search(&d, shots, TOP, &count, &stats, NULL), POOL_OK);
	assert_true(stats.budget_reached);
	assert_true(count >= 0 && count <= TOP);
	assert_true(stats.refined < stats.candidates);
}

static void expect_error(const pool_aim_def *d, pool_result code, const char *needle) {
	pool_aim_shot shots[TOP];
	int count = 0;
	pool_error e;
	assert_int_equal(pool_aim_search(d, shots, TOP, &count, NULL, &e), code);
	if (!strstr(e.message, needle))
		fail_msg("message '%s' lacks '%s'", e.message, needle);
	// The check alone says the same.
	pool_error v;
	assert_int_equal(pool_aim_def_validate(d, &v), code);
	assert_string_equal(v.message, e.message);
}

static void test_bad_input(void **state) {
	(void)state;
	pool_ball_state balls[] = {ball(0, 1.0, 0.5), ball(1, 2.0, 0.3)};
	pool_aim_def d = def_of(balls, 2);
	pool_aim_def b = d;
	b.cue_ball = 7;
	expect_error(&b, POOL_ERR_UNKNOWN_BALL, "aim.cue_ball: no ball has id 7");
	b = d, b.ball = 5;
	expect_error(&b, POOL_ERR_UNKNOWN_BALL, "aim.ball");
	b = d, b.ball = 0;
	expect_error(&b, POOL_ERR_UNKNOWN_BALL, "aim.ball");
	b = d, b.samples = 0;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.samples");
	b = d, b.top = 0;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.top");
	b = d, b.time_budget = -1.0;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.time_budget");
	b = d, b.time_budget = NAN;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.time_budget");
	b = d, b.kinds = 1u << POOL_AIM_KINDS;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.kinds");
	b = d, b.pocket = (pool_pocket)9;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.pocket");
	b = d, b.noise.phi = -1.0;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "phi");
	b = d, b.ball_count = 1;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "aim.balls");
	pool_ball_state overlap[] = {ball(0, 1.0, 0.5), ball(1, 1.01, 0.5)};
	b = def_of(overlap, 2);
	expect_error(&b, POOL_ERR_OVERLAP, "balls[1]");
	pool_ball_state moving[] = {ball(0, 1.0, 0.5), ball(1, 2.0, 0.3)};
	moving[1].vel.x = 0.5;
	b = def_of(moving, 2);
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "balls[1]: must be at rest");
	pool_ball_state carom[] = {ball(0, 1.0, 0.5), ball(1, 2.0, 0.3), ball(2, 0.5, 0.3)};
	pool_game_state three = pool_game_default_state(POOL_GAME_THREE_CUSHION);
	b = def_of(carom, 3), b.game = &three;
	expect_error(&b, POOL_ERR_INVALID_ARGUMENT, "three_cushion has no pockets");
	assert_int_equal(pool_aim_def_validate(&d, NULL), POOL_OK);
	assert_int_equal(pool_aim_def_validate(NULL, NULL), POOL_ERR_INVALID_ARGUMENT);
	pool_aim_shot shot;
	int count;
	assert_int_equal(pool_aim_search(NULL, &shot, 1, &count, NULL, NULL), POOL_ERR_INVALID_ARGUMENT);
	assert_int_equal(pool_aim_search(&d, NULL, 1, &count, NULL, NULL), POOL_ERR_INVALID_ARGUMENT);
	assert_int_equal(pool_aim_search(&d, &shot, 1, NULL, NULL, NULL), POOL_ERR_INVALID_ARGUMENT);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_names),         cmocka_unit_test(test_straight_in),
		cmocka_unit_test(test_blocked_finds_a_kick), cmocka_unit_test(test_nine_ball_rules),
		cmocka_unit_test(test_threads_agree), cmocka_unit_test(test_time_budget), cmocka_unit_test(test_distinct),
		cmocka_unit_test(test_bad_input),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
