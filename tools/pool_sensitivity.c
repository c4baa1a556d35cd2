// pool-sensitivity: how forgiving is a shot? The scenario's strike with Gaussian noise on the
// five cue parameters (and optionally on ball positions), N samples of libpool games' seeded
// noise (pool/noise.h), each simulated as pool-batch simulates a strike, on every core; prints and writes
// the cloud of the chosen balls' final positions (mean, covariance, 95 % ellipse), pocketing
// probabilities with Wilson intervals, and the picture; with a "game" in the scenario, the
// probability of a legal shot, of a legal pot and of each outcome under its rules. --models A,B runs the same samples under
// two model sets (e.g. default,spin-blind: the 2012 work's comparison with FastFiz).
// Exit status: 0 success, 2 bad input or usage (the message names the option or field), 1
// internal failure (out of memory, an output that cannot be written, a sample the library
// failed to simulate).
#define _XOPEN_SOURCE 700 // realpath
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "batch_layout.h"
#include "cli.h"
#include "read_input.h"
#include "sensitivity/study.h"
#include "text_escape.h"

#define PROGRAM SENS_PROGRAM
#define SENS_DEFAULT_SAMPLES 500L // the 2012 work's studies
#define SENS_MAX_SAMPLES 10000000L
#define SENS_MAX_THREADS 1024
// The scenario parser's limit on numbers (nothing on a table is 1e9 m, m/s or degrees).
#define SENS_MAX_ABS 1e9
// Seeds from 1 to 2^32 - 1, the range of the tool's first generator (GSL's mt19937), kept so
// that every command line that worked still does.
#define SENS_MAX_SEED 4294967295UL

typedef struct sens_options {
	const char *scenario_path;
	const char *sd_spec;
	const char *noise_spec; ///< --noise: a preset or NAME=SD pairs (pool/noise.h)
	bool have_position_sd;
	double position_sd;
	const char *position_balls;
	long samples;
	unsigned long seed;
	const char *balls;
	const char *models;
	long threads; ///< 0 = online CPUs
	const char *prefix;
	size_t max_input;
	bool no_progress;
	bool help;
} sens_options;

static const char usage_text[] =
	"usage: pool-sensitivity SCENARIO.json [--sd SPEC | --noise NAME|SPEC]\n"
	"                        [--position-sd M [--position-balls IDS]]\n"
	"                        [-n N] [--seed S] [--balls IDS] [--models A[,B]] [--threads N]\n"
	"                        [-o PREFIX] [--max-input BYTES] [--no-progress]\n"
	"\n"
	"Runs the scenario's strike N times with Gaussian noise and reports where the chosen balls end:\n"
	"mean, covariance and 95 % ellipse of their final positions on the table, and the probability\n"
	"of each being pocketed (in all and per pocket) with its 95 % Wilson score interval. With a\n"
	"\"game\" in the scenario, also the probability of a legal shot, of a legal pot (legal, and the\n"
	"shooter keeps the table or wins) and of each outcome under its rules.\n"
	"\n"
	"  --sd SPEC            standard deviations NAME=SIGMA, comma-separated, NAME among speed (m/s),\n"
	"                       phi, theta (degrees), a, b (m); unnamed parameters have none. theta is\n"
	"                       folded to |theta| (a cue does not point below the horizontal)\n"
	"  --noise NAME|SPEC    the same as a preset (none, fastfiz: the tournaments' noise) or a SPEC\n"
	"  --position-sd M      standard deviation (m) of x and of y of every ball's position\n"
	"  --position-balls IDS only these balls' positions are noisy (comma-separated ids)\n"
	"  -n, --samples N      samples (default 500, at most 10000000)\n"
	"  --seed S             seed of the noise, 1 to 4294967295 (default 1); sample i depends on\n"
	"                       the seed and i only, and its strike is pool-batch --noise's strike i\n"
	"  --balls IDS          balls whose final positions are studied (default: the struck ball)\n"
	"  --models A[,B]       model set(s): default (the scenario as written), thesis (the 2012\n"
	"                       work's laws), spin-blind (ball-ball and cushion frictions off, like\n"
	"                       FastFiz), model names (mathavan2010, alciatore, endmass, petit, ...),\n"
	"                       joined with '+' (thesis+spin-blind); two sets run the same samples\n"
	"                       and report the distance between means\n"
	"  --threads N          worker threads (default: the number of online CPUs); the results do\n"
	"                       not depend on it\n"
	"  -o, --output PREFIX  also write PREFIX.json (everything), PREFIX.csv (one summary row per\n"
	"                       model set and ball), PREFIX.samples.csv (every sample and its outcome)\n"
	"                       and PREFIX.svg (the clouds on the table)\n"
	"  --max-input BYTES    refuse a scenario longer than BYTES (default 64M)\n"
	"  --no-progress        no progress line (it is shown on a terminal for runs over 1 s)\n"
	"  -h, --help           show this help\n"
	"\n"
	"A sample the library refuses (a^2 + b^2 >= R^2, overlapping balls...) is counted as refused\n"
	"and left out of the statistics. Exit status: 0 success, 2 bad input or usage (message names\n"
	"the option or field), 1 internal error.\n";

// ---- option values ----------------------------------------------------------------------------

static int parse_sd(const char *spec, double sd[SENS_CUE_COUNT]) {
	bool seen[SENS_CUE_COUNT] = {false};
	if (!spec[0])
		return pool_cli_usage_error(PROGRAM, "--sd: empty specification (e.g. speed=0.05,phi=0.3)");
	for (const char *p = spec;;) {
		const char *end = strchr(p, ',');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		char item[128], shown[POOL_ESCAPE_SHORT];
		pool_escape_text(shown, sizeof shown, p, n);
		const char *eq = memchr(p, '=', n);
		if (n == 0 || n >= sizeof item || !eq)
			return pool_cli_usage_error(PROGRAM, "--sd: '%s' is not NAME=SIGMA", shown);
		memcpy(item, p, n);
		item[n] = '\0';
		size_t name_length = (size_t)(eq - p);
		int param = -1;
		for (int k = 0; k < SENS_CUE_COUNT; ++k)
			if (strlen(sens_cue_names[k]) == name_length && strncmp(sens_cue_names[k], p, name_length) == 0)
				param = k;
		if (param < 0) {
			char name[POOL_ESCAPE_SHORT];
			pool_escape_text(name, sizeof name, p, name_length);
			return pool_cli_usage_error(PROGRAM, "--sd: '%s': unknown parameter (speed, phi, theta, a, b)",
			                            name);
		}
		if (seen[param])
			return pool_cli_usage_error(PROGRAM, "--sd: %s is given twice", sens_cue_names[param]);
		seen[param] = true;
		double x;
		const char *value = item + name_length + 1;
		if (!pool_cli_parse_double(value, &x) || x < 0.0 || x > SENS_MAX_ABS)
			return pool_cli_usage_error(PROGRAM, "--sd: %s: '%s' is not a standard deviation (a number "
			                            "from 0 to %g)", sens_cue_names[param], pool_cli_arg(value),
			                            SENS_MAX_ABS);
		sd[param] = x;
		if (!end)
			break;
		p = end + 1;
	}
	return 0;
}

/// "1,2,3" as layout indices, each id a ball of the layout, none twice.
static int parse_ids(const char *option, const char *text, const pool_scenario *layout, int **out,
                     int *count) {
	*out = calloc((size_t)layout->ball_count + 1, sizeof **out);
	*count = 0;
	if (!*out) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	if (!text[0])
		return pool_cli_usage_error(PROGRAM, "%s: empty list of ball ids", option);
	for (const char *p = text;;) {
		char *end = NULL;
		errno = 0;
		long long id = strtoll(p, &end, 10);
		if (errno || end == p || (*end && *end != ',') || id < INT32_MIN || id > INT32_MAX)
			return pool_cli_usage_error(PROGRAM, "%s: '%s' is not a comma-separated list of ball ids",
			                            option, pool_cli_arg(text));
		int index = -1;
		for (int k = 0; k < layout->ball_count; ++k)
			if (layout->balls[k].id == id)
				index = k;
		if (index < 0)
			return pool_cli_usage_error(PROGRAM, "%s: no ball of the scenario has id %lld", option, id);
		for (int k = 0; k < *count; ++k)
			if ((*out)[k] == index)
				return pool_cli_usage_error(PROGRAM, "%s: ball %lld is given twice", option, id);
		(*out)[(*count)++] = index;
		if (!*end)
			break;
		p = end + 1;
	}
	return 0;
}

// One option of pool-sensitivity (pool_cli_walk).
static int sens_option(void *context, const char *a, const char *v) {
	sens_options *o = context;
	long count = 0;
	if (strcmp(a, "--no-progress") == 0) {
		o->no_progress = true;
	} else if (strcmp(a, "--sd") == 0) {
		o->sd_spec = v;
	} else if (strcmp(a, "--noise") == 0) {
		o->noise_spec = v;
	} else if (strcmp(a, "--position-sd") == 0) {
		o->have_position_sd = true;
		if (!pool_cli_parse_double(v, &o->position_sd) || o->position_sd < 0.0 || o->position_sd > SENS_MAX_ABS)
			return pool_cli_usage_error(PROGRAM, "--position-sd: '%s' is not a standard deviation in "
			                            "metres (a number from 0 to %g)", pool_cli_arg(v), SENS_MAX_ABS);
	} else if (strcmp(a, "--position-balls") == 0) {
		o->position_balls = v;
	} else if (strcmp(a, "-n") == 0 || strcmp(a, "--samples") == 0) {
		if (!pool_cli_parse_count(v, &o->samples) || o->samples < 1 || o->samples > SENS_MAX_SAMPLES)
			return pool_cli_usage_error(PROGRAM, "%s: '%s' is not a number of samples from 1 to %ld", a,
			                            pool_cli_arg(v), SENS_MAX_SAMPLES);
	} else if (strcmp(a, "--seed") == 0) {
		if (!pool_cli_parse_count(v, &count) || count < 1 || (unsigned long)count > SENS_MAX_SEED)
			return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number from 1 to %lu", pool_cli_arg(v),
			                            SENS_MAX_SEED);
		o->seed = (unsigned long)count;
	} else if (strcmp(a, "--balls") == 0) {
		o->balls = v;
	} else if (strcmp(a, "--models") == 0) {
		o->models = v;
	} else if (strcmp(a, "--threads") == 0) {
		if (!pool_cli_parse_count(v, &o->threads) || o->threads < 1 || o->threads > SENS_MAX_THREADS)
			return pool_cli_usage_error(PROGRAM, "--threads: '%s' is not a number of threads from 1 to %d",
			                            pool_cli_arg(v), SENS_MAX_THREADS);
	} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
		o->prefix = v;
		if (!v[0])
			return pool_cli_usage_error(PROGRAM, "%s: empty PREFIX", a);
	} else if (strcmp(a, "--max-input") == 0) {
		return pool_cli_max_input(PROGRAM, v, &o->max_input);
	}
	return 0;
}

static int parse_options(int argc, char **argv, sens_options *o) {
	memset(o, 0, sizeof *o);
	o->samples = SENS_DEFAULT_SAMPLES;
	o->seed = 1;
	o->max_input = POOL_INPUT_DEFAULT_MAX;
	static const char *const flags[] = {"--no-progress", NULL};
	static const char *const with_value[] = {"--sd",      "--position-sd", "--position-balls", "-n",        "--samples",
	                                         "--seed",    "--balls",       "--models",         "--threads", "-o",
	                                         "--output",  "--max-input",   "--noise",          NULL};
	const int status =
	    pool_cli_walk(PROGRAM, argc, argv, "scenario", flags, with_value, sens_option, o, &o->scenario_path, &o->help);
	if (status)
		return status;
	if (o->help)
		return 0;
	if (!o->scenario_path)
		return pool_cli_usage_error(PROGRAM, "%s", "missing SCENARIO.json");
	if (o->sd_spec && o->noise_spec)
		return pool_cli_usage_error(PROGRAM, "%s", "--noise: give --sd or --noise, not both");
	if (o->position_balls && !o->have_position_sd)
		return pool_cli_usage_error(PROGRAM, "%s", "--position-balls goes with --position-sd");
	return 0;
}

// ---- the study --------------------------------------------------------------------------------

/// Splits --models into one or two sets built on the scenario's definition.
static int parse_model_sets(const char *spec, const pool_scenario *layout, sens_study *s) {
	const char *text = spec ? spec : "default";
	const char *comma = strchr(text, ',');
	if (comma && strchr(comma + 1, ','))
		return pool_cli_usage_error(PROGRAM, "--models: '%s': at most %d model sets (A or A,B)",
		                            pool_cli_arg(text), SENS_MAX_SETS);
	char names[SENS_MAX_SETS][sizeof s->sets[0].name];
	size_t first = comma ? (size_t)(comma - text) : strlen(text);
	if (first >= sizeof names[0] || (comma && strlen(comma + 1) >= sizeof names[1]))
		return pool_cli_usage_error(PROGRAM, "--models: a model set name is longer than %zu bytes",
		                            sizeof names[0] - 1);
	memcpy(names[0], text, first);
	names[0][first] = '\0';
	s->set_count = 1;
	if (comma) {
		snprintf(names[1], sizeof names[1], "%s", comma + 1);
		s->set_count = 2;
	}
	for (int k = 0; k < s->set_count; ++k) {
		char err[512];
		if (sens_model_set_parse(names[k], &layout->def, &s->sets[k], err, sizeof err) != 0)
			return pool_cli_usage_error(PROGRAM, "%s", err);
		pool_error e = {{0}};
		if (pool_table_def_validate(&s->sets[k].def.table, &e) != POOL_OK ||
		    pool_params_validate(&s->sets[k].def.params, &e) != POOL_OK)
			return pool_cli_usage_error(PROGRAM, "--models: %s: %s", names[k], e.message);
	}
	return 0;
}

static int write_file(const char *prefix, const char *suffix, char *text) {
	if (!text) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	size_t n = strlen(prefix) + strlen(suffix) + 1;
	char *path = malloc(n);
	int status = POOL_EXIT_INTERNAL;
	if (path) {
		snprintf(path, n, "%s%s", prefix, suffix);
		status = pool_cli_write_output(PROGRAM, path, text);
		free(path);
	} else {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
	}
	free(text);
	return status;
}

/// Whether PREFIX + suffix names the scenario file itself (then writing would destroy the input).
static bool overwrites_scenario(const char *scenario, const char *prefix, const char *suffix) {
	if (strcmp(scenario, "-") == 0)
		return false;
	char path[4096], a[4096], b[4096];
	if (snprintf(path, sizeof path, "%s%s", prefix, suffix) >= (int)sizeof path)
		return false;
	return realpath(scenario, a) && realpath(path, b) && strcmp(a, b) == 0;
}

static int run_study(const sens_options *o, pool_scenario *layout, sens_study *s) {
	int status = 0;
	char err[512];
	status = pool_batch_load_layout(o->scenario_path, o->max_input, layout, err, sizeof err);
	if (status) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return status;
	}
	static const char *const suffixes[] = {".json", ".csv", ".samples.csv", ".svg"};
	for (size_t k = 0; o->prefix && k < sizeof suffixes / sizeof suffixes[0]; ++k)
		if (overwrites_scenario(o->scenario_path, o->prefix, suffixes[k]))
			return pool_cli_usage_error(PROGRAM, "-o: %s%s is the scenario itself (choose another PREFIX)",
			                            pool_cli_arg(o->prefix), suffixes[k]);
	s->scenario_path = o->scenario_path;
	s->layout = layout;
	s->seed = o->seed;
	if (!layout->has_strike)
		return pool_cli_usage_error(PROGRAM, "%s: strike: missing (the study perturbs the scenario's "
		                            "strike)", pool_cli_arg(o->scenario_path));
	s->nominal = layout->written;
	if (o->sd_spec && (status = parse_sd(o->sd_spec, s->noise.cue_sd)) != 0)
		return status;
	// The noise in pool_noise's units (radians for the angles, as pool_noise_parse makes them).
	s->noise.cue = (pool_noise){.speed = s->noise.cue_sd[SENS_SPEED], .phi = s->noise.cue_sd[SENS_PHI] * POOL_DEGREE,
	                            .theta = s->noise.cue_sd[SENS_THETA] * POOL_DEGREE, .a = s->noise.cue_sd[SENS_A],
	                            .b = s->noise.cue_sd[SENS_B]};
	if (o->noise_spec) {
		pool_error e;
		if (pool_noise_parse(o->noise_spec, &s->noise.cue, &e) != POOL_OK) {
			char shown[POOL_ESCAPE_SHORT];
			return pool_cli_usage_error(PROGRAM, "--noise: %s", pool_escape_str(shown, sizeof shown,
			                                                                     e.message + strlen("noise: ")));
		}
		const pool_noise *n = &s->noise.cue;
		const double sd[SENS_CUE_COUNT] = {n->speed, n->phi / POOL_DEGREE, n->theta / POOL_DEGREE, n->a, n->b};
		memcpy(s->noise.cue_sd, sd, sizeof sd);
	}
	s->noise.position_sd = o->position_sd;
	if (o->have_position_sd) {
		if (o->position_balls) {
			status = parse_ids("--position-balls", o->position_balls, layout, &s->noise.position_index,
			                   &s->noise.position_count);
			if (status)
				return status;
		} else {
			s->noise.position_index = calloc((size_t)layout->ball_count + 1, sizeof *s->noise.position_index);
			if (!s->noise.position_index) {
				fprintf(stderr, "%s: out of memory\n", PROGRAM);
				return POOL_EXIT_INTERNAL;
			}
			for (int k = 0; k < layout->ball_count; ++k)
				s->noise.position_index[k] = k;
			s->noise.position_count = layout->ball_count;
		}
	}
	if (o->balls) {
		if ((status = parse_ids("--balls", o->balls, layout, &s->tracked, &s->tracked_count)) != 0)
			return status;
	} else {
		s->tracked = calloc(1, sizeof *s->tracked);
		if (!s->tracked) {
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
			return POOL_EXIT_INTERNAL;
		}
		for (int k = 0; k < layout->ball_count; ++k)
			if (layout->balls[k].id == layout->strike_ball)
				s->tracked[0] = k;
		s->tracked_count = 1;
	}
	if ((status = parse_model_sets(o->models, layout, s)) != 0)
		return status;

	if (sens_draw_samples(layout, &s->nominal, &s->noise, o->samples, o->seed, &s->samples) != 0) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	long threads = o->threads;
	if (threads == 0) {
		threads = sysconf(_SC_NPROCESSORS_ONLN);
		threads = threads < 1 ? 1 : threads > SENS_MAX_THREADS ? SENS_MAX_THREADS : threads;
	}
	bool progress = !o->no_progress && isatty(STDERR_FILENO);
	s->clouds = calloc((size_t)(s->set_count * s->tracked_count), sizeof *s->clouds);
	if (!s->clouds) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	for (int set = 0; set < s->set_count; ++set) {
		if (sens_run_samples(layout, &s->sets[set].def, &s->noise, &s->samples, s->tracked,
		                     s->tracked_count, threads, progress, s->sets[set].name, &s->runs[set]) != 0) {
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
			return POOL_EXIT_INTERNAL;
		}
		for (int k = 0; k < s->tracked_count; ++k)
			if (sens_cloud_compute(&s->runs[set], k, layout->balls[s->tracked[k]].id,
			                       &s->clouds[set * s->tracked_count + k]) != 0) {
				fprintf(stderr, "%s: out of memory\n", PROGRAM);
				return POOL_EXIT_INTERNAL;
			}
	}

	char *text = sens_report_text(s);
	if (!text) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	status = pool_cli_write_output(PROGRAM, NULL, text);
	free(text);
	if (status == 0 && o->prefix) {
		status = write_file(o->prefix, ".json", sens_report_json(s));
		if (status == 0)
			status = write_file(o->prefix, ".csv", sens_report_csv(s));
		if (status == 0)
			status = write_file(o->prefix, ".samples.csv", sens_samples_csv(s));
		if (status == 0)
			status = write_file(o->prefix, ".svg", sens_svg(s));
	}
	long failed = 0;
	for (int set = 0; set < s->set_count; ++set)
		failed += s->runs[set].failed;
	if (status == 0 && failed > 0) {
		fprintf(stderr, "%s: %ld sample(s) failed inside the library (see the samples' error column)\n",
		        PROGRAM, failed);
		status = POOL_EXIT_INTERNAL;
	}
	return status;
}

int main(int argc, char **argv) {
	sens_options o;
	int status = parse_options(argc, argv, &o);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	pool_scenario layout = {0};
	sens_study study = {0};
	status = run_study(&o, &layout, &study);
	for (int set = 0; set < SENS_MAX_SETS; ++set)
		sens_run_free(&study.runs[set]);
	sens_samples_free(&study.samples);
	free(study.clouds);
	free(study.tracked);
	free(study.noise.position_index);
	pool_scenario_free(&layout);
	return status;
}
