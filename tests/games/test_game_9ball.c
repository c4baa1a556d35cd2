// Nine ball, one scenario per rule (WPA World Standardized Rules, docs/games.md): each shot is
// built so its events decide the rule, the events are checked by the independent recount
// (recount.h), then the judge's verdict is checked against the rule.
#include "game_fixture.h"

// A straight line to the north-east corner pocket: the object ball 0.25 m from the corner point,
// a second ball (combination) just behind it, the cue ball behind that.
typedef struct line_shot {
	fix_shot s;
	pool_vec3 pocket, first, second, cue;
} line_shot;

static void line_setup(line_shot *l, pool_vec3 cue, double first_to_pocket, double gap) {
	pool_sim_def def = fix_pool_def();
	fix_begin(&l->s, &def);
	const double R = def.params.ball_radius;
	l->pocket = fix_pocket(&def, POOL_POCKET_NE);
	l->cue = cue;
	l->second = fix_toward(l->pocket, cue, first_to_pocket);
	l->first = fix_toward(l->second, cue, 2.0 * R + gap);
}

// 2.5 (and the preamble of section 2): the 9 pocketed on a legal shot wins the rack, by a
// combination too (the 1 first, it sends the 9 in).
static void test_nine_by_combination_wins(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){0.9, 0.35, 0.0}, 0.25, 0.005);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 1, l.first.x, l.first.y);
	fix_ball(&l.s, 9, l.second.x, l.second.y);
	fix_ball(&l.s, 5, 0.3, 1.0);
	fix_run(&l.s, 0, 2.0, l.first, -0.4 * l.s.def.params.ball_radius);
	assert_int_equal(recount_first_hit(l.s.sim, NULL), 1);
	pool_pocket where;
	assert_true(fix_pocketed(&l.s, 9, &where));
	assert_false(fix_pocketed(&l.s, 0, NULL));
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_WIN);
	assert_int_equal(r.reason, POOL_REASON_NINE_POCKETED);
	assert_int_equal(r.first_hit, 1);
	fix_end(&l.s);
}

// Section 2's preamble and 6.2: the first ball the cue ball touches must be the lowest on the
// table. Hitting the 3 with the 1 on the table is a foul, even though the 3 drops (it stays down:
// only the 9 is spotted, 2.6); the opponent has the cue ball in hand anywhere (2.7).
static void test_wrong_ball_first(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){2.1, 0.95, 0.0}, 0.3, 0.0);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 3, l.second.x, l.second.y);
	fix_ball(&l.s, 1, 0.3, 0.3);
	fix_run(&l.s, 0, 1.5, l.second, -0.3 * l.s.def.params.ball_radius);
	assert_int_equal(recount_first_hit(l.s.sim, NULL), 3);
	assert_true(fix_pocketed(&l.s, 3, NULL));
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_false(r.legal);
	assert_int_equal(r.fouls, POOL_FOUL_WRONG_BALL_FIRST);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_true(r.ball_in_hand);
	assert_false(r.behind_head_string);
	assert_int_equal(r.spot_count, 0);
	assert_int_equal(r.next.player, 1);
	assert_int_equal(r.next.opponent_fouls, 1);
	fix_end(&l.s);
}

// 2.6: the 9 pocketed on a foul is spotted. The cue ball hits the 9 first with the 1 on the
// table: the 9 drops, is returned, and the opponent has ball in hand.
static void test_nine_on_a_foul_is_spotted(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){2.1, 0.95, 0.0}, 0.3, 0.0);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 9, l.second.x, l.second.y);
	fix_ball(&l.s, 1, 0.3, 0.3);
	fix_run(&l.s, 0, 1.5, l.second, -0.3 * l.s.def.params.ball_radius);
	assert_int_equal(recount_first_hit(l.s.sim, NULL), 9);
	assert_true(fix_pocketed(&l.s, 9, NULL));
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_WRONG_BALL_FIRST);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_int_equal(r.spot_count, 1);
	assert_int_equal(r.spot[0], 9);
	// The spot: the foot spot is free, so the 9 goes there (1.4).
	pool_vec3 at;
	pool_ball_state left[1] = {l.s.balls[2]};
	assert_int_equal(pool_game_spot_position(&st, 9, &l.s.def.table, l.s.def.params.ball_radius, left, 1, &at),
	                 POOL_OK);
	assert_true(at.x == 0.75 * l.s.def.table.length);
	assert_true(at.y == 0.5 * l.s.def.table.width);
	fix_end(&l.s);
}

// 6.1: the cue ball pocketed is a foul. A follow shot pots the 1 and the cue ball follows it in:
// the 1 does not count, the turn passes with ball in hand.
static void test_scratch(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){1.7, 0.7, 0.0}, 0.25, 0.0);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 1, l.second.x, l.second.y);
	fix_ball(&l.s, 9, 0.4, 0.3);
	fix_run(&l.s, 0, 2.5, l.second, 0.5 * l.s.def.params.ball_radius);
	assert_int_equal(recount_first_hit(l.s.sim, NULL), 1);
	assert_true(fix_pocketed(&l.s, 1, NULL));
	assert_true(fix_pocketed(&l.s, 0, NULL));
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_SCRATCH);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_true(r.ball_in_hand);
	fix_end(&l.s);
}

// 6.3: with no ball pocketed, some ball must reach a rail after the contact. A soft hit on the 1
// in the middle of the table leaves every ball short of the rails.
static void test_no_rail(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	fix_ball(&s, 0, 1.1, 0.635);
	fix_ball(&s, 1, 1.3, 0.635);
	fix_ball(&s, 9, 2.0, 0.3);
	fix_run(&s, 0, 0.5, s.balls[1].pos, 0.0);
	assert_int_equal(recount_first_hit(s.sim, NULL), 1);
	assert_int_equal(recount_rails_after_contact(s.sim), 0);
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_NO_RAIL);
	assert_int_equal(r.rails_after_contact, 0);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	fix_end(&s);
}

// A legal shot that pockets nothing: the 1 driven to a rail, the turn passes without a foul (2.5).
static void test_legal_miss_passes_the_turn(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	fix_ball(&s, 0, 1.1, 0.635);
	fix_ball(&s, 1, 1.3, 0.635);
	fix_ball(&s, 9, 2.0, 0.3);
	fix_run(&s, 0, 2.0, (pool_vec3){1.3, 0.655, 0.0}, 0.0);
	assert_int_equal(recount_first_hit(s.sim, NULL), 1);
	assert_true(recount_rails_after_contact(s.sim) > 0);
	int32_t ids[16];
	assert_int_equal(recount_gone(s.sim, POOL_EVENT_POCKET, ids, NULL, 16), 0);
	pool_game_state st = fix_state(POOL_GAME_9BALL);
	st.fouls = 2; // a legal shot clears the shooter's fouls (6.14: "without an intervening legal shot")
	const pool_game_result r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_false(r.ball_in_hand);
	assert_int_equal(r.next.opponent_fouls, 0);
	fix_end(&s);
}

// 2.5: a ball legally pocketed keeps the shooter at the table.
static void test_legal_pot_continues(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){2.1, 0.95, 0.0}, 0.3, 0.0);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 2, l.second.x, l.second.y);
	fix_ball(&l.s, 9, 0.3, 0.3);
	fix_run(&l.s, 0, 1.5, l.second, -0.3 * l.s.def.params.ball_radius);
	assert_true(fix_pocketed(&l.s, 2, NULL));
	assert_false(fix_pocketed(&l.s, 0, NULL));
	pool_game_state st = fix_state(POOL_GAME_9BALL);
	st.fouls = 1;
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_CONTINUE);
	assert_int_equal(r.next.player, 0);
	assert_int_equal(r.next.fouls, 0);
	fix_end(&l.s);
}

// 6.2: the cue ball touching no ball is a foul; with two fouls already it is the third
// consecutive one, and the shooter loses the rack (6.14, 2.8).
static void test_no_contact_and_three_fouls(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	fix_ball(&s, 0, 1.0, 0.635);
	fix_ball(&s, 1, 2.0, 0.4);
	fix_ball(&s, 9, 2.1, 0.9);
	fix_run(&s, 0, 0.6, (pool_vec3){0.0, 0.635, 0.0}, 0.0);
	assert_int_equal(recount_first_hit(s.sim, NULL), RECOUNT_NONE);
	pool_game_state st = fix_state(POOL_GAME_9BALL);
	pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_NO_CONTACT);
	assert_int_equal(r.first_hit, POOL_GAME_NO_BALL);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	st.fouls = 2;
	r = fix_judge(&s, &st);
	assert_int_equal(r.outcome, POOL_OUTCOME_LOSS);
	assert_int_equal(r.reason, POOL_REASON_THREE_FOULS);
	// In 8-ball a third foul is a foul like another (WPA 3.9 does not list 6.14).
	pool_game_state eight = fix_state(POOL_GAME_8BALL);
	eight.fouls = 2;
	r = fix_judge(&s, &eight);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	fix_end(&s);
}

// 2.4: on a push out, 6.2 and 6.3 are suspended: the cue ball may hit the 3 first; the incoming
// player may play or pass the shot back; a 9 pocketed on a push out is spotted.
static void test_push_out(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){2.1, 0.95, 0.0}, 0.3, 0.0);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 9, l.second.x, l.second.y);
	fix_ball(&l.s, 1, 0.3, 0.3);
	fix_run(&l.s, 0, 1.5, l.second, -0.3 * l.s.def.params.ball_radius);
	assert_int_equal(recount_first_hit(l.s.sim, NULL), 9);
	assert_true(fix_pocketed(&l.s, 9, NULL));
	pool_game_state st = fix_state(POOL_GAME_9BALL);
	st.push_out_available = true;
	st.push_out = true;
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_int_equal(r.reason, POOL_REASON_PUSH_OUT);
	assert_true(r.pass_option);
	assert_false(r.ball_in_hand);
	assert_int_equal(r.spot_count, 1);
	assert_int_equal(r.spot[0], 9);
	assert_false(r.next.push_out_available);
	fix_end(&l.s);
}

// 2.3: the break from behind the head string must pocket a ball or drive four object balls to
// rails; the 1 first (6.2). A soft break of the frozen diamond does neither: a foul, ball in hand.
static void test_illegal_break(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	s.n = pool_rack(POOL_RACK_9BALL, &def.table, &def.params, 0.0, s.balls, POOL_GAME_MAX_BALLS);
	fix_run(&s, 0, 1.2, s.balls[1].pos, 0.0);
	assert_int_equal(recount_first_hit(s.sim, NULL), 1);
	int railed = 0;
	for (int32_t id = 1; id <= 9; ++id)
		railed += recount_railed(s.sim, id);
	int32_t ids[16];
	assert_true(railed < 4);
	assert_int_equal(recount_gone(s.sim, POOL_EVENT_POCKET, ids, NULL, 16), 0);
	const pool_game_state st = pool_game_default_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_int_equal(r.fouls, POOL_FOUL_ILLEGAL_BREAK);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	assert_true(r.ball_in_hand);
	assert_false(r.next.push_out_available);
	fix_end(&s);
}

// 2.3 and 2.4: a hard break that meets the requirements is legal, and the player at the table
// after it may push out.
static void test_legal_break_allows_push_out(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	s.n = pool_rack(POOL_RACK_9BALL, &def.table, &def.params, 0.0, s.balls, POOL_GAME_MAX_BALLS);
	fix_run(&s, 0, 8.0, s.balls[1].pos, 0.0);
	int railed = 0;
	for (int32_t id = 1; id <= 9; ++id)
		railed += recount_railed(s.sim, id);
	assert_true(railed >= 4);
	assert_false(fix_pocketed(&s, 0, NULL));
	assert_false(fix_pocketed(&s, 9, NULL));
	const pool_game_state st = pool_game_default_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_true(r.legal);
	assert_true(r.next.push_out_available);
	assert_false(r.next.break_shot);
	fix_end(&s);
}

// 2.5 with 2.3: the 9 pocketed on the break wins (the 1 first, from behind the head string).
static void test_nine_on_the_break_wins(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){0.6, 0.45, 0.0}, 0.3, 0.0);
	l.first = fix_toward(l.cue, l.pocket, 0.1); // the 1 close to the cue ball, the 9 far on
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 1, l.first.x, l.first.y);
	fix_ball(&l.s, 9, l.second.x, l.second.y);
	fix_run(&l.s, 0, 4.0, l.first, 0.0);
	assert_int_equal(recount_first_hit(l.s.sim, NULL), 1);
	assert_true(fix_pocketed(&l.s, 9, NULL));
	assert_false(fix_pocketed(&l.s, 0, NULL));
	const pool_game_state st = pool_game_default_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_true(r.legal);
	assert_int_equal(r.outcome, POOL_OUTCOME_WIN);
	assert_int_equal(r.reason, POOL_REASON_NINE_POCKETED);
	fix_end(&l.s);
}

// 6.10 with 2.3 (a): the breaker's cue ball in hand must be behind the head string.
static void test_break_from_in_front_of_the_head_string(void **state) {
	(void)state;
	line_shot l;
	line_setup(&l, (pool_vec3){0.9, 0.45, 0.0}, 0.3, 0.0);
	l.first = fix_toward(l.cue, l.pocket, 0.1);
	fix_ball(&l.s, 0, l.cue.x, l.cue.y);
	fix_ball(&l.s, 1, l.first.x, l.first.y);
	fix_ball(&l.s, 9, l.second.x, l.second.y);
	fix_run(&l.s, 0, 4.0, l.first, 0.0);
	assert_true(l.cue.x > 0.25 * l.s.def.table.length);
	const pool_game_state st = pool_game_default_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&l.s, &st);
	assert_true(r.fouls & POOL_FOUL_BAD_PLACEMENT);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER); // not a win: the 9 is spotted (2.6)
	assert_int_equal(r.spot_count, 1);
	fix_end(&l.s);
}

// 6.6: striking a ball other than the cue ball is a foul.
static void test_wrong_cue_ball(void **state) {
	(void)state;
	pool_sim_def def = fix_pool_def();
	fix_shot s;
	fix_begin(&s, &def);
	fix_ball(&s, 0, 0.6, 0.3);
	fix_ball(&s, 1, 1.3, 0.635);
	fix_ball(&s, 2, 1.5, 0.635);
	fix_run(&s, 1, 1.0, s.balls[2].pos, 0.0);
	const pool_game_state st = fix_state(POOL_GAME_9BALL);
	const pool_game_result r = fix_judge(&s, &st);
	assert_true(r.fouls & POOL_FOUL_WRONG_CUE_BALL);
	assert_int_equal(r.outcome, POOL_OUTCOME_TURN_OVER);
	fix_end(&s);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_nine_by_combination_wins),
		cmocka_unit_test(test_wrong_ball_first),
		cmocka_unit_test(test_nine_on_a_foul_is_spotted),
		cmocka_unit_test(test_scratch),
		cmocka_unit_test(test_no_rail),
		cmocka_unit_test(test_legal_miss_passes_the_turn),
		cmocka_unit_test(test_legal_pot_continues),
		cmocka_unit_test(test_no_contact_and_three_fouls),
		cmocka_unit_test(test_push_out),
		cmocka_unit_test(test_illegal_break),
		cmocka_unit_test(test_legal_break_allows_push_out),
		cmocka_unit_test(test_nine_on_the_break_wins),
		cmocka_unit_test(test_break_from_in_front_of_the_head_string),
		cmocka_unit_test(test_wrong_cue_ball),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
