// One shot of a batch: a layout, a strike given in the file's degrees, simulated on a reused
// simulation to its final states, with pool-batch's messages for strikes the library refuses.
// Shared by pool-batch and pool-sensitivity, so a sensitivity sample and the pool-batch row of
// the same strike are the same shot, bit for bit.
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

#define POOL_BATCH_PI 3.14159265358979323846
/// Degrees to radians exactly as the scenario parser converts strike.phi and strike.theta.
#define POOL_BATCH_DEG (POOL_BATCH_PI / 180.0)

/// A strike as the user writes it: angles in degrees.
typedef struct pool_batch_strike {
	int32_t ball;
	double speed; ///< m/s
	double phi;   ///< degrees
	double theta; ///< degrees
	double a, b;  ///< m
} pool_batch_strike;

/// Simulates strike s on layout (whose balls are shared, read only) in *sim (created when NULL,
/// else reset), and writes the final states (layout->ball_count of them) to final. Returns true
/// when the shot ran; false with pool-batch's message in error when the library refused the
/// strike (*internal false) or failed (out of memory, an internal error: *internal true).
POOL_API bool pool_batch_shoot(const pool_scenario *layout, const pool_batch_strike *s, pool_sim **sim,
                      pool_ball_state *final, char *error, size_t error_size, bool *internal);

/// Strike `nominal` with noise: sample `sample` of `seed` (pool_noise_normal's deviates k = 0..4
/// for speed, phi, theta, a, b), each parameter nominal + sd * z in the file's units (phi and
/// theta in degrees: the noise's radians divided by POOL_BATCH_DEG), exactly nominal where sd is
/// 0, theta folded to |theta|. pool-batch --noise and pool-sensitivity draw their strikes here.
POOL_API pool_batch_strike pool_batch_noisy(const pool_batch_strike *nominal, const pool_noise *noise, uint64_t seed,
                                   uint64_t sample);

/// Judges the shot pool_batch_shoot just ran on a layout with a "game": false when the layout
/// has none or the rules refuse the shot.
POOL_API bool pool_batch_judge(const pool_scenario *layout, const pool_sim *sim, pool_game_result *result);

/// The id of the first ball the struck ball hits (ball_ball or link_begin), or false.
POOL_API bool pool_batch_first_hit(const pool_sim *sim, int32_t ball, int32_t *hit);

#ifdef __cplusplus
}
#endif

#endif
