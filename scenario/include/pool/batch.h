// The batch shot: one layout (a parsed scenario), many strikes given in the file's degrees, each
// simulated on a reused simulation to its final states, with the figures pool-batch prints for it
// (stop reason, events, first ball hit, the game's verdict) and the messages it prints for strikes
// the library refuses. pool-batch, pool-sensitivity and Python's libpool.batch shoot here, so a
// row of any of them is the same shot, bit for bit.
#ifndef POOL_BATCH_H
#define POOL_BATCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pool/game.h"
#include "pool/noise.h"
#include "pool/pool.h"
#include "pool/scenario.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A buffer this long holds every message of a shot whole: the library's message (pool_error,
/// 256 bytes) with the batch's prefix.
#define POOL_BATCH_MESSAGE_SIZE 400

/// What one shot of a batch gave.
typedef struct pool_batch_shot {
	pool_result result;           ///< POOL_OK when simulated; else the library's code
	bool failed;                  ///< the library failed (out of memory, an internal error, a
	                              ///< simulation that could not go on), as opposed to a strike it
	                              ///< refused (a^2 + b^2 >= R^2, an unknown ball...)
	pool_stop_reason stop_reason; ///< why the simulation stopped (simulated shots)
	int events;                   ///< events processed (simulated shots)
	double end_time;              ///< s, the instant of the final states (simulated shots)
	bool hit;                     ///< the struck ball hit a ball: first_hit is its id
	int32_t first_hit;            ///< the first ball the struck ball hit (ball_ball or link_begin)
	bool judged;                  ///< the layout's rules judged the shot: game is the verdict
	pool_game_result game;        ///< legal, fouls, outcome, points... (when judged)
	char message[POOL_BATCH_MESSAGE_SIZE]; ///< "" when simulated; else why not, as pool-batch
	                                       ///< prints it ("strike.a: a^2 + b^2 must be < R^2")
} pool_batch_shot;

/// Simulates strikes[0..count) on layout (its balls are shared, read only; its own strike is not
/// used) one after another in *sim (created when NULL, reset for each shot). Shot i's record goes
/// to shots[i] and its final states, layout->ball_count of them in the layout's order, to
/// finals[i * layout->ball_count ...] (left as they were for a shot that was not simulated).
/// A strike the library refuses is recorded and the batch goes on; after a shot that failed
/// (shots[i].failed) it stops. Returns the number of records written: count, or i + 1 when shot i
/// failed. Deterministic: a shot depends only on the layout and its strike. The caller may run
/// several batches at once on separate simulations (one per thread).
POOL_API int pool_batch_run(const pool_scenario *layout, const pool_batch_strike *strikes, int count,
                            pool_sim **sim, pool_batch_shot *shots, pool_ball_state *finals);

/// One shot of pool_batch_run without its figures: simulates strike s on layout in *sim (created
/// when NULL, else reset) and writes the final states (layout->ball_count of them) to final.
/// Returns true when the shot ran; false with pool-batch's message in error when the library
/// refused the strike (*internal false) or failed (out of memory, an internal error: *internal
/// true).
POOL_API bool pool_batch_shoot(const pool_scenario *layout, const pool_batch_strike *s, pool_sim **sim,
                               pool_ball_state *final, char *error, size_t error_size, bool *internal);

/// Strike `nominal` with noise: sample `sample` of `seed` (pool_noise_normal's deviates k = 0..4
/// for speed, phi, theta, a, b), each parameter nominal + sd * z in the file's units (phi and
/// theta in degrees: the noise's radians divided by POOL_DEGREE), exactly nominal where sd is
/// 0, theta folded to |theta|. pool-batch --noise and pool-sensitivity draw their strikes here.
POOL_API pool_batch_strike pool_batch_noisy(const pool_batch_strike *nominal, const pool_noise *noise,
                                            uint64_t seed, uint64_t sample);

/// Judges the shot pool_batch_shoot just ran on a layout with a "game": false when the layout
/// has none or the rules refuse the shot.
POOL_API bool pool_batch_judge(const pool_scenario *layout, const pool_sim *sim, pool_game_result *result);

/// The id of the first ball the struck ball hits (ball_ball or link_begin), or false.
POOL_API bool pool_batch_first_hit(const pool_sim *sim, int32_t ball, int32_t *hit);

#ifdef __cplusplus
}
#endif

#endif
