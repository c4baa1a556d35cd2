// Named model sets for --models: the scenario's definition with some laws switched, so the
// same noise can be run under two sets and the clouds compared.
#include <stdio.h>
#include <string.h>

#include "models_json.h"
#include "study.h"

const char *sens_model_set_names(void) {
	return "default, spin-blind, thesis, mathavan2010, alciatore, endmass, petit, constant, none";
}

/// Applies one '+'-separated component to def; false when the name is unknown.
static bool apply_component(const char *name, pool_sim_def *def) {
	if (strcmp(name, "spin-blind") == 0) {
		// FastFiz's limitation measured in the 2012 work: collisions that ignore spin, i.e. no
		// tangential friction at ball-ball and ball-cushion contacts, whatever the laws: the
		// constant mu_ball and Alciatore's fit (throw_a + throw_b e^(-c v) = 0), Petit's
		// mu_cushion and Mathavan's nose friction.
		def->params.mu_ball = 0.0;
		def->params.throw_a = 0.0;
		def->params.throw_b = 0.0;
		def->params.mu_cushion = 0.0;
		def->params.mu_cushion_mathavan = 0.0;
		return true;
	}
	// "default" stands alone (the scenario as written), so here it is not the library's set.
	return strcmp(name, "default") != 0 && pool_models_apply(&def->models, name);
}

int sens_model_set_parse(const char *name, const pool_sim_def *base, sens_model_set *out,
                         char *err, size_t err_size) {
	memset(out, 0, sizeof *out);
	out->def = *base;
	if (!name[0]) {
		snprintf(err, err_size, "--models: empty model set name (%s)", sens_model_set_names());
		return -1;
	}
	if (strlen(name) >= sizeof out->name) {
		snprintf(err, err_size, "--models: model set name longer than %zu bytes", sizeof out->name - 1);
		return -1;
	}
	snprintf(out->name, sizeof out->name, "%s", name);
	if (strcmp(name, "default") == 0)
		return 0;
	char copy[sizeof out->name];
	snprintf(copy, sizeof copy, "%s", name);
	for (char *part = copy;;) {
		char *plus = strchr(part, '+');
		if (plus)
			*plus = '\0';
		if (!apply_component(part, &out->def)) {
			snprintf(err, err_size, "--models: '%.60s': unknown model set%s (%s, joined with '+')", part,
			         strcmp(part, "default") == 0 ? " part (default stands alone)" : "",
			         sens_model_set_names());
			return -1;
		}
		if (!plus)
			break;
		part = plus + 1;
	}
	return 0;
}
