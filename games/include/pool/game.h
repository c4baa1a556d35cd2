// libpool games: the rules of 8-ball, 9-ball and three-cushion applied to a shot's events
// (docs/games.md). A library of its own on libpool's public API; libpool knows nothing of games.
#ifndef POOL_GAME_H
#define POOL_GAME_H

#include <stdbool.h>
#include <stdint.h>

#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The most balls a game's table holds (8-ball: the cue ball and 15 object balls).
#define POOL_GAME_MAX_BALLS 16

/// A ball id that names no ball (first_hit when the cue ball touched nothing, no called ball).
#define POOL_GAME_NO_BALL INT32_MIN

/// Which rules judge the shot.
typedef enum pool_game_rules {
	POOL_GAME_8BALL = 0,        ///< "8ball": WPA eight ball, ids 0 (cue) and 1..15
	POOL_GAME_9BALL = 1,        ///< "9ball": WPA nine ball, ids 0 (cue) and 1..9
	POOL_GAME_THREE_CUSHION = 2 ///< "three_cushion": UMB three cushion, three balls of any ids
} pool_game_rules;

/// What the shot means for the shooter.
typedef enum pool_game_outcome {
	POOL_OUTCOME_CONTINUE = 0,  ///< "continue": the same player shoots again
	POOL_OUTCOME_TURN_OVER = 1, ///< "turn_over": the opponent shoots next
	POOL_OUTCOME_WIN = 2,       ///< "win": the shooter wins the rack (or reaches the target score)
	POOL_OUTCOME_LOSS = 3       ///< "loss": the shooter loses the rack
} pool_game_outcome;

/// Fouls, as bits of pool_game_result.fouls (names as in docs/interfaces.md "Games").
typedef enum pool_game_foul {
	POOL_FOUL_SCRATCH = 1 << 0,          ///< "scratch": cue ball pocketed or off the table (WPA 6.1)
	POOL_FOUL_NO_CONTACT = 1 << 1,       ///< "no_contact": the cue ball hit no ball (WPA 6.2)
	POOL_FOUL_WRONG_BALL_FIRST = 1 << 2, ///< "wrong_ball_first": not a legal ball first (WPA 6.2)
	POOL_FOUL_NO_RAIL = 1 << 3,          ///< "no_rail": nothing pocketed, no ball to a rail after contact (WPA 6.3)
	POOL_FOUL_BALL_OFF_TABLE = 1 << 4,   ///< "ball_off_table": an object ball left the table (WPA 6.5, UMB 28)
	POOL_FOUL_ILLEGAL_BREAK = 1 << 5,    ///< "illegal_break": nothing pocketed, < 4 balls to rails (WPA 2.3, 3.3)
	POOL_FOUL_WRONG_CUE_BALL = 1 << 6,   ///< "wrong_cue_ball": the cue struck another ball (WPA 6.6, UMB 41)
	POOL_FOUL_BAD_PLACEMENT = 1 << 7,    ///< "bad_placement": ball in hand put in front of the head string (WPA 6.10)
} pool_game_foul;

/// How many foul kinds there are (bits 0 .. POOL_GAME_FOUL_KINDS - 1).
#define POOL_GAME_FOUL_KINDS 8

/// Why the outcome is what it is, when the fouls do not say it all.
typedef enum pool_game_reason {
	POOL_REASON_NONE = 0,              ///< "none": the ordinary consequence of the shot
	POOL_REASON_EIGHT_EARLY = 1,       ///< "eight_early": 8 pocketed before the group was cleared (WPA 3.8)
	POOL_REASON_EIGHT_WRONG_POCKET = 2, ///< "eight_wrong_pocket": 8 pocketed in another pocket than called (WPA 3.8)
	POOL_REASON_EIGHT_ON_FOUL = 3,     ///< "eight_on_foul": 8 pocketed on a foul (WPA 3.8)
	POOL_REASON_EIGHT_OFF_TABLE = 4,   ///< "eight_off_table": 8 driven off the table (WPA 3.8)
	POOL_REASON_EIGHT_POCKETED = 5,    ///< "eight_pocketed": the 8 legally pocketed, the rack won (WPA 3.5)
	POOL_REASON_NINE_POCKETED = 6,     ///< "nine_pocketed": the 9 legally pocketed, the rack won (WPA 2.5)
	POOL_REASON_THREE_FOULS = 7,       ///< "three_fouls": a third consecutive foul (WPA 6.14, 2.8)
	POOL_REASON_TARGET_REACHED = 8,    ///< "target_reached": three cushion, the shooter reached the target score
	POOL_REASON_EIGHT_ON_BREAK = 9,    ///< "eight_on_break": the 8 down or off on the break, spotted (WPA 3.3)
	POOL_REASON_PUSH_OUT = 10,         ///< "push_out": a push out, the opponent may play or pass it back (WPA 2.4)
	POOL_REASON_SAFETY = 11,           ///< "safety": a declared safety, the turn passes (WPA 1.6)
	POOL_REASON_NOT_CALLED = 12,       ///< "not_called": the called ball not in the called pocket (WPA 3.5, 3.6)
} pool_game_reason;

/// 8-ball groups, as the shooter's ("open" before they are chosen, WPA 3.4).
typedef enum pool_game_group {
	POOL_GROUP_OPEN = 0,    ///< "open"
	POOL_GROUP_SOLIDS = 1,  ///< "solids": 1 to 7
	POOL_GROUP_STRIPES = 2, ///< "stripes": 9 to 15
} pool_game_group;

/// What the rules need to know from earlier shots, seen from the player about to shoot.
/// pool_game_default_state() gives a game's first shot (the break).
typedef struct pool_game_state {
	pool_game_rules rules;        ///< the game
	int player;                   ///< 0 or 1: who shoots (flips when the turn passes)
	bool break_shot;              ///< the opening break ("break")
	int32_t cue_ball;             ///< id of the ball the shooter must strike (0; three cushion: the shooter's own)
	int32_t opponent_cue_ball;    ///< three cushion: the opponent's cue ball (1); unused otherwise
	pool_game_group group;        ///< 8-ball: the shooter's group
	int32_t called_ball;          ///< 8-ball: the called ball, or POOL_GAME_NO_BALL (any legal ball counts)
	pool_pocket called_pocket;    ///< 8-ball: the called pocket, or POOL_POCKET_NONE (any pocket)
	bool safety;                  ///< the shooter declared a safety (WPA 1.6): the turn passes after the shot
	bool push_out;                ///< 9-ball: the shooter plays a push out (needs push_out_available)
	bool push_out_available;      ///< 9-ball: this is the shot after the break, a push out may be declared
	bool ball_in_hand;            ///< the shooter placed the cue ball (after a foul, or for the break)
	bool behind_head_string;      ///< ... and had to place it behind the head string (x <= L/4)
	int fouls;                    ///< the shooter's consecutive fouls so far (WPA 6.14)
	int opponent_fouls;           ///< the opponent's consecutive fouls
	int points;                   ///< the shooter's score (three cushion)
	int opponent_points;          ///< the opponent's score
	int target_points;            ///< three cushion: the score that wins (0: play on)
} pool_game_state;

/// One shot as the rules read it: its events and their after-states, and the balls on the table
/// when it began. pool_game_shot_of_sim() fills it from a simulation that has run.
typedef struct pool_game_shot {
	const pool_event *events;            ///< in time order; events[0] must be the strike
	int event_count;                     ///< number of events
	const pool_ball_state *event_states; ///< events[i]'s balls are event_states[events[i].first_state ...]
	const pool_ball_state *balls;        ///< every ball on the table when the shot began (ids)
	int ball_count;                      ///< number of balls (at most POOL_GAME_MAX_BALLS)
} pool_game_shot;

/// What a shot means under the rules (docs/interfaces.md "Games").
typedef struct pool_game_result {
	bool legal;                    ///< no foul
	uint32_t fouls;                ///< pool_game_foul bits
	pool_game_outcome outcome;     ///< continue, turn over, win, loss
	pool_game_reason reason;       ///< why, when it is more than the fouls
	bool ball_in_hand;             ///< the next shooter places the cue ball
	bool behind_head_string;       ///< ... behind the head string (8-ball after a foul on the break)
	bool rerack_option;            ///< the rules let a player ask for a re-rack (8-ball break, WPA 3.3)
	bool pass_option;              ///< the incoming player may pass the shot back (after a push out, WPA 2.4)
	int points;                    ///< what the shot scored (three cushion: 1 for a point)
	int32_t first_hit;             ///< first ball the cue ball touched, or POOL_GAME_NO_BALL
	int rails_after_contact;       ///< ball_cushion events (any ball) after the cue ball's first contact
	int cue_cushions;              ///< the cue ball's cushion contacts before it met the second ball (three cushion)
	int pocketed_count;            ///< balls pocketed, in event order
	int32_t pocketed[POOL_GAME_MAX_BALLS];     ///< their ids
	pool_pocket pocketed_in[POOL_GAME_MAX_BALLS]; ///< and their pockets
	int off_table_count;           ///< balls that left the table, in event order
	int32_t off_table[POOL_GAME_MAX_BALLS];    ///< their ids
	int spot_count;                ///< balls the rules put back on the table (the 9 after a foul, the 8 on the break)
	int32_t spot[POOL_GAME_MAX_BALLS];         ///< their ids
	pool_game_state next;          ///< the next shot's state (the next shooter's view)
} pool_game_result;

/// "8ball", "9ball", "three_cushion"; NULL out of range.
POOL_API const char *pool_game_rules_name(pool_game_rules rules);
/// The rules of that name, or -1.
POOL_API int pool_game_rules_from_name(const char *name);
/// "continue", "turn_over", "win", "loss"; NULL out of range.
POOL_API const char *pool_game_outcome_name(pool_game_outcome outcome);
/// The outcome of that name, or -1.
POOL_API int pool_game_outcome_from_name(const char *name);
/// The name of one foul bit ("scratch", ...); NULL for anything but a single known bit.
POOL_API const char *pool_game_foul_name(uint32_t foul);
/// The foul bit of that name, or 0.
POOL_API uint32_t pool_game_foul_from_name(const char *name);
/// The reason's name ("none", "eight_early", ...); NULL out of range.
POOL_API const char *pool_game_reason_name(pool_game_reason reason);
/// The reason of that name, or -1.
POOL_API int pool_game_reason_from_name(const char *name);
/// "open", "solids", "stripes"; NULL out of range.
POOL_API const char *pool_game_group_name(pool_game_group group);
/// The group of that name, or -1.
POOL_API int pool_game_group_from_name(const char *name);

/// The first shot of a game: the break, player 0, cue ball 0 in hand behind the head string
/// (three cushion: player 0 plays ball 0 against 1 and 2, no ball in hand), nothing called.
POOL_API pool_game_state pool_game_default_state(pool_game_rules rules);

/// Checks a state's ranges; the message names the field ("game.state.fouls: must be 0, 1 or 2").
POOL_API pool_result pool_game_state_validate(const pool_game_state *state, pool_error *error);

/// Checks that the balls (count of them) can be a table of state->rules: the state in range, at
/// most POOL_GAME_MAX_BALLS balls, every id one of the game's (8-ball 0 to 15, 9-ball 0 to 9, the
/// cue ball 0 among them; three cushion exactly three balls, the two cue balls among them). The
/// message names the field ("balls: id 16 is not a ball of 8ball (0 to 15)").
POOL_API pool_result pool_game_check_balls(const pool_game_state *state, const pool_ball_state *balls,
                                           int count, pool_error *error);

/// The shot a simulation has run: its events and every ball it holds (pocketed ones included:
/// they were on the table when the shot began). Valid until the simulation changes.
POOL_API pool_game_shot pool_game_shot_of_sim(const pool_sim *sim);

/// Judges a shot under state->rules: fouls, outcome, points, the facts the rules read (first
/// ball hit, rails after contact, pocketed balls) and the next state. table gives the head string
/// (x = L/4) for ball-in-hand placement. Errors (the message names the field): the state out of
/// range, no strike first, more than POOL_GAME_MAX_BALLS balls, an id the game has no ball for
/// ("balls: id 16 is not a ball of 8ball (0 to 15)"), three cushion without three balls.
POOL_API pool_result pool_game_judge(const pool_game_state *state, const pool_game_shot *shot,
                                     const pool_table_def *table, pool_game_result *result,
                                     pool_error *error);

/// One shot of a game in one call, what a player loop does per shot: resets sim to def, adds the
/// balls (count of them), strikes state->cue_ball, runs the shot to its end, judges it under
/// state, and writes every ball's state at the end (count of them, in the order given) to final.
/// Returns POOL_OK, or the first error with its message (a ball the library refuses, a strike it
/// refuses: a^2 + b^2 >= R^2...), *result untouched.
POOL_API pool_result pool_game_shoot(pool_sim *sim, const pool_sim_def *def, const pool_ball_state *balls,
                                     int count, const pool_strike *strike, const pool_game_state *state,
                                     pool_game_result *result, pool_ball_state *final, pool_error *error);

/// Where the rules put a ball back on the table (WPA 1.4: on the foot spot, else as near to it
/// as possible behind it on the long string, else in front of it; three cushion, UMB art. 28: its
/// starting spot, else the other spots). balls are the balls on the table (count of them) that
/// it must not touch; the ball lies on the cloth. Returns POOL_OK with *pos, or
/// POOL_ERR_INVALID_ARGUMENT when the long string has no room.
POOL_API pool_result pool_game_spot_position(const pool_game_state *state, int32_t id,
                                             const pool_table_def *table, double ball_radius,
                                             const pool_ball_state *balls, int count,
                                             pool_vec3 *pos);

/// The balls of a game's opening position, at rest on the cloth: 8-ball and 9-ball the racks of
/// pool_rack (gap m between neighbours), three cushion UMB's (art. 23): red (2) on the foot spot,
/// the opponent's ball (1) on the head spot, the breaker's ball (0) on the head string 0.182 m to
/// the side. Returns the number written or a negative pool_result.
POOL_API int pool_game_rack(pool_game_rules rules, const pool_table_def *table, const pool_params *params,
                            double gap, pool_ball_state *balls, int capacity);

#ifdef __cplusplus
}
#endif

#endif
