// Three cushion, UMB World Rules of Carom Billiard (docs/games.md names each article): the
// carom with three cushions before the second object ball (art. 83), the red first on the
// opening shot (art. 23), balls leaving the table (art. 28) and the fouls the events show (art. 41).
#include <stdbool.h>

#include "rules.h"

pool_result pool_game_judge_three_cushion(const pool_game_state *state, const pool_game_shot *shot,
                                          const pool_game_facts *f, const pool_table_def *table,
                                          pool_game_result *r, pool_error *error) {
	(void)table;
	(void)error;
	int32_t red = POOL_GAME_NO_BALL; // the ball that is neither player's
	for (int i = 0; i < shot->ball_count; ++i)
		if (shot->balls[i].id != state->cue_ball && shot->balls[i].id != state->opponent_cue_ball)
			red = shot->balls[i].id;
	uint32_t fouls = 0;
	if (f->struck != state->cue_ball)
		fouls |= POOL_FOUL_WRONG_CUE_BALL; // art. 41: playing the wrong ball
	// Art. 28: a ball leaving the table is a foul. This table may still have pocket mouths (until
	// the carom table without pockets is used): a ball pocketed has left it too.
	if (f->off_table_count > 0 || f->pocketed_count > 0)
		fouls |= POOL_FOUL_BALL_OFF_TABLE;
	if (state->break_shot && f->first_hit != POOL_GAME_NO_BALL && f->first_hit != red)
		fouls |= POOL_FOUL_WRONG_BALL_FIRST; // art. 23: the opening shot hits the red first
	r->fouls = fouls;
	for (int i = 0; i < f->off_table_count && r->spot_count < POOL_GAME_MAX_BALLS; ++i)
		r->spot[r->spot_count++] = f->off_table[i];
	for (int i = 0; i < f->pocketed_count && r->spot_count < POOL_GAME_MAX_BALLS; ++i)
		r->spot[r->spot_count++] = f->pocketed[i];
	// Art. 83: both object balls, and at least three cushion contacts (the same cushion counts
	// each time, before the first ball too) before the second.
	const bool carom = f->first_hit != POOL_GAME_NO_BALL && f->second_hit != POOL_GAME_NO_BALL &&
	                   f->cue_cushions_before_second >= 3;
	r->points = carom && !fouls ? 1 : 0;
	pool_game_state s = *state;
	if (r->points && state->target_points > 0 && state->points + 1 >= state->target_points) {
		r->reason = POOL_REASON_TARGET_REACHED;
		pool_game_finish(&s, POOL_OUTCOME_WIN, r);
		return POOL_OK;
	}
	pool_game_finish(&s, r->points ? POOL_OUTCOME_CONTINUE : POOL_OUTCOME_TURN_OVER, r);
	return POOL_OK;
}
