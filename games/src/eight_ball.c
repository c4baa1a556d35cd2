// Eight ball, WPA World Standardized Rules section 3 (docs/games.md names each paragraph): the
// break (3.3), the open table and the groups (3.4), continuing play (3.5), called shots (3.6),
// the 8-ball spotted on the break (3.7), losing the rack (3.8) and the standard fouls (3.9, 6.x).
#include <stdbool.h>

#include "rules.h"

#define EIGHT 8

static pool_game_group group_of(int32_t id) {
	if (id >= 1 && id <= 7)
		return POOL_GROUP_SOLIDS;
	if (id >= 9 && id <= 15)
		return POOL_GROUP_STRIPES;
	return POOL_GROUP_OPEN;
}

/// The shooter's group is cleared: none of its balls was on the table when the shot began.
static bool group_cleared(const pool_game_shot *shot, pool_game_group group) {
	if (group == POOL_GROUP_OPEN)
		return false;
	for (int i = 0; i < shot->ball_count; ++i)
		if (group_of(shot->balls[i].id) == group)
			return false;
	return true;
}

/// Fouls every shot can commit: another ball struck (6.6), the cue ball placed in front of the
/// head string (6.10), the cue ball pocketed or off the table (6.1), an object ball off the table (6.5).
static uint32_t common_fouls(const pool_game_state *state, const pool_game_facts *f, const pool_table_def *table,
                             bool behind_head_string) {
	uint32_t fouls = 0;
	if (f->struck != state->cue_ball)
		fouls |= POOL_FOUL_WRONG_CUE_BALL;
	if (behind_head_string && !pool_game_behind_head_string(table, f->struck_pos))
		fouls |= POOL_FOUL_BAD_PLACEMENT;
	if (pool_game_facts_pocketed(f, state->cue_ball) || pool_game_facts_off_table(f, state->cue_ball))
		fouls |= POOL_FOUL_SCRATCH;
	for (int i = 0; i < f->off_table_count; ++i)
		if (f->off_table[i] != state->cue_ball)
			fouls |= POOL_FOUL_BALL_OFF_TABLE;
	return fouls;
}

static int object_balls_pocketed(const pool_game_state *state, const pool_game_facts *f) {
	int n = 0;
	for (int i = 0; i < f->pocketed_count; ++i)
		n += f->pocketed[i] != state->cue_ball;
	return n;
}

static pool_result judge_break(const pool_game_state *state, const pool_game_shot *shot, const pool_game_facts *f,
                               const pool_table_def *table, pool_game_result *r) {
	// 3.3 (a): from behind the head string; (b): no ball called, no ball required first.
	r->fouls = common_fouls(state, f, table, true);
	const int pocketed = object_balls_pocketed(state, f);
	int railed = 0;
	for (int i = 0; i < shot->ball_count; ++i)
		railed += shot->balls[i].id != state->cue_ball && (f->railed >> i & 1u);
	// 3.3 (d): a ball pocketed or four object balls driven to one or more rails.
	if (pocketed == 0 && railed < 4)
		r->fouls |= POOL_FOUL_ILLEGAL_BREAK;
	const bool eight_down = pool_game_facts_pocketed(f, EIGHT) || pool_game_facts_off_table(f, EIGHT);
	if (eight_down) { // 3.3 (e), (f), 3.7: the 8 is spotted (or the balls re-racked)
		r->spot[r->spot_count++] = EIGHT;
		r->reason = POOL_REASON_EIGHT_ON_BREAK;
		r->rerack_option = true;
	}
	pool_game_state s = *state;
	s.group = POOL_GROUP_OPEN; // 3.4: the table is open after the break, whatever dropped
	if (r->fouls & ~(uint32_t)POOL_FOUL_ILLEGAL_BREAK) {
		// A scratch or another foul on the break: the incoming player has the cue ball in hand
		// behind the head string (3.3 (f)-(h)).
		r->ball_in_hand = true;
		r->behind_head_string = true;
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
	} else if (r->fouls) {
		// 3.3 (d): the incoming player accepts the table in position (or asks for a re-rack).
		r->rerack_option = true;
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
	} else {
		// 3.3 (c): a ball pocketed without a foul keeps the breaker at the table.
		pool_game_finish(&s, pocketed > 0 ? POOL_OUTCOME_CONTINUE : POOL_OUTCOME_TURN_OVER, r);
	}
	return POOL_OK;
}

/// The ball the shot pockets for the shooter: the called ball in the called pocket, or without a
/// call the first ball of a legal group to drop (any pocket). POOL_GAME_NO_BALL when none.
static int32_t scored_ball(const pool_game_state *state, const pool_game_facts *f, pool_game_group group) {
	for (int i = 0; i < f->pocketed_count; ++i) {
		const int32_t id = f->pocketed[i];
		if (id == state->cue_ball || id == EIGHT)
			continue;
		if (state->called_ball != POOL_GAME_NO_BALL && id != state->called_ball)
			continue;
		if (state->called_pocket != POOL_POCKET_NONE && f->pocketed_in[i] != state->called_pocket)
			continue;
		if (group == POOL_GROUP_OPEN || group_of(id) == group)
			return id;
	}
	return POOL_GAME_NO_BALL;
}

pool_result pool_game_judge_8ball(const pool_game_state *state, const pool_game_shot *shot,
                                  const pool_game_facts *f, const pool_table_def *table,
                                  pool_game_result *r, pool_error *error) {
	(void)error;
	if (state->break_shot)
		return judge_break(state, shot, f, table, r);
	const bool on_eight = group_cleared(shot, state->group);
	r->fouls = common_fouls(state, f, table, state->ball_in_hand && state->behind_head_string);
	// 6.2 and 3.4: the first ball must be one of the shooter's group, the 8 once the group is
	// cleared, any object ball but the 8 on an open table.
	if (f->first_hit == POOL_GAME_NO_BALL) {
		r->fouls |= POOL_FOUL_NO_CONTACT;
	} else {
		const bool legal_first = on_eight ? f->first_hit == EIGHT
		                         : state->group == POOL_GROUP_OPEN
		                             ? f->first_hit != EIGHT && group_of(f->first_hit) != POOL_GROUP_OPEN
		                             : group_of(f->first_hit) == state->group;
		if (!legal_first)
			r->fouls |= POOL_FOUL_WRONG_BALL_FIRST;
		// 6.3: with no object ball pocketed, some ball must reach a rail after the contact.
		if (object_balls_pocketed(state, f) == 0 && f->rails_after_contact == 0)
			r->fouls |= POOL_FOUL_NO_RAIL;
	}
	pool_game_state s = *state;
	// 3.8: the 8 ends the rack, won or lost.
	if (pool_game_facts_off_table(f, EIGHT)) {
		r->reason = POOL_REASON_EIGHT_OFF_TABLE;
		pool_game_finish(&s, POOL_OUTCOME_LOSS, r);
		return POOL_OK;
	}
	for (int i = 0; i < f->pocketed_count; ++i) {
		if (f->pocketed[i] != EIGHT)
			continue;
		if (!on_eight)
			r->reason = POOL_REASON_EIGHT_EARLY; // 3.8 (b), (e)
		else if (r->fouls)
			r->reason = POOL_REASON_EIGHT_ON_FOUL; // 3.8 (a)
		else if (state->called_pocket != POOL_POCKET_NONE && f->pocketed_in[i] != state->called_pocket)
			r->reason = POOL_REASON_EIGHT_WRONG_POCKET; // 3.8 (d)
		else
			r->reason = POOL_REASON_EIGHT_POCKETED; // 3.5: the 8 legally pocketed wins
		pool_game_finish(&s, r->reason == POOL_REASON_EIGHT_POCKETED ? POOL_OUTCOME_WIN : POOL_OUTCOME_LOSS, r);
		return POOL_OK;
	}
	if (r->fouls) { // 3.9: the incoming player has the cue ball in hand anywhere
		r->ball_in_hand = true;
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
		return POOL_OK;
	}
	if (state->safety) { // 1.6: a declared safety passes the turn; what dropped stays down
		r->reason = POOL_REASON_SAFETY;
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
		return POOL_OK;
	}
	const int32_t scored = on_eight ? POOL_GAME_NO_BALL : scored_ball(state, f, state->group);
	if (scored == POOL_GAME_NO_BALL) {
		if (object_balls_pocketed(state, f) > 0)
			r->reason = POOL_REASON_NOT_CALLED; // 3.6: balls pocketed, not the called one
		pool_game_finish(&s, POOL_OUTCOME_TURN_OVER, r);
		return POOL_OK;
	}
	if (s.group == POOL_GROUP_OPEN) // 3.4: the called ball legally pocketed chooses the groups
		s.group = group_of(scored);
	pool_game_finish(&s, POOL_OUTCOME_CONTINUE, r); // 3.5
	return POOL_OK;
}
