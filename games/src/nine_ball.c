// Nine ball, WPA World Standardized Rules section 2 (docs/games.md names each paragraph): the
// lowest-numbered ball first (section 2's preamble, 6.2), the legal break (2.3), the push out
// (2.4), continuing play and the 9 (2.5), spotting the 9 (2.6), the standard fouls (2.7, 6.x) and
// three consecutive fouls (2.8, 6.14).
#include <stdbool.h>

#include "rules.h"

#define NINE 9

static int32_t lowest_object_ball(const pool_game_state *state, const pool_game_shot *shot) {
	int32_t lowest = POOL_GAME_NO_BALL;
	for (int i = 0; i < shot->ball_count; ++i) {
		const int32_t id = shot->balls[i].id;
		if (id != state->cue_ball && (lowest == POOL_GAME_NO_BALL || id < lowest))
			lowest = id;
	}
	return lowest;
}

pool_result pool_game_judge_9ball(const pool_game_state *state, const pool_game_shot *shot,
                                  const pool_game_facts *f, const pool_table_def *table,
                                  pool_game_result *r, pool_error *error) {
	(void)error;
	const int32_t cue = state->cue_ball;
	const bool push_out = state->push_out; // validated: only where push_out_available
	uint32_t fouls = 0;
	if (f->struck != cue)
		fouls |= POOL_FOUL_WRONG_CUE_BALL; // 6.6
	if (state->ball_in_hand && state->behind_head_string && !pool_game_behind_head_string(table, f->struck_pos))
		fouls |= POOL_FOUL_BAD_PLACEMENT; // 2.3 (a), 6.10
	if (pool_game_facts_pocketed(f, cue) || pool_game_facts_off_table(f, cue))
		fouls |= POOL_FOUL_SCRATCH; // 6.1
	for (int i = 0; i < f->off_table_count; ++i)
		if (f->off_table[i] != cue)
			fouls |= POOL_FOUL_BALL_OFF_TABLE; // 6.5
	int pocketed = 0;
	for (int i = 0; i < f->pocketed_count; ++i)
		pocketed += f->pocketed[i] != cue;
	// 6.2 and 6.3 are suspended on a push out (2.4).
	if (!push_out) {
		if (f->first_hit == POOL_GAME_NO_BALL)
			fouls |= POOL_FOUL_NO_CONTACT;
		else if (f->first_hit != lowest_object_ball(state, shot))
			fouls |= POOL_FOUL_WRONG_BALL_FIRST;
		if (state->break_shot) {
			// 2.3 (b): a ball pocketed or four object balls driven to one or more rails.
			int railed = 0;
			for (int i = 0; i < shot->ball_count; ++i)
				railed += shot->balls[i].id != cue && (f->railed >> i & 1u);
			if (pocketed == 0 && railed < 4)
				fouls |= POOL_FOUL_ILLEGAL_BREAK;
		} else if (f->first_hit != POOL_GAME_NO_BALL && pocketed == 0 && f->rails_after_contact == 0) {
			fouls |= POOL_FOUL_NO_RAIL;
		}
	}
	r->fouls = fouls;
	const bool nine_pocketed = pool_game_facts_pocketed(f, NINE);
	pool_game_state s = *state;
	if (nine_pocketed && !fouls && !push_out) { // 2.5: the 9 on a legal shot, the break included
		r->reason = POOL_REASON_NINE_POCKETED;
		pool_game_finish(&s, POOL_OUTCOME_WIN, r);
		return POOL_OK;
	}
	if (nine_pocketed || pool_game_facts_off_table(f, NINE))
		r->spot[r->spot_count++] = NINE; // 2.6: pocketed on a foul or a push out, or off the table
	if (fouls) {
		if (state->fouls + 1 >= 3) { // 6.14 and 2.8: the third consecutive foul loses the rack
			r->reason = POOL_REASON_THREE_FOULS;
			pool_game_finish(&s, POOL_OUTCOME_LOSS, r);
			return POOL_OK;
		}
		r->ball_in_hand = true; // 2.7: cue ball in hand anywhere on the table
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
		return POOL_OK;
	}
	if (push_out) { // 2.4: the incoming player plays from there or passes the shot back
		r->reason = POOL_REASON_PUSH_OUT;
		r->pass_option = true;
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
		return POOL_OK;
	}
	if (state->safety) { // 1.6
		r->reason = POOL_REASON_SAFETY;
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
		return POOL_OK;
	}
	pool_game_finish(&s, pocketed > 0 ? POOL_OUTCOME_CONTINUE : POOL_OUTCOME_TURN_OVER, r); // 2.5
	// 2.4: after a break without a foul, the player at the table may push out.
	r->next.push_out_available = state->break_shot;
	return POOL_OK;
}
