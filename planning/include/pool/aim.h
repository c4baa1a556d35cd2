// libpool planning: the shots that pot a ball, ranked by their chance of success under the noise
// of a real stroke (docs/planning.md). A library of its own on libpool's and libpool games'
// public API: candidates from the geometry (ghost ball, mirror images), refined by simulation,
// the cue stick checked against the balls and the rail, each ranked by batch sampling with a
// confidence interval, on every core.
#ifndef POOL_AIM_H
#define POOL_AIM_H

#include <stdbool.h>
#include <stdint.h>

#include "pool/game.h"
#include "pool/noise.h"
#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// An id that names no ball: any target ball (pool_aim_def.ball), no second ball (via).
#define POOL_AIM_NO_BALL INT32_MIN

/// How a shot pots its ball.
typedef enum pool_aim_kind {
	POOL_AIM_STRAIGHT = 0,    ///< "straight": the cue ball drives the ball into the pocket (ghost ball)
	POOL_AIM_BANK = 1,        ///< "bank": the ball goes off one cushion into the pocket
	POOL_AIM_KICK = 2,        ///< "kick": the cue ball goes off one cushion, then into the ball
	POOL_AIM_COMBINATION = 3, ///< "combination": the cue ball drives another ball (via) into the ball
	POOL_AIM_CAROM = 4,       ///< "carom": the ball glances off another ball (via) into the pocket
} pool_aim_kind;

/// Number of kinds.
#define POOL_AIM_KINDS 5

/// "straight", "bank", "kick", "combination", "carom"; NULL out of range.
POOL_API const char *pool_aim_kind_name(pool_aim_kind kind);
/// The kind of that name, or -1.
POOL_API int pool_aim_kind_from_name(const char *name);

/// What to search, and how hard.
typedef struct pool_aim_def {
	pool_sim_def sim;              ///< table, parameters, models (as for pool_sim_create)
	const pool_ball_state *balls;  ///< the position: every ball at rest on the cloth
	int ball_count;                ///< number of balls
	int32_t cue_ball;              ///< the ball the cue strikes
	int32_t ball;                  ///< the ball to pot, or POOL_AIM_NO_BALL for any
	pool_pocket pocket;            ///< the pocket, or POOL_POCKET_NONE for any
	unsigned kinds;                ///< kinds searched, bits 1 << pool_aim_kind; 0 = all
	const pool_game_state *game;   ///< the rules judging success, or NULL: the ball in the pocket
	                               ///< and the cue ball still on the table
	pool_noise noise;              ///< the stroke's noise (pool/noise.h)
	uint64_t seed;                 ///< of the noise's samples
	int samples;                   ///< samples behind each reported p_success (and the most a
	                               ///< candidate gets while the ranking is decided)
	int top;                       ///< shots wanted (K)
	double time_budget;            ///< s of wall time; 0 = none (then the result depends on the
	                               ///< input alone, not on the threads or the machine)
	int threads;                   ///< worker threads; 0 = the online CPUs
	bool position;                 ///< score where the cue ball ends (pool_aim_shot.position)
	bool distinct;                 ///< one shot per ball, pocket, kind, second ball and cushion (its
	                               ///< best speed and spin), so the K shown are K different shots
} pool_aim_def;

/// One shot found.
typedef struct pool_aim_shot {
	pool_strike strike;     ///< the cue parameters (radians), refined by simulation
	int32_t ball;           ///< the ball it pots
	pool_pocket pocket;     ///< into this pocket
	pool_aim_kind kind;     ///< how
	int32_t via;            ///< combination: the ball the cue ball drives; carom: the ball kissed;
	                        ///< else POOL_AIM_NO_BALL
	pool_rail rail;         ///< bank and kick: the cushion; else POOL_RAIL_NONE
	double p_success;       ///< share of noisy repetitions that succeed
	double ci_low, ci_high; ///< its 95 % Wilson score interval (with continuity correction)
	int samples;            ///< repetitions behind it (drawn after the shot was chosen)
	pool_vec3 cue_final;    ///< where the cue ball ends without noise
	int position;           ///< balls the cue ball then has a clear straight pot on (-1: not scored)
} pool_aim_shot;

/// What a search did.
typedef struct pool_aim_stats {
	int candidates;          ///< geometric candidates (kinds x balls x pockets x cushions x speeds x spins)
	int blocked;             ///< of those, discarded for a cue stick blocked by a ball or the rail
	int refined;             ///< refined by simulation
	int potting;             ///< refined into a shot that pots without noise
	long long simulations;   ///< shots simulated
	double seconds;          ///< wall time
	bool budget_reached;     ///< the time budget cut the search short
} pool_aim_stats;

/// Defaults: WPA 9 ft table and docs/physics.md parameters, cue ball 0, any ball and pocket, all
/// kinds, no rules, fastfiz noise, seed 1, 400 samples, top 5, no time budget, all CPUs, no
/// position score.
POOL_API pool_aim_def pool_default_aim_def(void);

/// Checks a def as pool_aim_search does, without searching (a service checks a request before it
/// waits for its turn); the message names the field.
POOL_API pool_result pool_aim_def_validate(const pool_aim_def *def, pool_error *error);

/// Searches the shots of the position and writes the best (up to capacity, and def->top), best
/// first, into shots; *count receives how many. Errors name the field ("aim.ball: no ball has id
/// 16", "balls[2].pos: overlaps ball 1 by ...", "aim.game: three_cushion has no pockets").
/// Finding no shot is not an error (*count = 0).
POOL_API pool_result pool_aim_search(const pool_aim_def *def, pool_aim_shot *shots, int capacity, int *count,
                                     pool_aim_stats *stats, pool_error *error);

#ifdef __cplusplus
}
#endif

#endif
