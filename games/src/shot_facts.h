// What the rules of every game read from a shot's events: the struck ball, its first contact,
// the cushions it and the other balls touched, the balls pocketed or off the table. One pass over
// the events; the games (eight_ball.c, nine_ball.c, three_cushion.c) decide from these facts only.
#ifndef POOL_GAME_SHOT_FACTS_H
#define POOL_GAME_SHOT_FACTS_H

#include <stdbool.h>
#include <stdint.h>

#include "pool/game.h"

/// The facts of one shot. Ball sets are bit masks over the indices of shot->balls.
typedef struct pool_game_facts {
	int32_t struck;               ///< id of the ball the cue struck
	pool_vec3 struck_pos;         ///< where it stood when struck (m)
	int first_hit_event;          ///< index of the event of the cue ball's first contact, or -1
	int32_t first_hit;            ///< the ball it touched first, or POOL_GAME_NO_BALL
	int32_t second_hit;           ///< the first other ball it touched after that, or POOL_GAME_NO_BALL
	int cue_cushions_before_second; ///< the cue ball's ball_cushion events before second_hit (all if none)
	int rails_after_contact;      ///< ball_cushion events of any ball after first_hit_event
	uint32_t railed;              ///< balls with a ball_cushion event anywhere in the shot
	int pocketed_count;           ///< pocket events, in order
	int32_t pocketed[POOL_GAME_MAX_BALLS];
	pool_pocket pocketed_in[POOL_GAME_MAX_BALLS];
	int off_table_count;          ///< off_table events, in order
	int32_t off_table[POOL_GAME_MAX_BALLS];
} pool_game_facts;

/// Index of ball id in shot->balls, or -1.
int pool_game_ball_index(const pool_game_shot *shot, int32_t id);

/// Reads the facts of a shot whose cue ball is `cue` (the ball the rules expect struck; the facts
/// follow the ball actually struck). Returns POOL_OK, or an error naming "events" when the shot has
/// no strike first.
pool_result pool_game_read_facts(const pool_game_shot *shot, pool_game_facts *facts, pool_error *error);

/// Whether ball id was pocketed, or left the table, in this shot.
bool pool_game_facts_pocketed(const pool_game_facts *f, int32_t id);
bool pool_game_facts_off_table(const pool_game_facts *f, int32_t id);

/// Copies the facts every result reports (first hit, rails, pocketed, off table).
void pool_game_report_facts(const pool_game_facts *f, pool_game_result *r);

#endif
