// pool-tracks: what a camera above the table would record of a shot. Simulates a scenario and
// writes every ball's position at a fixed frame rate as a tracks CSV (t, id, x, y), optionally
// with Gaussian position noise: the input pool-fit reads, made from known parameters, for tests,
// benchmarks and trying pool-fit out. docs/commands.md "pool-fit".
// Exit status: 0 success, 2 bad input or usage, 1 internal failure.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fit/fit.h"
#include "read_input.h"
#include "pool/scenario.h"
#include "text_buffer.h"

#define PROGRAM "pool-tracks"
#define TRACKS_MAX_RATE 100000.0 // frames per second: far beyond any camera
#define TRACKS_MAX_FRAMES 10000000.0

static const char usage_text[] =
	"usage: pool-tracks SCENARIO.json [--rate HZ] [--noise M] [--seed S] [--duration S]\n"
	"                   [-o FILE] [--max-input BYTES]\n"
	"\n"
	"Simulates the scenario's shot and writes every ball's position at each frame as CSV\n"
	"(t,id,x,y; t in s from the strike, x and y in m), as a camera above the table would see it:\n"
	"a ball pocketed or off the table is no longer seen.\n"
	"\n"
	"  --rate HZ      frames per second (default 100)\n"
	"  --noise M      standard deviation (m) of Gaussian noise added to x and to y (default 0)\n"
	"  --seed S       seed of GSL's mt19937 for the noise, 1 to 4294967295 (default 1)\n"
	"  --duration S   seconds recorded (default: until every ball rests)\n"
	"  -o FILE        write to FILE (atomically) instead of standard output\n"
	"  --max-input BYTES  refuse a scenario longer than BYTES (default 64M)\n"
	"  -h, --help     show this help\n";

static double standard_normal(void *rng) { return gsl_ran_gaussian(rng, 1.0); }

typedef struct tracks_options {
	const char *path, *output;
	double rate, noise, duration;
	unsigned long seed;
	size_t max_input;
	bool help;
} tracks_options;

static int option(void *context, const char *a, const char *v) {
	tracks_options *o = context;
	long count = 0;
	if (strcmp(a, "--rate") == 0) {
		if (!pool_cli_parse_double(v, &o->rate) || o->rate <= 0.0 || o->rate > TRACKS_MAX_RATE)
			return pool_cli_usage_error(PROGRAM, "--rate: '%s' is not a frame rate (above 0, at most %g Hz)",
			                            pool_cli_arg(v), TRACKS_MAX_RATE);
	} else if (strcmp(a, "--noise") == 0) {
		if (!pool_cli_parse_double(v, &o->noise) || o->noise < 0.0 || o->noise > 1.0)
			return pool_cli_usage_error(PROGRAM, "--noise: '%s' is not a standard deviation in metres (0 to 1)",
			                            pool_cli_arg(v));
	} else if (strcmp(a, "--seed") == 0) {
		if (!pool_cli_parse_count(v, &count) || count < 1 || count > 4294967295L)
			return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number from 1 to 4294967295",
			                            pool_cli_arg(v));
		o->seed = (unsigned long)count;
	} else if (strcmp(a, "--duration") == 0) {
		if (!pool_cli_parse_double(v, &o->duration) || o->duration <= 0.0 || o->duration > 1e4)
			return pool_cli_usage_error(PROGRAM, "--duration: '%s' is not a time in seconds (above 0, at most "
			                            "10000)", pool_cli_arg(v));
	} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
		o->output = v;
	} else if (strcmp(a, "--max-input") == 0) {
		return pool_cli_max_input(PROGRAM, v, &o->max_input);
	}
	return 0;
}

int main(int argc, char **argv) {
	tracks_options o = {.rate = 100.0, .seed = 1, .max_input = POOL_INPUT_DEFAULT_MAX};
	static const char *const flags[] = {NULL};
	static const char *const with_value[] = {"--rate", "--noise", "--seed", "--duration", "-o", "--output",
	                                         "--max-input", NULL};
	int status = pool_cli_walk(PROGRAM, argc, argv, "scenario", flags, with_value, option, &o, &o.path, &o.help);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	if (!o.path)
		return pool_cli_usage_error(PROGRAM, "%s", "missing SCENARIO.json");
	pool_scenario sc;
	char err[512];
	if (pool_scenario_load_file_limit(o.path, o.max_input, &sc, err, sizeof err) != 0) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return POOL_EXIT_BAD_INPUT;
	}
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	pool_result r = pool_scenario_setup(&sc, &sim, &e);
	if (r == POOL_OK)
		r = pool_sim_run(sim);
	if (r != POOL_OK) {
		fprintf(stderr, "%s: %s\n", PROGRAM, e.message[0] ? e.message : pool_result_str(r));
		pool_sim_destroy(sim);
		pool_scenario_free(&sc);
		return pool_cli_result_status(r);
	}
	double end = o.duration > 0.0 ? o.duration : pool_sim_end_time(sim);
	if (end * o.rate > TRACKS_MAX_FRAMES) {
		pool_sim_destroy(sim);
		pool_scenario_free(&sc);
		return pool_cli_usage_error(PROGRAM, "%.0f frames: more than %.0f (lower --rate or --duration)", end * o.rate,
		                            TRACKS_MAX_FRAMES);
	}
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	fit_observation *obs = NULL;
	long count = 0;
	pool_text_buffer out = {0};
	if (rng) {
		gsl_rng_set(rng, o.seed);
		if (fit_camera(sim, o.rate, end, o.noise, standard_normal, rng, &obs, &count) == 0) {
			pool_text_append(&out, "t,id,x,y\n", 9);
			for (long k = 0; k < count; ++k) {
				char line[160];
				int n = snprintf(line, sizeof line, "%.10g,%d,%.10g,%.10g\n", obs[k].t,
				                 (int)sc.balls[obs[k].ball].id, obs[k].x, obs[k].y);
				pool_text_append(&out, line, (size_t)n);
			}
		}
	}
	if (!rng || !obs || out.failed) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		status = POOL_EXIT_INTERNAL;
	} else {
		status = pool_cli_write_output(PROGRAM, o.output, out.data);
	}
	free(out.data);
	free(obs);
	gsl_rng_free(rng);
	pool_sim_destroy(sim);
	pool_scenario_free(&sc);
	return status;
}
