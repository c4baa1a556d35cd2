// The optional models of a simulation (pool_models, PHYSICS.md "Optional models"): validation
// of a def's choice. Each model lives with the law it replaces (cushion.c, ball_ball.c,
// strike.c).
#ifndef POOL_MODELS_H
#define POOL_MODELS_H

#include "pool/sim.h"

/// Rejects out-of-range enum values, naming the field: "models.cushion: unknown model 7".
pool_result pool_models_validate(const pool_models *models, pool_error *error);

#endif
