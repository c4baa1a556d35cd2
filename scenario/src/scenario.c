// Parsing and validation of libpool-scenario/1 documents (docs/interfaces.md). The JSON layer checks
// syntax, types, unknown fields and number ranges; the physical rules (table and parameter
// ranges, overlaps, off-table balls, strike limits) are libpool's own validators, whose messages
// already name the field, so the rules live in one place.
#include "pool/scenario.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "game_json.h"
#include "models_json.h"
#include "read_input.h"
#include "text_escape.h"

static const char *const scenario_format = POOL_SCENARIO_FORMAT;

typedef struct parse_ctx {
	char *err;
	size_t err_size;
} parse_ctx;

static int fail(parse_ctx *ctx, const char *format, ...) {
	if (ctx->err && ctx->err_size > 0) {
		va_list args;
		va_start(args, format);
		vsnprintf(ctx->err, ctx->err_size, format, args);
		va_end(args);
	}
	return -1;
}

// A libpool message normally starts with the field path ("params.mu_slide: ..."); when it does
// not, prefix the path of the object we handed over.
static bool starts_with_path(const char *message, const char *path) {
	size_t n = strlen(path);
	return strncmp(message, path, n) == 0 &&
	       (message[n] == '.' || message[n] == ':' || message[n] == '[');
}

// The library names the fields of its pool_sim_def "def.airborne", "def.max_time"...; a scenario
// file holds them in "options".
static const char *json_field_names(const char *message, char *out, size_t size) {
	static const char from[] = "def.", to[] = "options.";
	size_t n = 0;
	for (const char *m = message; *m && n + 1 < size;) {
		if (strncmp(m, from, sizeof from - 1) == 0 && (m == message || m[-1] == ' ' || m[-1] == '(') &&
		    n + sizeof to < size) {
			memcpy(out + n, to, sizeof to - 1);
			n += sizeof to - 1;
			m += sizeof from - 1;
		} else {
			out[n++] = *m++;
		}
	}
	out[n] = '\0';
	return out;
}

static int fail_lib(parse_ctx *ctx, const char *path, pool_result code, const pool_error *e) {
	static const char *const roots[] = {"table", "params", "balls", "strike", "options", "models",
	                                    NULL};
	char renamed[sizeof e->message + 64];
	const char *message = json_field_names(e->message[0] ? e->message : pool_result_str(code), renamed,
	                                       sizeof renamed);
	if (starts_with_path(message, path))
		return fail(ctx, "%s", message);
	for (const char *const *root = roots; *root; ++root)
		if (starts_with_path(message, *root))
			return fail(ctx, "%s", message);
	return fail(ctx, "%s: %s", path, message);
}

// Every key of obj must be one of allowed (NULL-terminated).
static int check_fields(parse_ctx *ctx, json_t *obj, const char *path, const char *const *allowed) {
	const char *key;
	json_t *value;
	json_object_foreach(obj, key, value) {
		bool known = false;
		for (const char *const *a = allowed; *a; ++a)
			if (strcmp(key, *a) == 0)
				known = true;
		if (!known) {
			// An empty key would give a message with no field name at all.
			if (!key[0])
				return fail(ctx, "%s: unknown field \"\"", path[0] ? path : "(document)");
			// The key is the file's text: escaped and cut, so it cannot drive the terminal.
			char shown[POOL_ESCAPE_SHORT];
			pool_escape_str(shown, sizeof shown, key);
			if (path[0])
				return fail(ctx, "%s.%s: unknown field", path, shown);
			return fail(ctx, "%s: unknown field", shown);
		}
	}
	return 0;
}

static int get_number(parse_ctx *ctx, json_t *value, const char *path, double *out) {
	if (!json_is_number(value))
		return fail(ctx, "%s: must be a number", path);
	double x = json_number_value(value);
	if (!isfinite(x))
		return fail(ctx, "%s: must be a finite number", path);
	if (fabs(x) > POOL_SCENARIO_MAX_ABS)
		return fail(ctx, "%s: %g is too large (limit %g)", path, x, POOL_SCENARIO_MAX_ABS);
	*out = x;
	return 0;
}

static int get_int(parse_ctx *ctx, json_t *value, const char *path, int64_t lo, int64_t hi, int64_t *out) {
	if (!json_is_integer(value))
		return fail(ctx, "%s: must be an integer", path);
	json_int_t x = json_integer_value(value);
	if (x < lo || x > hi)
		return fail(ctx, "%s: %lld is out of range [%lld, %lld]", path, (long long)x, (long long)lo,
		            (long long)hi);
	*out = (int64_t)x;
	return 0;
}

// An array of min_n..3 numbers; missing components stay as given in *out.
static int get_vec(parse_ctx *ctx, json_t *value, const char *path, size_t min_n, pool_vec3 *out) {
	if (!json_is_array(value) || json_array_size(value) < min_n || json_array_size(value) > 3) {
		if (min_n == 3)
			return fail(ctx, "%s: must be an array of 3 numbers", path);
		return fail(ctx, "%s: must be an array of %zu or 3 numbers", path, min_n);
	}
	double c[3] = {out->x, out->y, out->z};
	for (size_t i = 0; i < json_array_size(value); ++i) {
		char sub[96];
		snprintf(sub, sizeof sub, "%s[%zu]", path, i);
		if (get_number(ctx, json_array_get(value, i), sub, &c[i]))
			return -1;
	}
	out->x = c[0];
	out->y = c[1];
	out->z = c[2];
	return 0;
}

// "table": a preset (its balls and cloth become the params' defaults: *preset_name), then any
// field overriding it; the pocket model by name, cut angles in degrees.
static int parse_table(parse_ctx *ctx, json_t *table, pool_table_def *def, const char **preset_name) {
	static const char *const fields[] = {"preset", "length", "width", "cushion_height", "corner_mouth",
	                                     "side_mouth", "pockets", "corner_cut_angle", "side_cut_angle",
	                                     "corner_jaw_radius", "side_jaw_radius", "corner_shelf", "side_shelf",
	                                     "corner_hole_radius", "side_hole_radius", NULL};
	*def = pool_default_table_def();
	*preset_name = NULL;
	if (!table)
		return 0;
	// "table": "wpa-8ft" is short for {"preset": "wpa-8ft"}.
	if (json_is_string(table)) {
		if (pool_table_preset(json_string_value(table), def) != POOL_OK) {
			char shown[POOL_ESCAPE_SHORT];
			pool_escape_text(shown, sizeof shown, json_string_value(table), json_string_length(table));
			return fail(ctx, "table: unknown preset \"%s\" (wpa-9ft, wpa-8ft, wpa-7ft, snooker, carom)", shown);
		}
		return 0;
	}
	if (!json_is_object(table))
		return fail(ctx, "table: must be a preset name or an object");
	if (check_fields(ctx, table, "table", fields))
		return -1;
	json_t *preset = json_object_get(table, "preset");
	if (preset) {
		if (!json_is_string(preset))
			return fail(ctx, "table.preset: must be a string");
		if (pool_table_preset(json_string_value(preset), def) != POOL_OK) {
			char shown[POOL_ESCAPE_SHORT];
			pool_escape_text(shown, sizeof shown, json_string_value(preset), json_string_length(preset));
			return fail(ctx, "table.preset: unknown preset \"%s\" (wpa-9ft, wpa-8ft, wpa-7ft, snooker, carom)", shown);
		}
		*preset_name = json_string_value(preset);
	}
	json_t *pockets = json_object_get(table, "pockets");
	if (pockets) {
		const int model = json_is_string(pockets) ? pool_pockets_model_from_name(json_string_value(pockets)) : -1;
		if (model < 0)
			return fail(ctx, "table.pockets: must be \"jaws\", \"mouth_lines\" or \"none\"");
		def->pockets = (pool_pockets_model)model;
	}
	struct {
		const char *name;
		double *field;
		double scale;
	} overrides[] = {
		{"length", &def->length, 1.0},
		{"width", &def->width, 1.0},
		{"cushion_height", &def->cushion_height, 1.0},
		{"corner_mouth", &def->corner_mouth, 1.0},
		{"side_mouth", &def->side_mouth, 1.0},
		{"corner_cut_angle", &def->corner_cut_angle, POOL_DEGREE},
		{"side_cut_angle", &def->side_cut_angle, POOL_DEGREE},
		{"corner_jaw_radius", &def->corner_jaw_radius, 1.0},
		{"side_jaw_radius", &def->side_jaw_radius, 1.0},
		{"corner_shelf", &def->corner_shelf, 1.0},
		{"side_shelf", &def->side_shelf, 1.0},
		{"corner_hole_radius", &def->corner_hole_radius, 1.0},
		{"side_hole_radius", &def->side_hole_radius, 1.0},
	};
	for (size_t i = 0; i < sizeof overrides / sizeof overrides[0]; ++i) {
		json_t *v = json_object_get(table, overrides[i].name);
		char path[64];
		snprintf(path, sizeof path, "table.%s", overrides[i].name);
		double x = 0.0;
		if (v && get_number(ctx, v, path, &x))
			return -1;
		if (v)
			*overrides[i].field = x * overrides[i].scale;
	}
	pool_error e = {{0}};
	pool_result r = pool_table_def_validate(def, &e);
	if (r != POOL_OK)
		return fail_lib(ctx, "table", r, &e);
	return 0;
}

static int parse_params(parse_ctx *ctx, json_t *params, const char *preset, pool_params *p) {
	// The preset's balls and cloth, else the defaults.
	if (!preset || pool_params_preset(preset, p) != POOL_OK)
		*p = pool_default_params();
	if (!params)
		return 0;
	if (!json_is_object(params))
		return fail(ctx, "params: must be an object");
	struct {
		const char *name;
		double *field;
	} names[] = {
		{"g", &p->g},
		{"mu_slide", &p->mu_slide},
		{"mu_roll", &p->mu_roll},
		{"mu_spin", &p->mu_spin},
		{"mu_ball", &p->mu_ball},
		{"e_ball", &p->e_ball},
		{"mu_cushion", &p->mu_cushion},
		{"e_cushion", &p->e_cushion},
		{"mu_table", &p->mu_table},
		{"e_table", &p->e_table},
		{"ball_radius", &p->ball_radius},
		{"ball_mass", &p->ball_mass},
		{"cue_mass", &p->cue_mass},
		{"throw_a", &p->throw_a},
		{"throw_b", &p->throw_b},
		{"throw_c", &p->throw_c},
		{"cue_end_mass", &p->cue_end_mass},
		{"e_cushion_mathavan", &p->e_cushion_mathavan},
		{"mu_cushion_mathavan", &p->mu_cushion_mathavan},
	};
	size_t n = sizeof names / sizeof names[0];
	const char *key;
	json_t *value;
	json_object_foreach(params, key, value) {
		size_t i = 0;
		while (i < n && strcmp(key, names[i].name) != 0)
			++i;
		if (i == n && !key[0])
			return fail(ctx, "params: unknown field \"\"");
		if (i == n) {
			char shown[POOL_ESCAPE_SHORT];
			pool_escape_str(shown, sizeof shown, key);
			return fail(ctx, "params.%s: unknown field", shown);
		}
		char path[64];
		snprintf(path, sizeof path, "params.%s", key);
		if (get_number(ctx, value, path, names[i].field))
			return -1;
	}
	pool_error e = {{0}};
	pool_result r = pool_params_validate(p, &e);
	if (r != POOL_OK)
		return fail_lib(ctx, "params", r, &e);
	return 0;
}

static int parse_options(parse_ctx *ctx, json_t *options, pool_sim_def *def) {
	static const char *const fields[] = {"airborne", "max_time", "max_events", NULL};
	if (!options)
		return 0;
	if (!json_is_object(options))
		return fail(ctx, "options: must be an object");
	if (check_fields(ctx, options, "options", fields))
		return -1;
	json_t *v = json_object_get(options, "airborne");
	if (v) {
		if (!json_is_boolean(v))
			return fail(ctx, "options.airborne: must be true or false");
		def->airborne = json_is_true(v);
	}
	v = json_object_get(options, "max_time");
	if (v) {
		if (get_number(ctx, v, "options.max_time", &def->max_time))
			return -1;
		if (!(def->max_time > 0.0))
			return fail(ctx, "options.max_time: must be > 0");
	}
	v = json_object_get(options, "max_events");
	if (v) {
		int64_t n = 0;
		if (get_int(ctx, v, "options.max_events", 1, INT32_MAX, &n))
			return -1;
		def->max_events = (int)n;
	}
	return 0;
}

// A model set by name into *out ("default", "thesis"), or the message naming `path`.
static int parse_model_set(parse_ctx *ctx, json_t *name, const char *path, pool_models *out) {
	if (!json_is_string(name))
		return fail(ctx, "%s: must be a string", path);
	if (pool_models_preset(json_string_value(name), out) != POOL_OK) {
		char shown[POOL_ESCAPE_SHORT], known[128];
		pool_escape_text(shown, sizeof shown, json_string_value(name), json_string_length(name));
		pool_model_set_names(known, sizeof known);
		return fail(ctx, "%s: unknown model set \"%s\" (%s)", path, shown, known);
	}
	return 0;
}

// "models" (docs/physics.md "Models"): a model set by name ("thesis"), or an object whose "set"
// (default "default") is overridden kind by kind, each value a model name the library knows
// (models_json.c). Missing, it is the library's defaults.
static int parse_models(parse_ctx *ctx, json_t *models, pool_models *out) {
	*out = pool_default_models();
	if (!models)
		return 0;
	if (json_is_string(models))
		return parse_model_set(ctx, models, "models", out);
	if (!json_is_object(models))
		return fail(ctx, "models: must be a model set name or an object");
	static const char *const keys[] = {"set", "cushion", "ball_ball_friction", "squirt", NULL};
	if (check_fields(ctx, models, "models", keys))
		return -1;
	json_t *set = json_object_get(models, "set");
	if (set && parse_model_set(ctx, set, "models.set", out))
		return -1;
	for (const char *const *kind = pool_model_kinds; *kind; ++kind) {
		json_t *v = json_object_get(models, *kind);
		if (!v)
			continue;
		if (!json_is_string(v))
			return fail(ctx, "models.%s: must be a string", *kind);
		// (jansson refuses a NUL inside a string, so the C string is the whole name.)
		if (pool_models_set(out, *kind, json_string_value(v)) != 0) {
			char shown[POOL_ESCAPE_SHORT], known[128];
			pool_escape_text(shown, sizeof shown, json_string_value(v), json_string_length(v));
			pool_model_names(*kind, known, sizeof known);
			return fail(ctx, "models.%s: unknown model \"%s\" (%s)", *kind, shown, known);
		}
	}
	return 0;
}

// The state a ball starts in follows from its velocities (the library re-derives it; this copy
// is for callers that read the scenario without a simulation, such as the comparison plugins).
static pool_motion derive_motion(const pool_ball_state *b, double radius) {
	if (b->pos.z > radius + 1e-9 || b->vel.z != 0.0)
		return POOL_MOTION_AIRBORNE;
	// Slip of the contact point: u = v + R k x w.
	double ux = b->vel.x - radius * b->omega.y;
	double uy = b->vel.y + radius * b->omega.x;
	if (ux != 0.0 || uy != 0.0)
		return POOL_MOTION_SLIDING;
	if (b->vel.x != 0.0 || b->vel.y != 0.0)
		return POOL_MOTION_ROLLING;
	if (b->omega.z != 0.0)
		return POOL_MOTION_SPINNING;
	return POOL_MOTION_STATIONARY;
}

static int parse_ball(parse_ctx *ctx, json_t *ball, size_t i, double radius, pool_ball_state *out) {
	static const char *const fields[] = {"id", "pos", "vel", "omega", NULL};
	char path[64], sub[96];
	snprintf(path, sizeof path, "balls[%zu]", i);
	if (!json_is_object(ball))
		return fail(ctx, "%s: must be an object", path);
	if (check_fields(ctx, ball, path, fields))
		return -1;
	memset(out, 0, sizeof *out);
	json_t *id = json_object_get(ball, "id");
	if (!id)
		return fail(ctx, "%s.id: missing", path);
	int64_t id_value = 0;
	snprintf(sub, sizeof sub, "%s.id", path);
	if (get_int(ctx, id, sub, INT32_MIN, INT32_MAX, &id_value))
		return -1;
	out->id = (int32_t)id_value;
	json_t *pos = json_object_get(ball, "pos");
	if (!pos)
		return fail(ctx, "%s.pos: missing", path);
	snprintf(sub, sizeof sub, "%s.pos", path);
	out->pos.z = radius;
	if (get_vec(ctx, pos, sub, 2, &out->pos))
		return -1;
	json_t *vel = json_object_get(ball, "vel");
	snprintf(sub, sizeof sub, "%s.vel", path);
	if (vel && get_vec(ctx, vel, sub, 2, &out->vel))
		return -1;
	json_t *omega = json_object_get(ball, "omega");
	snprintf(sub, sizeof sub, "%s.omega", path);
	if (omega && get_vec(ctx, omega, sub, 3, &out->omega))
		return -1;
	out->motion = derive_motion(out, radius);
	return 0;
}

static int parse_strike(parse_ctx *ctx, json_t *strike, pool_scenario *s) {
	static const char *const fields[] = {"ball", "speed", "phi", "theta", "a", "b", NULL};
	if (!json_is_object(strike))
		return fail(ctx, "strike: must be an object");
	if (check_fields(ctx, strike, "strike", fields))
		return -1;
	json_t *ball = json_object_get(strike, "ball");
	if (!ball)
		return fail(ctx, "strike.ball: missing");
	int64_t id = 0;
	if (get_int(ctx, ball, "strike.ball", INT32_MIN, INT32_MAX, &id))
		return -1;
	s->strike_ball = (int)id;
	s->written = (pool_batch_strike){.ball = (int32_t)id};
	int found = -1;
	for (int i = 0; i < s->ball_count; ++i)
		if (s->balls[i].id == id)
			found = i;
	if (found < 0)
		return fail(ctx, "strike.ball: no ball has id %lld", (long long)id);
	json_t *speed = json_object_get(strike, "speed");
	if (!speed)
		return fail(ctx, "strike.speed: missing");
	memset(&s->strike, 0, sizeof s->strike);
	if (get_number(ctx, speed, "strike.speed", &s->strike.speed))
		return -1;
	s->written.speed = s->strike.speed;
	struct {
		const char *name;
		double *field;
		double *written; // the value as the file gives it
		double scale;
	} optional[] = {
		{"phi", &s->strike.phi, &s->written.phi, POOL_DEGREE},
		{"theta", &s->strike.theta, &s->written.theta, POOL_DEGREE},
		{"a", &s->strike.a, &s->written.a, 1.0},
		{"b", &s->strike.b, &s->written.b, 1.0},
	};
	for (size_t i = 0; i < sizeof optional / sizeof optional[0]; ++i) {
		json_t *v = json_object_get(strike, optional[i].name);
		char path[32];
		snprintf(path, sizeof path, "strike.%s", optional[i].name);
		double x = 0.0;
		if (v && get_number(ctx, v, path, &x))
			return -1;
		// The library checks the same range in radians; say it in the file's unit.
		if (optional[i].field == &s->strike.theta && !(x >= 0.0 && x < 90.0))
			return fail(ctx, "strike.theta: must be in [0, 90) degrees");
		*optional[i].written = x;
		*optional[i].field = x * optional[i].scale;
	}
	s->has_strike = true;
	return 0;
}

// A library message about "balls[0]" (a ball checked alone in a simulation of its own) is about
// balls[index] of the file.
static int fail_lib_ball(parse_ctx *ctx, int index, pool_result code, const pool_error *e) {
	const char *message = e->message[0] ? e->message : pool_result_str(code);
	static const char prefix[] = "balls[0]";
	if (strncmp(message, prefix, sizeof prefix - 1) == 0)
		return fail(ctx, "balls[%d]%s", index, message + sizeof prefix - 1);
	char path[32];
	snprintf(path, sizeof path, "balls[%d]", index);
	return fail_lib(ctx, path, code, e);
}

// The scenario's strike on sim (its struck ball in place): the cue's parameters with the
// library's own rules, then the strike itself; "strike" names what the library refused.
static int check_strike(parse_ctx *ctx, pool_sim *sim, const pool_scenario *s) {
	pool_error e = {{0}};
	pool_vec3 vel, omega;
	pool_result r = pool_strike_velocities(&s->def.params, &s->strike, &vel, &omega, &e);
	if (r == POOL_OK) {
		memset(&e, 0, sizeof e);
		r = pool_sim_strike(sim, s->strike_ball, &s->strike, &e);
	}
	return r == POOL_OK ? 0 : fail_lib(ctx, "strike", r, &e);
}

// Airborne scenarios (options.airborne = true): the rules the library has for planar balls are
// applied to each ball's
// projection on the cloth, one ball per throw-away planar simulation (finite numbers, speed
// limits, off the table), and the 3D rules here: a centre below z = R (beyond
// POOL_TOUCH_TOLERANCE) is under the cloth, balls may not interpenetrate in 3D (a ball above
// another is fine), the 3D speed is limited like the horizontal one, and the struck ball must be
// at rest on the cloth (pool_sim_strike's rule). A centre within the tolerance below z = R is
// put on the cloth (z = R).
static int check_airborne(parse_ctx *ctx, pool_scenario *s) {
	pool_sim_def planar = s->def;
	planar.airborne = false;
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	pool_result r = pool_sim_create(&planar, &sim, &e);
	if (r != POOL_OK)
		return fail_lib(ctx, "options", r, &e);
	const double radius = s->def.params.ball_radius;
	int status = 0;
	for (int j = 0; j < s->ball_count && status == 0; ++j) {
		pool_ball_state *b = &s->balls[j];
		if (b->pos.z < radius - POOL_TOUCH_TOLERANCE) {
			status = fail(ctx, "balls[%d].pos: below the cloth (z = %.9g m, the centre of a ball on the "
			              "cloth is at z = R = %.9g m)", j, b->pos.z, radius);
			break;
		}
		if (b->pos.z < radius)
			b->pos.z = radius;
		const double speed = sqrt(b->vel.x * b->vel.x + b->vel.y * b->vel.y + b->vel.z * b->vel.z);
		if (speed > POOL_MAX_SPEED) {
			status = fail(ctx, "balls[%d].vel: speed above the %g m/s limit (POOL_MAX_SPEED)", j,
			              POOL_MAX_SPEED);
			break;
		}
		for (int i = 0; i < j; ++i) {
			if (s->balls[i].id == b->id) {
				status = fail(ctx, "balls[%d].id: duplicate id %d (also balls[%d])", j, (int)b->id, i);
				break;
			}
			double dx = b->pos.x - s->balls[i].pos.x;
			double dy = b->pos.y - s->balls[i].pos.y;
			double dz = b->pos.z - s->balls[i].pos.z;
			double depth = 2.0 * radius - sqrt(dx * dx + dy * dy + dz * dz);
			if (depth > POOL_TOUCH_TOLERANCE) {
				status = fail(ctx, "balls[%d].pos: overlaps ball %d by %.3g m", j, (int)s->balls[i].id, depth);
				break;
			}
		}
		if (status)
			break;
		pool_ball_state projected = *b;
		projected.pos.z = radius;
		projected.vel.z = 0.0;
		memset(&e, 0, sizeof e);
		r = pool_sim_reset(sim, &planar, &e);
		if (r == POOL_OK)
			r = pool_sim_add_ball(sim, &projected, &e);
		if (r != POOL_OK)
			status = fail_lib_ball(ctx, j, r, &e);
		b->motion = derive_motion(b, radius);
	}
	if (status == 0 && s->has_strike) {
		const pool_ball_state *b = NULL;
		for (int i = 0; i < s->ball_count; ++i)
			if (s->balls[i].id == s->strike_ball)
				b = &s->balls[i];
		if (b->pos.z > radius + POOL_TOUCH_TOLERANCE || b->vel.z != 0.0) {
			status = fail(ctx, "strike.ball: ball %d must be at rest on the cloth to be struck",
			              (int)s->strike_ball);
		} else {
			pool_ball_state projected = *b;
			projected.pos.z = radius;
			memset(&e, 0, sizeof e);
			r = pool_sim_reset(sim, &planar, &e);
			if (r == POOL_OK)
				r = pool_sim_add_ball(sim, &projected, &e);
			status = r == POOL_OK ? check_strike(ctx, sim, s) : fail_lib(ctx, "strike", r, &e);
		}
	}
	pool_sim_destroy(sim);
	return status;
}

// Checks the balls against each other with the library's own rules, by building a throw-away
// simulation: pool_sim_add_ball rejects duplicates, overlaps and off-table balls and names the
// ball "balls[i]" with i its insertion index, which is also its index in the file.
static int check_with_sim(parse_ctx *ctx, const pool_scenario *s) {
	// The def as a whole first (e.g. a ball too big for the table), then the balls.
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	pool_result r = pool_sim_create(&s->def, &sim, &e);
	if (r != POOL_OK)
		return fail_lib(ctx, "options", r, &e);
	// Overlaps here, so the message has the documented form
	// "balls[2].pos: overlaps ball 1 by 0.003 m" whatever the library's wording.
	double radius = s->def.params.ball_radius;
	for (int j = 0; j < s->ball_count; ++j) {
		for (int i = 0; i < j; ++i) {
			if (s->balls[i].id == s->balls[j].id) {
				pool_sim_destroy(sim);
				return fail(ctx, "balls[%d].id: duplicate id %d (also balls[%d])", j,
				            (int)s->balls[j].id, i);
			}
			double dx = s->balls[j].pos.x - s->balls[i].pos.x;
			double dy = s->balls[j].pos.y - s->balls[i].pos.y;
			double dz = s->balls[j].pos.z - s->balls[i].pos.z;
			double depth = 2.0 * radius - sqrt(dx * dx + dy * dy + dz * dz);
			if (depth > POOL_TOUCH_TOLERANCE) {
				pool_sim_destroy(sim);
				return fail(ctx, "balls[%d].pos: overlaps ball %d by %.3g m", j,
				            (int)s->balls[i].id, depth);
			}
		}
	}
	int status = 0;
	for (int i = 0; i < s->ball_count && status == 0; ++i) {
		memset(&e, 0, sizeof e);
		r = pool_sim_add_ball(sim, &s->balls[i], &e);
		if (r != POOL_OK) {
			char path[32];
			snprintf(path, sizeof path, "balls[%d]", i);
			status = fail_lib(ctx, path, r, &e);
		}
	}
	if (status == 0 && s->has_strike)
		status = check_strike(ctx, sim, s);
	pool_sim_destroy(sim);
	return status;
}

// "game" (docs/interfaces.md "Games"): the rules judge the struck shot, on a table of their balls.
static int parse_game(parse_ctx *ctx, json_t *game, pool_scenario *s) {
	if (!game)
		return 0;
	if (pool_game_json_parse(game, "game", &s->game, ctx->err, ctx->err_size))
		return -1;
	pool_error e;
	if (pool_game_check_balls(&s->game, s->balls, s->ball_count, &e) != POOL_OK)
		return fail(ctx, "%s", e.message);
	if (!s->has_strike)
		return fail(ctx, "game: the rules judge a struck shot: the scenario needs a strike");
	s->has_game = true;
	return 0;
}

static int parse_document(parse_ctx *ctx, json_t *root, pool_scenario *s) {
	static const char *const fields[] = {"format", "name", "description", "table", "params",
	                                     "balls", "strike", "options", "models", "game", NULL};
	if (!json_is_object(root))
		return fail(ctx, "(document): must be a JSON object");
	if (check_fields(ctx, root, "", fields))
		return -1;
	json_t *format = json_object_get(root, "format");
	if (!format)
		return fail(ctx, "format: missing (expected \"%s\")", scenario_format);
	if (!json_is_string(format) || strcmp(json_string_value(format), scenario_format) != 0)
		return fail(ctx, "format: expected \"%s\"", scenario_format);
	const char *text_fields[] = {"name", "description"};
	for (int i = 0; i < 2; ++i) {
		json_t *v = json_object_get(root, text_fields[i]);
		if (v && !json_is_string(v))
			return fail(ctx, "%s: must be a string", text_fields[i]);
	}

	s->def = pool_default_sim_def();
	const char *preset = NULL;
	if (parse_table(ctx, json_object_get(root, "table"), &s->def.table, &preset))
		return -1;
	if (parse_params(ctx, json_object_get(root, "params"), preset, &s->def.params))
		return -1;
	if (parse_options(ctx, json_object_get(root, "options"), &s->def))
		return -1;
	if (parse_models(ctx, json_object_get(root, "models"), &s->def.models))
		return -1;

	json_t *balls = json_object_get(root, "balls");
	if (!balls)
		return fail(ctx, "balls: missing");
	if (!json_is_array(balls) || json_array_size(balls) == 0)
		return fail(ctx, "balls: must be a non-empty array");
	if (json_array_size(balls) > POOL_SCENARIO_MAX_BALLS)
		return fail(ctx, "balls: too many balls (limit %d)", POOL_SCENARIO_MAX_BALLS);
	s->balls = calloc(json_array_size(balls), sizeof *s->balls);
	if (!s->balls)
		return fail(ctx, "balls: out of memory");
	for (size_t i = 0; i < json_array_size(balls); ++i) {
		if (parse_ball(ctx, json_array_get(balls, i), i, s->def.params.ball_radius, &s->balls[i]))
			return -1;
		s->ball_count = (int)i + 1;
	}

	json_t *strike = json_object_get(root, "strike");
	if (strike && parse_strike(ctx, strike, s))
		return -1;
	if (parse_game(ctx, json_object_get(root, "game"), s))
		return -1;
	return s->def.airborne ? check_airborne(ctx, s) : check_with_sim(ctx, s);
}

int pool_scenario_parse(const char *json, size_t length, pool_scenario *scenario, char *err,
                        size_t err_size) {
	parse_ctx ctx = {err, err_size};
	memset(scenario, 0, sizeof *scenario);
	if (err && err_size)
		err[0] = '\0';
	json_error_t jerr;
	json_t *root = json_loadb(json, length, JSON_REJECT_DUPLICATES, &jerr);
	if (!root) {
		// jansson's text may quote the offending input ("invalid token near '...'").
		char shown[POOL_ESCAPE_LONG];
		pool_escape_str(shown, sizeof shown, jerr.text);
		return fail(&ctx, "(document): malformed JSON at line %d, column %d: %s", jerr.line,
		            jerr.column, shown);
	}
	int status = parse_document(&ctx, root, scenario);
	json_decref(root);
	if (status != 0)
		pool_scenario_free(scenario);
	return status;
}

int pool_scenario_load_file(const char *path, pool_scenario *scenario, char *err,
                            size_t err_size) {
	return pool_scenario_load_file_limit(path, POOL_INPUT_DEFAULT_MAX, scenario, err, err_size);
}

int pool_scenario_load_file_limit(const char *path, size_t max_bytes, pool_scenario *scenario,
                                  char *err, size_t err_size) {
	memset(scenario, 0, sizeof *scenario);
	char *data = NULL;
	size_t length = 0;
	char local[8];
	if (!err || err_size == 0)
		err = local, err_size = sizeof local;
	if (pool_read_input(path, max_bytes, &data, &length, err, err_size) != 0)
		return -1;
	int status = pool_scenario_parse(data, length, scenario, err, err_size);
	free(data);
	return status;
}

void pool_scenario_free(pool_scenario *scenario) {
	if (!scenario)
		return;
	free(scenario->balls);
	memset(scenario, 0, sizeof *scenario);
}

pool_result pool_scenario_setup(const pool_scenario *scenario, pool_sim **sim, pool_error *err) {
	pool_error local = {{0}};
	pool_error *e = err ? err : &local;
	e->message[0] = '\0';
	pool_result r = *sim ? pool_sim_reset(*sim, &scenario->def, e)
	                     : pool_sim_create(&scenario->def, sim, e);
	if (r != POOL_OK)
		return r;
	for (int i = 0; i < scenario->ball_count; ++i) {
		r = pool_sim_add_ball(*sim, &scenario->balls[i], e);
		if (r != POOL_OK)
			return r;
	}
	if (scenario->has_strike)
		r = pool_sim_strike(*sim, scenario->strike_ball, &scenario->strike, e);
	return r;
}
