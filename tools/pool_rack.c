// pool-rack: writes a libpool-scenario/1 file with a standard 8-ball or 9-ball rack and a break
// strike, so nobody has to compute triangle coordinates by hand.
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "json_writer.h"
#include "models_json.h"
#include "pool/scenario.h"

#define PROGRAM "pool-rack"
#define POOL_PI 3.14159265358979323846

// Cue speed of a firm amateur break (the ball leaves at about 1.5 times this).
#define DEFAULT_SPEED 6.0
// Neighbouring balls a tenth of a millimetre apart: a well-racked but not frozen triangle.
#define DEFAULT_GAP 1e-4

typedef struct rack_options {
	pool_rack_kind kind;
	double speed; ///< m/s, cue speed
	double gap;   ///< m, between neighbouring rack balls
	double a, b;  ///< m, tip offsets
	double phi;   ///< degrees
	double theta; ///< degrees
	bool has_phi;
	const char *table;  ///< preset name
	const char *output; ///< NULL = standard output
	bool airborne;
	pool_models models; ///< --models and --model choices, on the default models
	bool has_models;    ///< written into the scenario only when chosen
	bool help;
} rack_options;

static const char usage_text[] =
	"usage: pool-rack 8ball|9ball|snooker|carom [--speed V] [--gap G] [--spin A,B] [--phi DEG]\n"
	"                 [--theta DEG] [--table PRESET] [--airborne] [--models SET] [--model KIND=NAME ...]\n"
	"                 [-o FILE]\n"
	"\n"
	"Writes a libpool-scenario/1 file: the cue ball (id 0) on the head spot, a standard rack\n"
	"(8ball: ids 1..15, 9ball: ids 1..9) with its apex on the foot spot, and a break strike.\n"
	"snooker (the default rack of --table snooker): 15 reds (ids 1..15) behind the pink, the\n"
	"colours on their spots (ids 20 + value: yellow 22 ... black 27), the cue ball in the D.\n"
	"carom (the default of --table carom): red (id 2) on the foot spot, yellow (id 1) on the head\n"
	"spot, the cue ball 0.1524 m beside it. The break aims at the first object ball.\n"
	"\n"
	"  --speed V       cue speed in m/s (default 6)\n"
	"  --gap G         gap between neighbouring rack balls in m (default 0.0001; 0 = frozen)\n"
	"  --spin A,B      cue tip offsets in m: A right of centre, B above (default 0,0)\n"
	"  --phi DEG       aim direction in degrees from +x (default: straight at the apex)\n"
	"  --theta DEG     cue elevation in degrees (default 0)\n"
	"  --table PRESET  wpa-9ft (default), wpa-8ft, wpa-7ft, snooker or carom (with its balls)\n"
	"  --airborne      enable airborne motion in the scenario's options\n"
	"  --models SET    the scenario's \"models\": a model set, default (the measured laws) or\n"
	"                  thesis (the 2012 work's), or model names joined with '+' (thesis+endmass)\n"
	"  --model KIND=NAME  one kind of the scenario's \"models\" (repeatable, after --models):\n"
	"                  cushion=petit|mathavan2010, ball_ball_friction=constant|alciatore,\n"
	"                  squirt=none|endmass\n"
	"  -o FILE         write to FILE (atomically) instead of standard output\n"
	"  -h, --help      show this help\n";

// --model KIND=NAME: one kind of the scenario's "models" (models_json.h). Returns 0 or the usage
// error's exit status.
static int parse_model(const char *value, pool_models *models) {
	char buffer[128], known[128];
	snprintf(buffer, sizeof buffer, "%s", value);
	char *equals = strchr(buffer, '=');
	if (equals)
		*equals = '\0';
	int r = equals ? pool_models_set(models, buffer, equals + 1) : -1;
	if (r == -1) {
		pool_model_names(NULL, known, sizeof known);
		return pool_cli_usage_error(PROGRAM, "--model: '%s' is not KIND=NAME (KIND among %s)",
		                            pool_cli_arg(value), known);
	}
	if (r == -2) {
		pool_model_names(buffer, known, sizeof known);
		return pool_cli_usage_error(PROGRAM, "--model: unknown %s model '%s' (%s)", buffer,
		                            pool_cli_arg(equals + 1), known);
	}
	return 0;
}

static int parse_options(int argc, char **argv, rack_options *o) {
	memset(o, 0, sizeof *o);
	o->speed = DEFAULT_SPEED;
	o->gap = DEFAULT_GAP;
	o->table = "wpa-9ft";
	o->models = pool_default_models();
	bool have_kind = false, table_given = false;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		const char *value = i + 1 < argc ? argv[i + 1] : NULL;
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			o->help = true;
		} else if (strcmp(a, "8ball") == 0 || strcmp(a, "9ball") == 0 || strcmp(a, "snooker") == 0 ||
		           strcmp(a, "carom") == 0) {
			if (have_kind)
				return pool_cli_usage_error(PROGRAM, "unexpected argument '%s' (one rack)",
				                            pool_cli_arg(a));
			o->kind = a[0] == '8' ? POOL_RACK_8BALL : a[0] == '9' ? POOL_RACK_9BALL
			        : a[0] == 's' ? POOL_RACK_SNOOKER : POOL_RACK_CAROM;
			have_kind = true;
			if (!table_given) // each game on its own table unless --table says otherwise
				o->table = a[0] == 's' ? "snooker" : a[0] == 'c' ? "carom" : "wpa-9ft";
		} else if (strcmp(a, "--airborne") == 0) {
			o->airborne = true;
		} else if (a[0] == '-' && a[1] != '\0' && !value) {
			if (strcmp(a, "--speed") && strcmp(a, "--gap") && strcmp(a, "--spin") &&
			    strcmp(a, "--phi") && strcmp(a, "--theta") && strcmp(a, "--table") && strcmp(a, "-o") &&
			    strcmp(a, "--model") && strcmp(a, "--models"))
				return pool_cli_usage_error(PROGRAM, "unknown option '%s'", pool_cli_arg(a));
			return pool_cli_usage_error(PROGRAM, "option %s needs a value", a);
		} else if (strcmp(a, "--speed") == 0) {
			if (!pool_cli_parse_double(value, &o->speed) || o->speed <= 0.0)
				return pool_cli_usage_error(PROGRAM, "--speed: '%s' is not a positive speed in m/s",
				                            pool_cli_arg(value));
			++i;
		} else if (strcmp(a, "--gap") == 0) {
			if (!pool_cli_parse_double(value, &o->gap) || o->gap < 0.0)
				return pool_cli_usage_error(PROGRAM, "--gap: '%s' is not a gap >= 0 in m",
				                            pool_cli_arg(value));
			++i;
		} else if (strcmp(a, "--spin") == 0) {
			char buffer[128];
			snprintf(buffer, sizeof buffer, "%s", value);
			char *comma = strchr(buffer, ',');
			if (!comma)
				return pool_cli_usage_error(PROGRAM, "--spin: '%s' is not A,B (tip offsets in m)",
				                            pool_cli_arg(value));
			*comma = '\0';
			if (!pool_cli_parse_double(buffer, &o->a) || !pool_cli_parse_double(comma + 1, &o->b))
				return pool_cli_usage_error(PROGRAM, "--spin: '%s' is not A,B (tip offsets in m)",
				                            pool_cli_arg(value));
			++i;
		} else if (strcmp(a, "--phi") == 0) {
			if (!pool_cli_parse_double(value, &o->phi))
				return pool_cli_usage_error(PROGRAM, "--phi: '%s' is not an angle in degrees",
				                            pool_cli_arg(value));
			o->has_phi = true;
			++i;
		} else if (strcmp(a, "--theta") == 0) {
			if (!pool_cli_parse_double(value, &o->theta))
				return pool_cli_usage_error(PROGRAM, "--theta: '%s' is not an angle in degrees",
				                            pool_cli_arg(value));
			++i;
		} else if (strcmp(a, "--table") == 0) {
			pool_table_def t;
			if (pool_table_preset(value, &t) != POOL_OK)
				return pool_cli_usage_error(PROGRAM, "--table: unknown preset '%s' (wpa-9ft, wpa-8ft, wpa-7ft, "
				                            "snooker, carom)", pool_cli_arg(value));
			o->table = value;
			table_given = true;
			++i;
		} else if (strcmp(a, "--model") == 0) {
			int status = parse_model(value, &o->models);
			if (status)
				return status;
			o->has_models = true;
			++i;
		} else if (strcmp(a, "--models") == 0) {
			char err[512];
			if (pool_models_parse_spec(&o->models, value, err, sizeof err))
				return pool_cli_usage_error(PROGRAM, "--models: %s", err);
			o->has_models = true;
			++i;
		} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
			o->output = value;
			++i;
		} else {
			return pool_cli_usage_error(PROGRAM, "unknown argument '%s' (expected 8ball or 9ball, "
			                            "or an option)", pool_cli_arg(a));
		}
	}
	// --table snooker or carom alone racks that game.
	if (!have_kind && table_given && (strcmp(o->table, "snooker") == 0 || strcmp(o->table, "carom") == 0)) {
		o->kind = o->table[0] == 's' ? POOL_RACK_SNOOKER : POOL_RACK_CAROM;
		have_kind = true;
	}
	if (!o->help && !have_kind)
		return pool_cli_usage_error(PROGRAM, "%s", "missing the rack: 8ball, 9ball, snooker or carom");
	return 0;
}

static char *scenario_json(const rack_options *o, const pool_ball_state *balls, int count,
                           double radius) {
	pool_strike strike = pool_rack_break_strike(balls, count, o->speed);
	double phi = o->has_phi ? o->phi : strike.phi * 180.0 / POOL_PI;
	pool_jw w;
	pool_jw_init(&w, true);
	pool_jw_object(&w, false);
	pool_jw_key(&w, "format");
	pool_jw_string(&w, "libpool-scenario/1");
	pool_jw_key(&w, "name");
	static const char *const names[] = {"8-ball break", "9-ball break", "snooker break", "carom break"};
	pool_jw_string(&w, names[o->kind]);
	pool_jw_key(&w, "table");
	pool_jw_object(&w, true);
	pool_jw_key(&w, "preset");
	pool_jw_string(&w, o->table);
	pool_jw_end(&w, '}');
	pool_jw_key(&w, "balls");
	pool_jw_array(&w, false);
	for (int i = 0; i < count; ++i) {
		pool_jw_object(&w, true);
		pool_jw_key(&w, "id");
		pool_jw_int(&w, balls[i].id);
		pool_jw_key(&w, "pos");
		pool_jw_array(&w, true);
		pool_jw_number(&w, balls[i].pos.x);
		pool_jw_number(&w, balls[i].pos.y);
		if (balls[i].pos.z != radius)
			pool_jw_number(&w, balls[i].pos.z);
		pool_jw_end(&w, ']');
		pool_jw_end(&w, '}');
	}
	pool_jw_end(&w, ']');
	pool_jw_key(&w, "strike");
	pool_jw_object(&w, true);
	pool_jw_key(&w, "ball");
	pool_jw_int(&w, 0);
	pool_jw_key(&w, "speed");
	pool_jw_number(&w, strike.speed);
	pool_jw_key(&w, "phi");
	pool_jw_number(&w, phi);
	pool_jw_key(&w, "theta");
	pool_jw_number(&w, o->theta);
	pool_jw_key(&w, "a");
	pool_jw_number(&w, o->a);
	pool_jw_key(&w, "b");
	pool_jw_number(&w, o->b);
	pool_jw_end(&w, '}');
	if (o->has_models)
		pool_jw_models(&w, &o->models);
	if (o->airborne) {
		pool_jw_key(&w, "options");
		pool_jw_object(&w, true);
		pool_jw_key(&w, "airborne");
		pool_jw_bool(&w, true);
		pool_jw_end(&w, '}');
	}
	pool_jw_end(&w, '}');
	return pool_jw_finish(&w);
}

int main(int argc, char **argv) {
	rack_options o;
	int status = parse_options(argc, argv, &o);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	pool_table_def table;
	pool_table_preset(o.table, &table);
	pool_params params;
	pool_params_preset(o.table, &params); // the table's own balls
	pool_ball_state balls[32];
	int count = pool_rack(o.kind, &table, &params, o.gap, balls, 32);
	if (count < 0) {
		fprintf(stderr, "pool-rack: %s\n", pool_result_str((pool_result)count));
		return pool_cli_result_status(count);
	}
	char *json = scenario_json(&o, balls, count, params.ball_radius);
	if (!json) {
		fprintf(stderr, "pool-rack: out of memory\n");
		return POOL_EXIT_INTERNAL;
	}
	// Whatever we write must load in pool-sim; checking here reports a bad --spin or a gap that
	// pushes balls off the table with the scenario field it breaks.
	pool_scenario check;
	char err[512];
	if (pool_scenario_parse(json, strlen(json), &check, err, sizeof err) != 0) {
		fprintf(stderr, "pool-rack: %s\n", err);
		free(json);
		return POOL_EXIT_BAD_INPUT;
	}
	pool_scenario_free(&check);
	status = pool_cli_write_output(PROGRAM, o.output, json);
	free(json);
	return status;
}
