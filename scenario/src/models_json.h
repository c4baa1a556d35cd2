// The "models" of scenario and result files (docs/interfaces.md, docs/physics.md "Models"): the
// kinds of model and their names, the model sets, for the scenario parser, the commands' --model
// and --models and every tool that writes a scenario or a result back, so the models a shot was
// simulated with travel with it. The names themselves are the library's (pool_cushion_model_name,
// pool_models_preset_name...).
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

/// The names of the model sets (the library's pool_models_preset_name), "default, thesis", for
/// error messages; cut to fit size (> 0).
void pool_model_set_names(char *out, size_t size);

/// Applies one part of a --models value to *models: a model set ("default", "thesis": every
/// kind) or a model name of any kind ("mathavan2010", "endmass": that kind). False when the
/// name is neither (*models unchanged then).
bool pool_models_apply(pool_models *models, const char *part);

/// Applies a --models value to *models: parts joined with '+', each as pool_models_apply, left to
/// right ("thesis+endmass": the 2012 work's laws with the end-mass squirt). Returns 0, or -1 with
/// a message naming the part (*models unchanged then).
int pool_models_parse_spec(pool_models *models, const char *spec, char *err, size_t err_size);

/// Writes the key "models" and its object, every kind by its library name, on one line:
/// "models": {"cushion": "mathavan2010", "ball_ball_friction": "constant", "squirt": "none"}.
void pool_jw_models(pool_jw *w, const pool_models *models);

#ifdef __cplusplus
}
#endif

#endif
