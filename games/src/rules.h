// The games' judges and the turn bookkeeping they share (game.c). Each judge decides from the
// facts of the shot (shot_facts.h) and the state before it.
#ifndef POOL_GAME_RULES_H
#define POOL_GAME_RULES_H

#include "pool/game.h"
#include "shot_facts.h"

/// A judge: fills result (facts already reported, result->next a copy of the state) or fails
/// with a message naming the field.
typedef pool_result (*pool_game_judge_fn)(const pool_game_state *state, const pool_game_shot *shot,
                                          const pool_game_facts *facts, const pool_table_def *table,
                                          pool_game_result *result, pool_error *error);

pool_result pool_game_judge_8ball(const pool_game_state *state, const pool_game_shot *shot,
                                  const pool_game_facts *facts, const pool_table_def *table,
                                  pool_game_result *result, pool_error *error);
pool_result pool_game_judge_9ball(const pool_game_state *state, const pool_game_shot *shot,
                                  const pool_game_facts *facts, const pool_table_def *table,
                                  pool_game_result *result, pool_error *error);
pool_result pool_game_judge_three_cushion(const pool_game_state *state, const pool_game_shot *shot,
                                          const pool_game_facts *facts, const pool_table_def *table,
                                          pool_game_result *result, pool_error *error);

/// Sets result->outcome and result->next from the state before the shot: the same shooter again
/// (continue) or the opponent (turn over; win and loss end the rack and leave the next state as
/// the same shooter's). Clears what belongs to one shot only (the call, safety, push out, ball in
/// hand, break) and counts the shooter's consecutive fouls from result->fouls.
void pool_game_finish(const pool_game_state *state, pool_game_outcome outcome, pool_game_result *result);

/// Whether a ball in hand behind the head string was placed there: its centre at x <= L/4 (the
/// head string itself counts as behind, so the head spot of pool_rack is a legal break position).
bool pool_game_behind_head_string(const pool_table_def *table, pool_vec3 pos);

/// Sets a formatted message (if error is not NULL) and returns code.
pool_result pool_game_fail(pool_error *error, pool_result code, const char *format, ...)
#if defined(__GNUC__)
	__attribute__((format(printf, 3, 4)))
#endif
	;

#endif
