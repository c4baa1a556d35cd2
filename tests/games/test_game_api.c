// The games library's API: names both ways, states refused with a message naming the field, bad
// shots refused, spot positions (WPA 1.4, UMB art. 28) and the opening positions.
#include "game_fixture.h"

#include <stdlib.h>
#include <string.h>

static void test_names_round_trip(void **state) {
	(void)state;
	for (int r = 0; r < 3; ++r)
		assert_int_equal(pool_game_rules_from_name(pool_game_rules_name((pool_game_rules)r)), r);
	assert_null(pool_game_rules_name((pool_game_rules)3));
	assert_int_equal(pool_game_rules_from_name("snooker"), -1);
	assert_int_equal(pool_game_rules_from_name(NULL), -1);
	for (int o = 0; o < 4; ++o)
		assert_int_equal(pool_game_outcome_from_name(pool_game_outcome_name((pool_game_outcome)o)), o);
	for (int k = 0; k < POOL_GAME_FOUL_KINDS; ++k)
		assert_int_equal(pool_game_foul_from_name(pool_game_foul_name(1u << k)), 1u << k);
	assert_null(pool_game_foul_name(3u));
	assert_int_equal(pool_game_foul_from_name("push"), 0u);
	assert_string_equal(pool_game_foul_name(POOL_FOUL_NO_RAIL), "no_rail");
	for (int k = 0; k <= POOL_REASON_NOT_CALLED; ++k)
		assert_int_equal(pool_game_reason_from_name(pool_game_reason_name((pool_game_reason)k)), k);
	for (int g = 0; g < 3; ++g)
		assert_int_equal(pool_game_group_from_name(pool_game_group_name((pool_game_group)g)), g);
}

static void expect_refused(const pool_game_state *st, const char *field) {
	pool_error err;
	assert_int_equal(pool_game_state_validate(st, &err), POOL_ERR_INVALID_ARGUMENT);
	if (strncmp(err.message, field, strlen(field)) != 0)
		fail_msg("expected a message naming %s, got \"%s\"", field, err.message);
}

static void test_states_out_of_range(void **state) {
	(void)state;
	pool_error err;
	for (int r = 0; r < 3; ++r) {
		const pool_game_state st = pool_game_default_state((pool_game_rules)r);
		assert_int_equal(pool_game_state_validate(&st, &err), POOL_OK);
	}
	pool_game_state st = fix_state(POOL_GAME_9BALL);
	st.fouls = 3;
	expect_refused(&st, "game.state.fouls");
	st = fix_state(POOL_GAME_9BALL);
	st.push_out = true;
	expect_refused(&st, "game.state.push_out");
	st = fix_state(POOL_GAME_9BALL);
	st.group = POOL_GROUP_SOLIDS;
	expect_refused(&st, "game.state.group");
	st = fix_state(POOL_GAME_8BALL);
	st.called_ball = 16;
	expect_refused(&st, "game.state.called.ball");
	st = fix_state(POOL_GAME_8BALL);
	st.called_pocket = (pool_pocket)9;
	expect_refused(&st, "game.state.called.pocket");
	st = fix_state(POOL_GAME_8BALL);
	st.player = 2;
	expect_refused(&st, "game.state.player");
	st = fix_state(POOL_GAME_8BALL);
	st.behind_head_string = true;
	expect_refused(&st, "game.state.behind_head_string");
	st = fix_state(POOL_GAME_THREE_CUSHION);
	st.opponent_cue_ball = st.cue_ball;
	expect_refused(&st, "game.state.opponent_cue_ball");
	st = fix_state(POOL_GAME_8BALL);
	st.rules = (pool_game_rules)7;
	expect_refused(&st, "game.rules");
}

static void test_bad_shots_refused(void **state) {
	(void)state;
	const pool_sim_def def = fix_pool_def();
	pool_ball_state balls[3] = {{.id = 0}, {.id = 16}, {.id = 3}};
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	pool_error err;
	assert_int_equal(pool_game_check_balls(&st, balls, 3, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "balls: id 16 is not a ball of 8ball (0 to 15)");
	st = fix_state(POOL_GAME_9BALL);
	balls[1].id = 10;
	assert_int_equal(pool_game_check_balls(&st, balls, 3, &err), POOL_ERR_INVALID_ARGUMENT);
	st = fix_state(POOL_GAME_THREE_CUSHION);
	assert_int_equal(pool_game_check_balls(&st, balls, 2, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "balls: three_cushion is played with three balls, not 2");
	balls[1].id = 1;
	balls[2].id = 2;
	assert_int_equal(pool_game_check_balls(&st, balls, 3, &err), POOL_OK);
	balls[0].id = 7;
	assert_int_equal(pool_game_check_balls(&st, balls, 3, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "balls: no ball has id 0 (game.state.cue_ball)");
	// A shot that does not start with a strike (balls set rolling) is not judged.
	pool_sim *sim;
	assert_int_equal(pool_sim_create(&def, &sim, &err), POOL_OK);
	pool_ball_state rolling = {.id = 0, .pos = {1.0, 0.6, def.params.ball_radius}, .vel = {1.0, 0, 0},
	                           .omega = {0, 1.0 / def.params.ball_radius, 0}};
	assert_int_equal(pool_sim_add_ball(sim, &rolling, &err), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	pool_game_shot shot = pool_game_shot_of_sim(sim);
	pool_game_result r;
	st = fix_state(POOL_GAME_9BALL);
	assert_int_equal(pool_game_judge(&st, &shot, &def.table, &r, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "events: a shot judged by the rules starts with a strike");
	pool_sim_destroy(sim);
	assert_int_equal(pool_game_judge(&st, NULL, &def.table, &r, &err), POOL_ERR_INVALID_ARGUMENT);
}

// WPA 1.4: on the foot spot when free; else on the long string behind it, touching the ball in
// the way; with the string behind full, in front of the foot spot.
static void test_spot_positions(void **state) {
	(void)state;
	const pool_sim_def def = fix_pool_def();
	const double R = def.params.ball_radius, L = def.table.length, W = def.table.width;
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	pool_vec3 at;
	assert_int_equal(pool_game_spot_position(&st, 9, &def.table, R, NULL, 0, &at), POOL_OK);
	assert_true(at.x == 0.75 * L && at.y == 0.5 * W && at.z == R);
	pool_ball_state on_spot = {.id = 3, .pos = {0.75 * L, 0.5 * W, R}};
	assert_int_equal(pool_game_spot_position(&st, 9, &def.table, R, &on_spot, 1, &at), POOL_OK);
	assert_true(at.x > 0.75 * L);
	assert_true(fabs(hypot(at.x - on_spot.pos.x, at.y - on_spot.pos.y) - 2.0 * R) < 1e-8);
	// The long string behind the foot spot full: balls every 2R from the foot spot to the rail.
	pool_ball_state line[16];
	int n = 0;
	for (double x = 0.75 * L; x < L - R; x += 2.0 * R + 1e-6)
		line[n] = (pool_ball_state){.id = n + 20, .pos = {x, 0.5 * W, R}}, ++n;
	assert_int_equal(pool_game_spot_position(&st, 9, &def.table, R, line, n, &at), POOL_OK);
	assert_true(at.x < 0.75 * L);
	assert_true(fabs(0.75 * L - at.x - 2.0 * R) < 1e-8);
	// Three cushion: the red (2) to the foot spot, ball 0 to the head spot; taken, the next one.
	const pool_game_state carom = fix_state(POOL_GAME_THREE_CUSHION);
	assert_int_equal(pool_game_spot_position(&carom, 2, &def.table, R, NULL, 0, &at), POOL_OK);
	assert_true(at.x == 0.75 * L);
	assert_int_equal(pool_game_spot_position(&carom, 0, &def.table, R, NULL, 0, &at), POOL_OK);
	assert_true(at.x == 0.25 * L);
	pool_ball_state blocker = {.id = 1, .pos = {0.25 * L, 0.5 * W, R}};
	assert_int_equal(pool_game_spot_position(&carom, 0, &def.table, R, &blocker, 1, &at), POOL_OK);
	assert_true(at.x == 0.5 * L);
}

static void test_opening_positions(void **state) {
	(void)state;
	const pool_sim_def def = fix_carom_def();
	pool_ball_state balls[16];
	assert_int_equal(pool_game_rack(POOL_GAME_THREE_CUSHION, &def.table, &def.params, 0.0, balls, 16), 3);
	assert_true(balls[2].pos.x == 0.75 * def.table.length && balls[1].pos.x == 0.25 * def.table.length);
	assert_true(fabs(balls[1].pos.y - balls[0].pos.y - 0.182) < 1e-12);
	assert_int_equal(pool_game_rack(POOL_GAME_THREE_CUSHION, &def.table, &def.params, 0.0, balls, 2),
	                 POOL_ERR_INVALID_ARGUMENT);
	const pool_sim_def pool = fix_pool_def();
	assert_int_equal(pool_game_rack(POOL_GAME_8BALL, &pool.table, &pool.params, 0.0, balls, 16), 16);
	assert_int_equal(pool_game_rack(POOL_GAME_9BALL, &pool.table, &pool.params, 0.0, balls, 16), 10);
	// Every opening position sets up in the library, and its break state passes its own checks.
	for (int r = 0; r < 3; ++r) {
		const pool_sim_def *d = r == 2 ? &def : &pool;
		const int n = pool_game_rack((pool_game_rules)r, &d->table, &d->params, 0.0, balls, 16);
		pool_sim *sim;
		pool_error err;
		assert_int_equal(pool_sim_create(d, &sim, &err), POOL_OK);
		for (int i = 0; i < n; ++i)
			assert_int_equal(pool_sim_add_ball(sim, &balls[i], &err), POOL_OK);
		pool_sim_destroy(sim);
		const pool_game_state st = pool_game_default_state((pool_game_rules)r);
		assert_int_equal(pool_game_check_balls(&st, balls, n, &err), POOL_OK);
	}
}

// pool_game_shoot does in one call what a player loop does per shot: the same events, the same
// verdict and the final states of pool_sim_state_at at the end.
static void test_shoot_in_one_call(void **state) {
	(void)state;
	const pool_sim_def def = fix_pool_def();
	pool_ball_state balls[16];
	const int n = pool_rack(POOL_RACK_9BALL, &def.table, &def.params, 0.0, balls, 16);
	const pool_strike strike = pool_break_strike(7.0);
	const pool_game_state st = pool_game_default_state(POOL_GAME_9BALL);
	pool_sim *one, *two;
	pool_error err;
	assert_int_equal(pool_sim_create(&def, &one, &err), POOL_OK);
	assert_int_equal(pool_sim_create(&def, &two, &err), POOL_OK);
	pool_game_result r;
	pool_ball_state final[16];
	assert_int_equal(pool_game_shoot(one, &def, balls, n, &strike, &st, &r, final, &err), POOL_OK);
	for (int i = 0; i < n; ++i)
		assert_int_equal(pool_sim_add_ball(two, &balls[i], &err), POOL_OK);
	assert_int_equal(pool_sim_strike(two, 0, &strike, &err), POOL_OK);
	assert_int_equal(pool_sim_run(two), POOL_OK);
	const pool_game_shot shot = pool_game_shot_of_sim(two);
	pool_game_result want;
	assert_int_equal(pool_game_judge(&st, &shot, &def.table, &want, &err), POOL_OK);
	assert_memory_equal(&r, &want, sizeof r);
	pool_ball_state end[16];
	assert_int_equal(pool_sim_state_at(two, pool_sim_end_time(two), end), POOL_OK);
	assert_memory_equal(final, end, (size_t)n * sizeof *end);
	// A strike the library refuses: its message, the result untouched.
	pool_strike bad = strike;
	bad.a = def.params.ball_radius;
	pool_game_result untouched = r;
	assert_int_equal(pool_game_shoot(one, &def, balls, n, &bad, &st, &r, final, &err), POOL_ERR_BAD_STRIKE);
	assert_true(strncmp(err.message, "strike", 6) == 0);
	assert_memory_equal(&r, &untouched, sizeof r);
	pool_sim_destroy(one);
	pool_sim_destroy(two);
}

// An allocator that runs out after `left` blocks (the simulation's memory, docs/library.md).
typedef struct budget {
	int left;
} budget;
static void *budget_alloc(size_t size, void *context) {
	budget *b = context;
	return b->left-- > 0 ? malloc(size) : NULL;
}
static void budget_free(void *memory, void *context) {
	(void)context;
	free(memory);
}

// A shot whose run fails says what the run met (pool_sim_last_error: when memory ran out), not
// only the code's name: the simulation's memory runs out after ever more blocks until one runs
// out inside pool_sim_run (the history growing past its first room, 16 events).
static void test_shoot_says_what_the_run_met(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	pool_ball_state balls[16];
	const int n = pool_rack(POOL_RACK_9BALL, &def.table, &def.params, 0.0, balls, 16);
	const pool_strike strike = pool_break_strike(7.0);
	const pool_game_state st = pool_game_default_state(POOL_GAME_9BALL);
	int in_run = 0;
	for (int blocks = 1; blocks < 200 && !in_run; ++blocks) {
		budget b = {blocks};
		def.allocator = (pool_allocator){budget_alloc, budget_free, &b};
		pool_sim *sim = NULL;
		pool_error err = {{0}};
		if (pool_sim_create(&def, &sim, &err) != POOL_OK)
			continue;
		pool_game_result r;
		pool_ball_state final[16];
		const pool_result code = pool_game_shoot(sim, &def, balls, n, &strike, &st, &r, final, &err);
		if (code == POOL_ERR_OUT_OF_MEMORY && strstr(err.message, "s: out of memory")) {
			assert_true(strncmp(err.message, "t = ", 4) == 0); // the instant it happened
			in_run = 1;
		}
		pool_sim_destroy(sim);
	}
	assert_true(in_run);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_names_round_trip),
		cmocka_unit_test(test_states_out_of_range),
		cmocka_unit_test(test_bad_shots_refused),
		cmocka_unit_test(test_spot_positions),
		cmocka_unit_test(test_opening_positions),
		cmocka_unit_test(test_shoot_in_one_call),
		cmocka_unit_test(test_shoot_says_what_the_run_met),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
