// libpool games: Gaussian noise on the five cue parameters, reproducible from a seed and a sample
// number (docs/games.md "Noise"). One implementation for pool-batch --noise, pool-sensitivity,
// Python (libpool.game) and shot planning.
#ifndef POOL_NOISE_H
#define POOL_NOISE_H

#include <stdint.h>

#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Standard deviations of independent Gaussian noise on a strike's parameters, in the units of
/// pool_strike (radians here; degrees only in names and specs). Zero means no noise on it.
typedef struct pool_noise {
	double speed; ///< m/s
	double phi;   ///< rad
	double theta; ///< rad
	double a;     ///< m
	double b;     ///< m
} pool_noise;

/// The named presets, for messages: "none, fastfiz".
POOL_API const char *pool_noise_preset_names(void);

/// A named preset: "none" (all zero) or "fastfiz" (the Computational Pool tournaments' noise:
/// a 0.5 mm, b 0.5 mm, theta 0.1 deg, phi 0.125 deg, speed 0.075 m/s). POOL_ERR_INVALID_ARGUMENT
/// for another name.
POOL_API pool_result pool_noise_preset(const char *name, pool_noise *noise);

/// A preset name, or NAME=SD pairs separated by commas with NAME among speed (m/s), phi and theta
/// (degrees), a and b (m); parameters not named have no noise: "phi=0.2,speed=0.05". The message
/// names the part at fault ("noise: phi: 'x' is not a standard deviation >= 0").
POOL_API pool_result pool_noise_parse(const char *spec, pool_noise *noise, pool_error *error);

/// Checks every standard deviation is finite and >= 0; the message names the parameter.
POOL_API pool_result pool_noise_validate(const pool_noise *noise, pool_error *error);

/// The k-th standard normal deviate of sample `sample` under `seed`: a function of the three
/// numbers only (counter-based), so sample i is the same whatever the order or the threads.
POOL_API double pool_noise_normal(uint64_t seed, uint64_t sample, uint32_t k);

/// The nominal strike with noise: parameter p (speed, phi, theta, a, b for k = 0..4) becomes
/// nominal + sd * pool_noise_normal(seed, sample, k), exactly nominal when its sd is 0; theta is
/// folded to |theta| (a cue does not point below the horizontal). The result may be a strike the
/// library refuses (speed <= 0, a^2 + b^2 >= R^2): callers count or redraw it.
POOL_API pool_strike pool_noise_apply(const pool_noise *noise, uint64_t seed, uint64_t sample,
                                      const pool_strike *nominal);

#ifdef __cplusplus
}
#endif

#endif
