// Kinds and names of the models and of the model sets; the scenario parser (scenario.c) reads
// "models" with them, the commands' --models options apply them, and the writers write them.
#include "models_json.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

// Enumerations of models are small; this bounds the search for their names.
#define POOL_MAX_MODELS_PER_KIND 16

const char *const pool_model_kinds[] = {"cushion", "ball_ball_friction", "squirt", NULL};

// One kind: the library's name functions behind one signature, and where the value lives.
typedef struct model_kind {
	const char *key;
	const char *(*name)(int value);
	int (*from_name)(const char *name);
} model_kind;

static const char *cushion_name(int m) { return pool_cushion_model_name((pool_cushion_model)m); }
static const char *friction_name(int m) {
	return pool_ball_friction_model_name((pool_ball_friction_model)m);
}
static const char *squirt_name(int m) { return pool_squirt_model_name((pool_squirt_model)m); }

static const model_kind kinds[] = {
	{"cushion", cushion_name, pool_cushion_model_from_name},
	{"ball_ball_friction", friction_name, pool_ball_friction_model_from_name},
	{"squirt", squirt_name, pool_squirt_model_from_name},
};
#define KIND_COUNT (sizeof kinds / sizeof kinds[0])

static const model_kind *find_kind(const char *key) {
	for (size_t i = 0; key && i < KIND_COUNT; ++i)
		if (strcmp(kinds[i].key, key) == 0)
			return &kinds[i];
	return NULL;
}

int pool_models_set(pool_models *models, const char *kind, const char *name) {
	const model_kind *k = find_kind(kind);
	if (!k)
		return -1;
	int value = name ? k->from_name(name) : -1;
	if (value < 0)
		return -2;
	if (k == &kinds[0])
		models->cushion = (pool_cushion_model)value;
	else if (k == &kinds[1])
		models->ball_ball_friction = (pool_ball_friction_model)value;
	else
		models->squirt = (pool_squirt_model)value;
	return 0;
}

// Appends ", text" (no comma first) if it fits; false once the list is cut.
static bool append(char *out, size_t size, size_t *used, const char *text) {
	int n = snprintf(out + *used, size - *used, "%s%s", *used ? ", " : "", text);
	if (n < 0 || (size_t)n >= size - *used) {
		out[*used] = '\0';
		return false;
	}
	*used += (size_t)n;
	return true;
}

void pool_model_names(const char *kind, char *out, size_t size) {
	size_t used = 0;
	out[0] = '\0';
	const model_kind *k = find_kind(kind);
	if (!k) {
		for (size_t i = 0; i < KIND_COUNT; ++i)
			if (!append(out, size, &used, kinds[i].key))
				return;
		return;
	}
	// A value is a model when its name reads back as itself (the library's one list of names).
	for (int m = 0; m < POOL_MAX_MODELS_PER_KIND; ++m) {
		const char *name = k->name(m);
		if (name && k->from_name(name) == m && !append(out, size, &used, name))
			return;
	}
}

void pool_model_set_names(char *out, size_t size) {
	size_t used = 0;
	out[0] = '\0';
	for (int i = 0; pool_models_preset_name(i); ++i)
		if (!append(out, size, &used, pool_models_preset_name(i)))
			return;
}

bool pool_models_apply(pool_models *models, const char *part) {
	if (!part)
		return false;
	if (pool_models_preset(part, models) == POOL_OK)
		return true;
	for (size_t i = 0; i < KIND_COUNT; ++i)
		if (pool_models_set(models, kinds[i].key, part) == 0)
			return true;
	return false;
}

int pool_models_parse_spec(pool_models *models, const char *spec, char *err, size_t err_size) {
	char copy[256];
	if (!spec || !spec[0] || strlen(spec) >= sizeof copy) {
		snprintf(err, err_size, "%s", !spec || !spec[0] ? "empty" : "longer than 255 bytes");
		return -1;
	}
	snprintf(copy, sizeof copy, "%s", spec);
	pool_models m = *models;
	for (char *part = copy;;) {
		char *plus = strchr(part, '+');
		if (plus)
			*plus = '\0';
		if (!pool_models_apply(&m, part)) {
			char sets[64], names[192];
			size_t used = 0;
			pool_model_set_names(sets, sizeof sets);
			names[0] = '\0';
			for (size_t i = 0; i < KIND_COUNT; ++i) {
				char one[64];
				pool_model_names(kinds[i].key, one, sizeof one);
				if (!append(names, sizeof names, &used, one))
					break;
			}
			snprintf(err, err_size, "'%.60s' is no model set (%s) nor model (%s)", part, sets, names);
			return -1;
		}
		if (!plus)
			break;
		part = plus + 1;
	}
	*models = m;
	return 0;
}

// A value out of range (only a def the library would refuse has one) is named "unknown" by the
// library, which the parser refuses with the field named; NULL would be written as null.
static void write_name(pool_jw *w, const char *key, const char *name) {
	pool_jw_key(w, key);
	if (name)
		pool_jw_string(w, name);
	else
		pool_jw_number(w, NAN);
}

void pool_jw_models(pool_jw *w, const pool_models *models) {
	pool_jw_key(w, "models");
	pool_jw_object(w, true);
	write_name(w, "cushion", pool_cushion_model_name(models->cushion));
	write_name(w, "ball_ball_friction", pool_ball_friction_model_name(models->ball_ball_friction));
	write_name(w, "squirt", pool_squirt_model_name(models->squirt));
	pool_jw_end(w, '}');
}
