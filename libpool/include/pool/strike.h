// libpool: the five-parameter cue strike (docs/physics.md, "Cue strike").
#ifndef POOL_STRIKE_H
#define POOL_STRIKE_H

#include "pool/ball.h"
#include "pool/table.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Cue parameters. Angles in radians here (degrees only in JSON and on the command line).
typedef struct pool_strike {
	double speed; ///< m/s, cue speed V (> 0)
	double phi;   ///< rad, aim direction in the table plane from +x, counter-clockwise
	double theta; ///< rad, cue elevation in [0, pi/2)
	double a;     ///< m, horizontal tip offset, + = shooter's right
	double b;     ///< m, vertical tip offset, + = above centre; a^2 + b^2 < R^2
} pool_strike;

/// Velocity and spin the strike gives a ball at rest (Leckie & Greenspan impulse),
/// including the vertical component (dropped later in planar mode).
POOL_API pool_result pool_strike_velocities(const pool_params *params, const pool_strike *strike,
                                            pool_vec3 *vel, pool_vec3 *omega, pool_error *error);

#ifdef __cplusplus
}
#endif

#endif
