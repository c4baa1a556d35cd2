// The optional models of a simulation (pool_models, docs/physics.md "Models"): validation
// of a def's choice. Each model lives with the law it replaces (cushion.c, ball_ball.c,
// strike.c).
#ifndef POOL_MODELS_H
#define POOL_MODELS_H

#include "pool/sim.h"

/// Rejects out-of-range enum values, naming the field: "models.cushion: unknown model 7".
pool_result pool_models_validate(const pool_models *models, pool_error *error);

/// The squirt angle (rad, counter-clockwise seen from above) of a level strike with horizontal
/// tip offset a (m, + = shooter's right): Alciatore TP A.31,
/// tan alpha = (5/2)(a/R) sqrt(1 - (a/R)^2) / (1 + m/m_e + (5/2)(1 - (a/R)^2)), m_e = cue_end_mass.
/// Right English (a > 0) squirts the ball left: a positive angle.
double pool_squirt_angle(const pool_params *params, double a);

/// pool_strike_velocities, then the squirt model: "endmass" turns the horizontal velocity by
/// pool_squirt_angle (speed and spin are the strike's). pool_sim_strike calls this.
pool_result pool_strike_velocities_modelled(const pool_params *params, pool_squirt_model squirt,
                                            const pool_strike *strike, pool_vec3 *vel, pool_vec3 *omega,
                                            pool_error *error);

#endif
