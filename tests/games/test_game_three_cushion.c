// Three cushion (UMB World Rules of Carom Billiard, docs/games.md) on a carom table: the shots of
// a scan of aims and speeds from the starting position, each classified by the independent
// recount (recount.h) and judged. Every class of art. 83 must appear: a point (three cushions
// before the second ball), a near miss with two, a point whose first cushion comes before the
// first ball, a kiss (the cue ball meets the second ball before its third cushion).
#include "game_fixture.h"

typedef struct scan_counts {
	int shots, points, near_misses, cushion_first_points, kisses, wrong_first_on_break;
} scan_counts;

static void judge_scan_shot(const fix_shot *s, scan_counts *c) {
	int cushions = 0, first_at = -1;
	const int32_t first = recount_first_hit(s->sim, &first_at);
	const int32_t second = recount_second_hit(s->sim, &cushions);
	// The cue ball's cushions before its first contact, and every meeting with the second ball.
	int n = 0, before_first = 0, cue_cushions = 0, meetings_before_third = 0;
	const pool_event *ev = pool_sim_events(s->sim, &n);
	const double radius = s->def.params.ball_radius;
	for (int k = 1; k < n; ++k) {
		if (ev[k].type == POOL_EVENT_BALL_CUSHION && pool_sim_event_states(s->sim, &ev[k])[0].id == 0) {
			cue_cushions++;
			before_first += first_at < 0 || k < first_at;
		}
		int32_t met[4];
		const int m = recount_touches(s->sim, &ev[k], 0, radius, met, 4);
		for (int j = 0; j < m; ++j)
			meetings_before_third += second != RECOUNT_NONE && met[j] == second && cue_cushions < 3;
	}
	const bool point = first != RECOUNT_NONE && second != RECOUNT_NONE && cushions >= 3;
	pool_game_state st = fix_state(POOL_GAME_THREE_CUSHION);
	st.points = 7;
	const pool_game_result r = fix_judge(s, &st);
	c->shots++;
	assert_true(r.legal); // nothing leaves a table without pockets in planar mode
	assert_int_equal(r.first_hit, first);
	assert_int_equal(r.points, point ? 1 : 0);
	assert_int_equal(r.outcome, point ? POOL_OUTCOME_CONTINUE : POOL_OUTCOME_TURN_OVER);
	if (point) {
		assert_int_equal(r.cue_cushions, cushions);
		assert_int_equal(r.next.points, 8);
		assert_int_equal(r.next.cue_ball, 0);
	} else {
		// The opponent plays their own ball (1) against 0 and 2, with their score.
		assert_int_equal(r.next.cue_ball, 1);
		assert_int_equal(r.next.opponent_cue_ball, 0);
		assert_int_equal(r.next.opponent_points, 7);
		assert_int_equal(r.next.player, 1);
	}
	c->points += point;
	c->near_misses += second != RECOUNT_NONE && cushions == 2;
	c->cushion_first_points += point && before_first > 0;
	c->kisses += second != RECOUNT_NONE && cushions < 3 && meetings_before_third > 0 && cue_cushions >= 3;
	// Art. 23: on the opening shot the cue ball must meet the red (2) first.
	pool_game_state brk = pool_game_default_state(POOL_GAME_THREE_CUSHION);
	const pool_game_result b = fix_judge(s, &brk);
	if (first == 1) {
		assert_int_equal(b.fouls, POOL_FOUL_WRONG_BALL_FIRST);
		assert_int_equal(b.points, 0);
		assert_int_equal(b.outcome, POOL_OUTCOME_TURN_OVER);
		c->wrong_first_on_break++;
	} else {
		assert_int_equal(b.fouls, 0);
		assert_int_equal(b.points, point ? 1 : 0);
	}
}

static void test_scan_of_shots(void **state) {
	(void)state;
	const pool_sim_def def = fix_carom_def();
	pool_ball_state start[3];
	assert_int_equal(pool_game_rack(POOL_GAME_THREE_CUSHION, &def.table, &def.params, 0.0, start, 3), 3);
	scan_counts c = {0};
	const double speeds[] = {3.0, 5.0};
	for (int v = 0; v < 2; ++v)
		for (int k = 0; k < 360; ++k) {
			fix_shot s;
			fix_begin(&s, &def);
			for (int i = 0; i < 3; ++i)
				fix_ball(&s, start[i].id, start[i].pos.x, start[i].pos.y);
			const double phi = k * FIX_DEG;
			const pool_vec3 to = {start[0].pos.x + cos(phi), start[0].pos.y + sin(phi), 0};
			fix_run(&s, 0, speeds[v], to, 0.3 * def.params.ball_radius);
			judge_scan_shot(&s, &c);
			fix_end(&s);
		}
	print_message("three cushion scan: %d shots, %d points (%d with a cushion before the first ball), "
	              "%d near misses with two cushions, %d kisses before the third cushion, %d hitting the "
	              "opponent's ball first\n", c.shots, c.points, c.cushion_first_points, c.near_misses, c.kisses,
	              c.wrong_first_on_break);
	assert_true(c.points > 0);
	assert_true(c.near_misses > 0);
	assert_true(c.cushion_first_points > 0);
	assert_true(c.kisses > 0);
	assert_true(c.wrong_first_on_break > 0);
}

// Art. 41: the shooter must strike their own ball; and a point that reaches the target score
// wins (the match's length, docs/games.md).
static void test_wrong_ball_and_target(void **state) {
	(void)state;
	const pool_sim_def def = fix_carom_def();
	pool_ball_state start[3];
	pool_game_rack(POOL_GAME_THREE_CUSHION, &def.table, &def.params, 0.0, start, 3);
	fix_shot s;
	fix_begin(&s, &def);
	for (int i = 0; i < 3; ++i)
		fix_ball(&s, start[i].id, start[i].pos.x, start[i].pos.y);
	fix_run(&s, 1, 2.0, start[2].pos, 0.0);
	pool_game_state st = fix_state(POOL_GAME_THREE_CUSHION);
	pool_game_result r = fix_judge(&s, &st);
	assert_true(r.fouls & POOL_FOUL_WRONG_CUE_BALL);
	assert_int_equal(r.points, 0);
	fix_end(&s);
	// A point found by the scan's first speed, at the target.
	for (int k = 0; k < 360; ++k) {
		fix_begin(&s, &def);
		for (int i = 0; i < 3; ++i)
			fix_ball(&s, start[i].id, start[i].pos.x, start[i].pos.y);
		const double phi = k * FIX_DEG;
		fix_run(&s, 0, 3.0, (pool_vec3){start[0].pos.x + cos(phi), start[0].pos.y + sin(phi), 0},
		        0.3 * def.params.ball_radius);
		st = fix_state(POOL_GAME_THREE_CUSHION);
		st.points = 14;
		st.target_points = 15;
		r = fix_judge(&s, &st);
		fix_end(&s);
		if (r.points == 1) {
			assert_int_equal(r.outcome, POOL_OUTCOME_WIN);
			assert_int_equal(r.reason, POOL_REASON_TARGET_REACHED);
			assert_int_equal(r.next.points, 15);
			return;
		}
	}
	fail_msg("no point in the scan");
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_scan_of_shots),
		cmocka_unit_test(test_wrong_ball_and_target),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
