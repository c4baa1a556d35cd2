// Eight ball, one scenario per rule (WPA World Standardized Rules section 3, docs/games.md): each
// shot is built so its events decide the rule, checked first by the independent recount.
#include "game_fixture.h"

// A straight pot of `ball` into the north-east corner: the ball 0.3 m from the corner point, the
// cue ball 0.24 m behind it on the same line, struck with draw so that it stays out.
static void straight_pot(fix_shot *s, int32_t ball) {
	pool_sim_def def = fix_pool_def();
	fix_begin(s, &def);
	const pool_vec3 target = fix_pocket(&def, POOL_POCKET_NE), from = {2.1, 0.95, 0};
	const pool_vec3 obj = fix_toward(target, from, 0.3);
	fix_ball(s, 0, from.x, from.y);
	fix_ball(s, ball, obj.x, obj.y);
}

static void shoot_straight(fix_shot *s, int32_t ball, double speed, double b_factor) {
	fix_run(s, 0, speed, s->balls[1].pos, b_factor * s->def.params.ball_radius);
	assert_int_equal(recount_first_hit(s->sim, NULL), ball);
}

// Balls away from the shot's line, at the head end of the table.
static void park(fix_shot *s, const int32_t *ids, int n) {
	for (int i = 0; i < n; ++i)
		fix_ball(s, ids[i], 0.15 + 0.08 * i, 0.15);
}

// 3.4: on an open table any object ball may be hit first except the 8.
static void test_open_table_eight_first(void **state) {
	(void)state;
	fix_shot s;
	straight_pot(&s, 8);
	const int32_t rest[] = {3, 12};
	park(&s, rest, 2);
	shoot_straight(&s, 8, 1.0, -0.3);
	const pool_game_state st = fix_state(POOL_GAME_8BALL);
	const pool_game_result r = fix_judge(&s, &st);
	// The 8 dropped on a foul before the group was cleared: the rack is lost (3.8).
	assert_true(r.fouls & POOL_FOUL_WRONG_BALL_FIRST);
	assert_int_equal(r.outcome, POOL_OUTCOME_LOSS);
	assert_int_equal(r.reason, POOL_REASON_EIGHT_EARLY);
	fix_end(&s);
}

// 3.4: the called ball legally pocketed on an open table gives the shooter its group; 3.5: the
// shooter continues.
static void test_called_ball_chooses_the_group(void **state) {
	(void)state;
	fix_shot s;
	straight_pot(&s, 3);
	const int32_t rest[] = {8, 12, 5};
	park(&s, rest, 3);
	shoot_straight(&s, 3, 1.5, -0.3);
	pool_pocket where;
	assert_true(fix_pocketed(&s, 3, &where));
	assert_int_equal(where, POOL_POCKET_NE);
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	st.called_ball = 3;
	st.called_pocket = POOL_POCKET_NE;
	pool_game_result r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_CONTINUE);
	assert_int_equal(r.next.group, POOL_GROUP_SOLIDS);
	assert_int_equal(r.next.called_ball, POOL_GAME_NO_BALL);
	// 3.6: called in another pocket, the same shot pockets nothing for the shooter: the turn
	// passes without a foul, the ball stays down and the table stays open.
	st.called_pocket = POOL_POCKET_NW;
	r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_int_equal(r.reason, POOL_REASON_NOT_CALLED);
	assert_int_equal(r.next.group, POOL_GROUP_OPEN);
	assert_false(r.ball_in_hand);
	fix_end(&s);
}

// Without a call (docs/games.md: the first ball of a legal group to drop counts as called), a
// stripe pocketed on an open table makes the shooter stripes, the opponent solids.
static void test_uncalled_shot_chooses_the_group(void **state) {
	(void)state;
	fix_shot s;
	straight_pot(&s, 12);
	const int32_t rest[] = {8, 3};
	park(&s, rest, 2);
	shoot_straight(&s, 12, 1.5, -0.3);
	assert_true(fix_pocketed(&s, 12, NULL));
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.outcome, POOL_OUTCOME_CONTINUE);
	assert_int_equal(r.next.group, POOL_GROUP_STRIPES);
	// 1.6: the same shot declared a safety passes the turn; the group is not chosen.
	st.safety = true;
	r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_int_equal(r.reason, POOL_REASON_SAFETY);
	assert_int_equal(r.next.group, POOL_GROUP_OPEN);
	fix_end(&s);
}

// 6.2 and 3.9: a shooter with solids hitting a stripe first fouls; the opponent has ball in hand
// anywhere and sees the other group (stripes) as theirs.
static void test_wrong_group_first(void **state) {
	(void)state;
	fix_shot s;
	straight_pot(&s, 12);
	const int32_t rest[] = {8, 3};
	park(&s, rest, 2);
	shoot_straight(&s, 12, 1.5, -0.3);
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	st.group = POOL_GROUP_SOLIDS;
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_WRONG_BALL_FIRST);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_true(r.ball_in_hand);
	assert_false(r.behind_head_string);
	assert_int_equal(r.next.group, POOL_GROUP_STRIPES);
	fix_end(&s);
}

// 3.8 (e): the 8 pocketed before the shooter's group is cleared loses the rack.
static void test_eight_early_loses(void **state) {
	(void)state;
	fix_shot s;
	straight_pot(&s, 8);
	const int32_t rest[] = {3, 12};
	park(&s, rest, 2);
	shoot_straight(&s, 8, 1.5, -0.3);
	assert_true(fix_pocketed(&s, 8, NULL));
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	st.group = POOL_GROUP_STRIPES; // the 12 is still on the table
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.outcome, POOL_OUTCOME_LOSS);
	assert_int_equal(r.reason, POOL_REASON_EIGHT_EARLY);
	fix_end(&s);
}

// 3.5 and 3.8 (d): with the group cleared, the 8 pocketed in the called pocket wins; in another
// pocket it loses.
static void test_eight_in_the_called_pocket_wins(void **state) {
	(void)state;
	fix_shot s;
	straight_pot(&s, 8);
	const int32_t rest[] = {12, 14};
	park(&s, rest, 2);
	shoot_straight(&s, 8, 1.5, -0.3);
	pool_pocket where;
	assert_true(fix_pocketed(&s, 8, &where));
	assert_int_equal(where, POOL_POCKET_NE);
	assert_false(fix_pocketed(&s, 0, NULL));
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	st.group = POOL_GROUP_SOLIDS; // no solid left on the table
	st.called_ball = 8;
	st.called_pocket = POOL_POCKET_NE;
	pool_game_result r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_WIN);
	assert_int_equal(r.reason, POOL_REASON_EIGHT_POCKETED);
	st.called_pocket = POOL_POCKET_NW;
	r = fix_judge(&s, &st);
	assert_int_equal(r.outcome, POOL_OUTCOME_LOSS);
	assert_int_equal(r.reason, POOL_REASON_EIGHT_WRONG_POCKET);
	fix_end(&s);
}

// 3.8 (a): the 8 pocketed on a foul (the cue ball follows it in) loses the rack.
static void test_eight_with_a_scratch_loses(void **state) {
	(void)state;
	fix_shot s;
	pool_sim_def def = fix_pool_def();
	fix_begin(&s, &def);
	const pool_vec3 pocket = fix_pocket(&def, POOL_POCKET_NE);
	const pool_vec3 cue = {1.7, 0.7, 0};
	const pool_vec3 eight = fix_toward(pocket, cue, 0.25);
	fix_ball(&s, 0, cue.x, cue.y);
	fix_ball(&s, 8, eight.x, eight.y);
	const int32_t rest[] = {12};
	park(&s, rest, 1);
	fix_run(&s, 0, 2.5, eight, 0.5 * def.params.ball_radius);
	assert_true(fix_pocketed(&s, 8, NULL));
	assert_true(fix_pocketed(&s, 0, NULL));
	pool_game_state st = fix_state(POOL_GAME_8BALL);
	st.group = POOL_GROUP_SOLIDS;
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_SCRATCH);
	assert_int_equal(r.outcome, POOL_OUTCOME_LOSS);
	assert_int_equal(r.reason, POOL_REASON_EIGHT_ON_FOUL);
	fix_end(&s);
}

// 3.3 (d): a break that pockets nothing and drives fewer than four object balls to rails is
// illegal: the incoming player accepts the table (no ball in hand) or asks for a re-rack.
static void test_illegal_break(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	s.n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 0.0, s.balls, POOL_GAME_MAX_BALLS);
	fix_run(&s, 0, 1.5, s.balls[1].pos, 0.0);
	int railed = 0;
	for (int32_t id = 1; id <= 15; ++id)
		railed += recount_railed(s.sim, id);
	int32_t ids[16];
	assert_true(railed < 4);
	assert_int_equal(recount_gone(s.sim, POOL_EVENT_POCKET, ids, NULL, 16), 0);
	const pool_game_state st = pool_game_default_state(POOL_GAME_8BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_ILLEGAL_BREAK);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_false(r.ball_in_hand);
	assert_true(r.rerack_option);
	assert_int_equal(r.next.group, POOL_GROUP_OPEN);
	fix_end(&s);
}

// 3.3 (e) and 3.7: the 8 pocketed on a legal break is no foul: it is spotted and the breaker
// continues (or asks for a re-break).
static void test_eight_on_the_break_is_spotted(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	const pool_vec3 pocket = fix_pocket(&def, POOL_POCKET_NE);
	const pool_vec3 cue = {0.6, 0.45, 0};
	const pool_vec3 eight = fix_toward(cue, pocket, 0.1);
	fix_ball(&s, 0, cue.x, cue.y);
	fix_ball(&s, 8, eight.x, eight.y);
	const int32_t rest[] = {1, 9};
	for (int i = 0; i < 2; ++i)
		fix_ball(&s, rest[i], 1.9 + 0.1 * i, 0.2);
	fix_run(&s, 0, 4.0, eight, 0.0);
	assert_true(fix_pocketed(&s, 8, NULL));
	assert_false(fix_pocketed(&s, 0, NULL));
	const pool_game_state st = pool_game_default_state(POOL_GAME_8BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_CONTINUE);
	assert_int_equal(r.reason, POOL_REASON_EIGHT_ON_BREAK);
	assert_true(r.rerack_option);
	assert_int_equal(r.spot_count, 1);
	assert_int_equal(r.spot[0], 8);
	assert_int_equal(r.next.group, POOL_GROUP_OPEN);
	fix_end(&s);
}

// 3.3: a scratch on the break is a foul; balls pocketed stay down, the table stays open, and the
// incoming player has the cue ball in hand behind the head string.
static void test_scratch_on_the_break(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	const pool_vec3 pocket = fix_pocket(&def, POOL_POCKET_NE);
	const pool_vec3 cue = {0.6, 0.45, 0};
	const pool_vec3 one = fix_toward(pocket, cue, 0.25);
	fix_ball(&s, 0, cue.x, cue.y);
	fix_ball(&s, 1, one.x, one.y);
	fix_ball(&s, 8, 0.5, 1.1);
	fix_run(&s, 0, 3.5, one, 0.5 * def.params.ball_radius);
	assert_true(fix_pocketed(&s, 1, NULL));
	assert_true(fix_pocketed(&s, 0, NULL));
	const pool_game_state st = pool_game_default_state(POOL_GAME_8BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_SCRATCH);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_true(r.ball_in_hand);
	assert_true(r.behind_head_string);
	assert_true(r.next.ball_in_hand && r.next.behind_head_string);
	assert_int_equal(r.next.group, POOL_GROUP_OPEN);
	// 6.10: the incoming player then places the cue ball in front of the head string: a foul.
	fix_shot t;
	fix_begin(&t, &def);
	fix_ball(&t, 0, 1.0, 0.635);
	fix_ball(&t, 3, 1.5, 0.635);
	fix_ball(&t, 8, 2.2, 0.3);
	fix_run(&t, 0, 2.0, t.balls[1].pos, 0.0);
	const pool_game_result u = fix_judge(&t, &r.next);
	assert_true(u.fouls & POOL_FOUL_BAD_PLACEMENT);
	fix_end(&t);
	fix_end(&s);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_open_table_eight_first),
		cmocka_unit_test(test_called_ball_chooses_the_group),
		cmocka_unit_test(test_uncalled_shot_chooses_the_group),
		cmocka_unit_test(test_wrong_group_first),
		cmocka_unit_test(test_eight_early_loses),
		cmocka_unit_test(test_eight_in_the_called_pocket_wins),
		cmocka_unit_test(test_eight_with_a_scratch_loses),
		cmocka_unit_test(test_illegal_break),
		cmocka_unit_test(test_eight_on_the_break_is_spotted),
		cmocka_unit_test(test_scratch_on_the_break),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
