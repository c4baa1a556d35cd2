// The games' names, states, their validation and the judge's dispatch (pool/game.h).
#include "pool/game.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "rules.h"

static const char *const rules_names[] = {"8ball", "9ball", "three_cushion"};
static const char *const outcome_names[] = {"continue", "turn_over", "win", "loss"};
static const char *const foul_names[POOL_GAME_FOUL_KINDS] = {
	"scratch", "no_contact", "wrong_ball_first", "no_rail",
	"ball_off_table", "illegal_break", "wrong_cue_ball", "bad_placement"};
static const char *const reason_names[] = {
	"none", "eight_early", "eight_wrong_pocket", "eight_on_foul", "eight_off_table", "eight_pocketed",
	"nine_pocketed", "three_fouls", "target_reached", "eight_on_break", "push_out", "safety",
	"not_called"};
static const char *const group_names[] = {"open", "solids", "stripes"};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

static const char *name_of(const char *const *names, int count, int value) {
	return value >= 0 && value < count ? names[value] : NULL;
}

static int value_of(const char *const *names, int count, const char *name) {
	if (!name)
		return -1;
	for (int i = 0; i < count; ++i)
		if (strcmp(names[i], name) == 0)
			return i;
	return -1;
}

const char *pool_game_rules_name(pool_game_rules rules) {
	return name_of(rules_names, COUNT(rules_names), (int)rules);
}
int pool_game_rules_from_name(const char *name) { return value_of(rules_names, COUNT(rules_names), name); }
const char *pool_game_outcome_name(pool_game_outcome outcome) {
	return name_of(outcome_names, COUNT(outcome_names), (int)outcome);
}
int pool_game_outcome_from_name(const char *name) {
	return value_of(outcome_names, COUNT(outcome_names), name);
}
const char *pool_game_reason_name(pool_game_reason reason) {
	return name_of(reason_names, COUNT(reason_names), (int)reason);
}
int pool_game_reason_from_name(const char *name) { return value_of(reason_names, COUNT(reason_names), name); }
const char *pool_game_group_name(pool_game_group group) {
	return name_of(group_names, COUNT(group_names), (int)group);
}
int pool_game_group_from_name(const char *name) { return value_of(group_names, COUNT(group_names), name); }

const char *pool_game_foul_name(uint32_t foul) {
	for (int k = 0; k < POOL_GAME_FOUL_KINDS; ++k)
		if (foul == 1u << k)
			return foul_names[k];
	return NULL;
}

uint32_t pool_game_foul_from_name(const char *name) {
	const int k = value_of(foul_names, POOL_GAME_FOUL_KINDS, name);
	return k < 0 ? 0u : 1u << k;
}

pool_result pool_game_fail(pool_error *error, pool_result code, const char *format, ...) {
	if (error) {
		va_list args;
		va_start(args, format);
		vsnprintf(error->message, sizeof error->message, format, args);
		va_end(args);
	}
	return code;
}

pool_game_state pool_game_default_state(pool_game_rules rules) {
	pool_game_state s;
	memset(&s, 0, sizeof s);
	s.rules = rules;
	s.break_shot = true;
	s.cue_ball = 0;
	s.opponent_cue_ball = 1;
	s.group = POOL_GROUP_OPEN;
	s.called_ball = POOL_GAME_NO_BALL;
	s.called_pocket = POOL_POCKET_NONE;
	// The break is played from behind the head string (WPA 2.3 (a), 3.3 (a)); a carom break is
	// played from the starting position as it stands (UMB art. 23).
	s.ball_in_hand = rules != POOL_GAME_THREE_CUSHION;
	s.behind_head_string = s.ball_in_hand;
	return s;
}

pool_result pool_game_state_validate(const pool_game_state *s, pool_error *error) {
	if (!s)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state: missing");
	if (!pool_game_rules_name(s->rules))
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.rules: unknown rules %d", (int)s->rules);
	const char *rules = pool_game_rules_name(s->rules);
	if (s->player != 0 && s->player != 1)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.player: must be 0 or 1");
	if (s->fouls < 0 || s->opponent_fouls < 0)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.%s: must be >= 0",
		                      s->fouls < 0 ? "fouls" : "opponent_fouls");
	if (s->rules == POOL_GAME_9BALL && (s->fouls > 2 || s->opponent_fouls > 2))
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT,
		                      "game.state.%s: must be 0, 1 or 2 (a third consecutive foul loses the rack)",
		                      s->fouls > 2 ? "fouls" : "opponent_fouls");
	if (s->points < 0 || s->opponent_points < 0 || s->target_points < 0)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.%s: must be >= 0",
		                      s->points < 0 ? "points" : s->opponent_points < 0 ? "opponent_points" : "target");
	if (!pool_game_group_name(s->group))
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.group: unknown group %d", (int)s->group);
	if (s->rules != POOL_GAME_8BALL && s->group != POOL_GROUP_OPEN)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.group: only in 8ball, not %s", rules);
	if (s->break_shot && s->group != POOL_GROUP_OPEN)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.group: the table is open on the break");
	if (s->called_ball != POOL_GAME_NO_BALL) {
		if (s->rules != POOL_GAME_8BALL)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.called.ball: only in 8ball, not %s", rules);
		if (s->called_ball < 1 || s->called_ball > 15)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT,
			                      "game.state.called.ball: %d is not an object ball (1 to 15)", (int)s->called_ball);
	}
	if (s->called_pocket != POOL_POCKET_NONE) {
		if (s->rules != POOL_GAME_8BALL)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.called.pocket: only in 8ball, not %s", rules);
		if (!pool_pocket_name(s->called_pocket))
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.called.pocket: unknown pocket %d",
			                      (int)s->called_pocket);
	}
	if ((s->push_out || s->push_out_available) && s->rules != POOL_GAME_9BALL)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.push_out: only in 9ball, not %s", rules);
	if (s->push_out && !s->push_out_available)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT,
		                      "game.state.push_out: only on the shot after the break (push_out_available)");
	if (s->break_shot && (s->push_out_available || s->safety))
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.%s: not on the break",
		                      s->safety ? "safety" : "push_out_available");
	if (s->behind_head_string && !s->ball_in_hand)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT,
		                      "game.state.behind_head_string: needs ball_in_hand");
	if (s->rules == POOL_GAME_THREE_CUSHION) {
		if (s->cue_ball == s->opponent_cue_ball)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT,
			                      "game.state.opponent_cue_ball: must differ from cue_ball (%d)", (int)s->cue_ball);
		if (s->ball_in_hand)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.ball_in_hand: not in three_cushion");
	} else if (s->cue_ball != 0) {
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "game.state.cue_ball: must be 0 in %s", rules);
	}
	return POOL_OK;
}

pool_game_shot pool_game_shot_of_sim(const pool_sim *sim) {
	pool_game_shot shot;
	memset(&shot, 0, sizeof shot);
	if (!sim)
		return shot;
	shot.events = pool_sim_events(sim, &shot.event_count);
	if (shot.event_count > 0)
		shot.event_states = pool_sim_event_states(sim, &shot.events[0]) - shot.events[0].first_state;
	shot.balls = pool_sim_balls(sim);
	shot.ball_count = pool_sim_ball_count(sim);
	return shot;
}

bool pool_game_behind_head_string(const pool_table_def *table, pool_vec3 pos) {
	return pos.x <= 0.25 * table->length;
}

static int ball_index(const pool_ball_state *balls, int count, int32_t id) {
	for (int i = 0; i < count; ++i)
		if (balls[i].id == id)
			return i;
	return -1;
}

pool_result pool_game_check_balls(const pool_game_state *s, const pool_ball_state *balls, int count,
                                  pool_error *error) {
	pool_result r = pool_game_state_validate(s, error);
	if (r != POOL_OK)
		return r;
	if (count < 0 || (count > 0 && !balls))
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "balls: missing");
	const char *rules = pool_game_rules_name(s->rules);
	if (count > POOL_GAME_MAX_BALLS)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "balls: %d balls, more than a %s table holds (%d)",
		                      count, rules, POOL_GAME_MAX_BALLS);
	const int32_t last = s->rules == POOL_GAME_8BALL ? 15 : 9;
	for (int i = 0; i < count; ++i) {
		const int32_t id = balls[i].id;
		if (s->rules != POOL_GAME_THREE_CUSHION && (id < 0 || id > last))
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "balls: id %d is not a ball of %s (0 to %d)",
			                      (int)id, rules, (int)last);
	}
	if (s->rules == POOL_GAME_THREE_CUSHION) {
		if (count != 3)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT,
			                      "balls: three_cushion is played with three balls, not %d", count);
		const bool own = ball_index(balls, count, s->cue_ball) >= 0;
		if (!own || ball_index(balls, count, s->opponent_cue_ball) < 0)
			return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "balls: no ball has id %d (game.state.%s)",
			                      (int)(own ? s->opponent_cue_ball : s->cue_ball),
			                      own ? "opponent_cue_ball" : "cue_ball");
	} else if (ball_index(balls, count, 0) < 0) {
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "balls: no cue ball (id 0)");
	}
	return POOL_OK;
}

pool_result pool_game_judge(const pool_game_state *state, const pool_game_shot *shot,
                            const pool_table_def *table, pool_game_result *result, pool_error *error) {
	if (error)
		error->message[0] = '\0';
	if (!shot || !table || !result)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "%s: missing",
		                      !shot ? "shot" : !table ? "table" : "result");
	pool_result r = pool_game_check_balls(state, shot->balls, shot->ball_count, error);
	if (r != POOL_OK)
		return r;
	pool_game_facts facts;
	if ((r = pool_game_read_facts(shot, &facts, error)) != POOL_OK)
		return r;
	memset(result, 0, sizeof *result);
	pool_game_report_facts(&facts, result);
	result->next = *state;
	static const pool_game_judge_fn judges[] = {pool_game_judge_8ball, pool_game_judge_9ball,
	                                            pool_game_judge_three_cushion};
	r = judges[state->rules](state, shot, &facts, table, result, error);
	if (r == POOL_OK)
		result->legal = result->fouls == 0;
	return r;
}

void pool_game_finish(const pool_game_state *state, pool_game_outcome outcome, pool_game_result *result) {
	pool_game_state *next = &result->next;
	*next = *state;
	result->outcome = outcome;
	const int fouls = result->fouls ? state->fouls + 1 : 0;
	next->break_shot = false;
	next->called_ball = POOL_GAME_NO_BALL;
	next->called_pocket = POOL_POCKET_NONE;
	next->safety = false;
	next->push_out = false;
	next->push_out_available = false;
	next->ball_in_hand = result->ball_in_hand;
	next->behind_head_string = result->behind_head_string;
	next->points = state->points + result->points;
	next->fouls = fouls;
	if (outcome != POOL_OUTCOME_TURN_OVER)
		return;
	// The opponent's view: the counts, scores, cue balls and groups change sides.
	next->player = 1 - state->player;
	next->fouls = state->opponent_fouls;
	next->opponent_fouls = fouls;
	next->points = state->opponent_points;
	next->opponent_points = state->points + result->points;
	next->cue_ball = state->opponent_cue_ball;
	next->opponent_cue_ball = state->cue_ball;
	if (state->rules != POOL_GAME_THREE_CUSHION) { // one cue ball for both players
		next->cue_ball = state->cue_ball;
		next->opponent_cue_ball = state->opponent_cue_ball;
	}
	if (next->group != POOL_GROUP_OPEN)
		next->group = next->group == POOL_GROUP_SOLIDS ? POOL_GROUP_STRIPES : POOL_GROUP_SOLIDS;
}
