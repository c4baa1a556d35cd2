// The models of a simulation (docs/physics.md "Models", docs/interfaces.md "models"): their names,
// the named model sets ("default": the measured laws; "thesis": the 2012 work's) and validation.
#include "models.h"

#include <string.h>

#include "error.h"

static const char *const cushion_names[] = {"petit", "mathavan2010"};
static const char *const ball_friction_names[] = {"constant", "alciatore"};
static const char *const squirt_names[] = {"none", "endmass"};

#define COUNT(names) ((int)(sizeof names / sizeof names[0]))

static const char *name_of(const char *const *names, int count, int value) {
	return value >= 0 && value < count ? names[value] : "unknown";
}

static int value_of(const char *const *names, int count, const char *name) {
	for (int i = 0; name && i < count; ++i)
		if (strcmp(name, names[i]) == 0)
			return i;
	return -1;
}

const char *pool_cushion_model_name(pool_cushion_model model) {
	return name_of(cushion_names, COUNT(cushion_names), (int)model);
}
const char *pool_ball_friction_model_name(pool_ball_friction_model model) {
	return name_of(ball_friction_names, COUNT(ball_friction_names), (int)model);
}
const char *pool_squirt_model_name(pool_squirt_model model) {
	return name_of(squirt_names, COUNT(squirt_names), (int)model);
}

pool_models pool_default_models(void) {
	// The measured laws (docs/physics.md "Models"): Mathavan 2010's cushion rebounds 0.90-0.95 of
	// a rolling ball's speed as measured tables do, Alciatore's throw falls with speed as Marlow
	// measured it (a break's rack opens: docs/measurements.md "Breaks").
	return (pool_models){POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_ALCIATORE, POOL_SQUIRT_NONE};
}

pool_models pool_thesis_models(void) {
	return (pool_models){POOL_CUSHION_PETIT, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_NONE};
}

static const char *const preset_names[] = {"default", "thesis"};

const char *pool_models_preset_name(int i) {
	return i >= 0 && i < COUNT(preset_names) ? preset_names[i] : NULL;
}

pool_result pool_models_preset(const char *name, pool_models *models) {
	if (!name || !models)
		return POOL_ERR_INVALID_ARGUMENT;
	switch (value_of(preset_names, COUNT(preset_names), name)) {
	case 0: *models = pool_default_models(); return POOL_OK;
	case 1: *models = pool_thesis_models(); return POOL_OK;
	default: return POOL_ERR_UNKNOWN_PRESET;
	}
}

int pool_cushion_model_from_name(const char *name) {
	return value_of(cushion_names, COUNT(cushion_names), name);
}
int pool_ball_friction_model_from_name(const char *name) {
	return value_of(ball_friction_names, COUNT(ball_friction_names), name);
}
int pool_squirt_model_from_name(const char *name) {
	return value_of(squirt_names, COUNT(squirt_names), name);
}

pool_result pool_models_validate(const pool_models *m, pool_error *error) {
	if ((int)m->cushion < 0 || (int)m->cushion >= COUNT(cushion_names))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "models.cushion: unknown model %d",
		                      (int)m->cushion);
	if ((int)m->ball_ball_friction < 0 || (int)m->ball_ball_friction >= COUNT(ball_friction_names))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "models.ball_ball_friction: unknown model %d",
		                      (int)m->ball_ball_friction);
	if ((int)m->squirt < 0 || (int)m->squirt >= COUNT(squirt_names))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "models.squirt: unknown model %d",
		                      (int)m->squirt);
	return POOL_OK;
}
