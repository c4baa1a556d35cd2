// The "models" object of scenario and result files (docs/interfaces.md, docs/physics.md "Optional
// models"): the kinds of model and their names, for the scenario parser, pool-rack --model and
// every tool that writes a scenario or a result back, so the models a shot was simulated with
// travel with it. The names themselves are the library's (pool_cushion_model_name...).
#ifndef POOL_TOOLS_MODELS_JSON_H
#define POOL_TOOLS_MODELS_JSON_H

#include <stdbool.h>
#include <stddef.h>

#include "json_writer.h"
#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The keys of the "models" object, NULL-terminated: "cushion", "ball_ball_friction", "squirt".
extern const char *const pool_model_kinds[];

/// Sets one kind of *models by its name ("cushion", "mathavan2010"). Returns 0; -1 when kind is
/// not a key of "models"; -2 when name is not a model of that kind (*models unchanged then).
int pool_models_set(pool_models *models, const char *kind, const char *name);

/// The names of one kind's models, "petit, mathavan2010", or of the kinds when kind is NULL or
/// unknown, for error messages; cut to fit size (> 0).
void pool_model_names(const char *kind, char *out, size_t size);

/// Whether every model is the default one (all fields zero: today's laws). Writers leave the
/// "models" key out then, so documents of default shots are byte-identical to those written
/// before models existed, and a reader takes a missing "models" as the defaults.
bool pool_models_are_default(const pool_models *models);

/// Writes the key "models" and its object, every kind by its library name, on one line:
/// "models": {"cushion": "mathavan2010", "ball_ball_friction": "constant", "squirt": "none"}.
void pool_jw_models(pool_jw *w, const pool_models *models);

#ifdef __cplusplus
}
#endif

#endif
