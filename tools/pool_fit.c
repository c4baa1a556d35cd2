// pool-fit: the strike and the table's parameters from observed ball tracks. One or more shots,
// each a scenario (the layout, the table, and a starting strike) and a CSV of observed positions;
// nonlinear least squares on the simulated tracks (GSL's gsl_multifit_nlinear), the table's
// parameters shared by all shots and each shot's strike its own; prints the fitted values with
// standard errors and 95 % intervals (libpool-fit/1 JSON), and with -o the picture of observed
// against fitted tracks. docs/commands.md "pool-fit".
// Exit status: 0 success, 2 bad input or usage (the message names the option, file, line or
// field), 1 internal failure.
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "fit/fit.h"
#include "read_input.h"
#include "text_escape.h"

#define PROGRAM FIT_PROGRAM
#define FIT_MAX_SHOTS 1000
#define FIT_MAX_THREADS 1024
#define FIT_DEFAULT_STARTS 6
#define FIT_DEFAULT_ITERATIONS 200
#define FIT_DEFAULT_RETRIES 8

typedef struct fit_cli {
	const char *paths[2 * FIT_MAX_SHOTS];
	int path_count;
	const char *spec;
	fit_options solver;
	long threads;
	fit_linear_kind linear;
	bool have_ball;
	int32_t ball;
	const char *prefix;
	size_t max_input;
	bool summary;
	bool help;
} fit_cli;

static const char usage_text[] =
	"usage: pool-fit SCENARIO.json TRACKS.csv [SCENARIO.json TRACKS.csv ...] [--fit NAMES]\n"
	"                [--sigma M] [--starts N] [--retries N] [--max-iterations N] [--seed S] [--ball ID]\n"
	"                [--intervals auto|wald|profile] [--linear auto|dense|blocks] [--threads N]\n"
	"                [-o PREFIX] [--summary] [--quiet] [--max-input BYTES]\n"
	"\n"
	"Fits the strike and/or the table's parameters to observed ball tracks by nonlinear least\n"
	"squares on libpool's simulated tracks, and prints the fitted values with standard errors and\n"
	"95 % intervals (libpool-fit/1 JSON). Several shots are fitted together: the table's\n"
	"parameters are shared, each shot has its own strike.\n"
	"\n"
	"  SCENARIO.json     a libpool-scenario/1 file: the balls where they start, the table, the\n"
	"                    models, and a strike (the starting guess; without one, the struck ball\n"
	"                    is --ball and the guess comes from its first observed positions)\n"
	"  TRACKS.csv        observed positions: a header naming the columns t, id, x, y (s from the\n"
	"                    strike, ball id, m); other columns are ignored; any frame rate; a row\n"
	"                    with empty x and y is a frame where the ball was not seen\n"
	"  --fit NAMES       free parameters, comma-separated (default strike): speed, phi, theta,\n"
	"                    a, b, t0 (each shot's own; t0 is when the strike happened on the tracks'\n"
	"                    clock), mu_slide, mu_roll, mu_spin, mu_ball, e_ball, mu_cushion,\n"
	"                    e_cushion, mu_table, e_table, throw_a, throw_b, throw_c, cue_end_mass,\n"
	"                    e_cushion_mathavan, mu_cushion_mathavan (shared; each needs the laws that\n"
	"                    use it: mu_ball constant friction, throw_* alciatore, mu_cushion and\n"
	"                    e_cushion petit cushions, *_mathavan mathavan2010, cue_end_mass endmass);\n"
	"                    groups strike = speed,phi,a,b, cue = the five cue parameters,\n"
	"                    cloth = mu_slide,mu_roll,mu_spin\n"
	"  --sigma M         the position noise of the tracks (m), when known; by default it is\n"
	"                    estimated from the residual\n"
	"  --starts N        starting points (default 6): the scenario's strike and the guess from the\n"
	"                    tracks, then starts near the best fit; the lowest residual wins, and the\n"
	"                    intervals span other minima that fit as well\n"
	"  --retries N       more starts from random points near the first (default 8), tried only while\n"
	"                    the best fit's rms is above 1.15 times the tracks' own noise (estimated from\n"
	"                    each ball's second differences): a fit in a wrong minimum\n"
	"  --max-iterations N  per start (default 200)\n"
	"  --seed S          seed of the perturbed starts (default 1)\n"
	"  --ball ID         the struck ball of scenarios without a strike\n"
	"  --intervals K     95 % intervals from the profile of the cost (profile: where the cost,\n"
	"                    refitted over the other parameters, rises by q^2 sigma^2), from the\n"
	"                    standard errors (wald: value +- q se), or auto (default: profile up to 12\n"
	"                    parameters)\n"
	"  --linear K        how each step's linear system is solved: dense (QR of the whole\n"
	"                    Jacobian), blocks (J^T J built shot by shot, Cholesky: linear in the\n"
	"                    number of shots), or auto (default: dense up to 16 parameters)\n"
	"  --threads N       worker threads (default: the number of online CPUs); the results do\n"
	"                    not depend on it\n"
	"  -o, --output PREFIX  also write PREFIX.json and PREFIX.svg (observed against fitted tracks)\n"
	"  --summary         a table of the fitted values on standard error\n"
	"  --quiet           no progress lines on standard error\n"
	"  --max-input BYTES refuse a scenario or tracks file longer than BYTES (default 64M)\n"
	"  -h, --help        show this help\n"
	"\n"
	"Exit status: 0 success, 2 bad input or usage (the message names the option, file, line or\n"
	"field), 1 internal error.\n";

static int parse_options(int argc, char **argv, fit_cli *o) {
	memset(o, 0, sizeof *o);
	o->spec = "strike";
	o->solver.starts = FIT_DEFAULT_STARTS;
	o->solver.max_iterations = FIT_DEFAULT_ITERATIONS;
	o->solver.seed = 1;
	o->solver.retries = FIT_DEFAULT_RETRIES;
	o->max_input = POOL_INPUT_DEFAULT_MAX;
	bool options_done = false;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		if (options_done || a[0] != '-' || strcmp(a, "-") == 0) {
			if (o->path_count == 2 * FIT_MAX_SHOTS)
				return pool_cli_usage_error(PROGRAM, "more than %d shots", FIT_MAX_SHOTS);
			o->paths[o->path_count++] = a;
			continue;
		}
		if (strcmp(a, "--") == 0) {
			options_done = true;
			continue;
		}
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			o->help = true;
			continue;
		}
		if (strcmp(a, "--summary") == 0) {
			o->summary = true;
			continue;
		}
		if (strcmp(a, "--quiet") == 0) {
			o->solver.quiet = true;
			continue;
		}
		static const char *const with_value[] = {"--fit", "--sigma", "--starts", "--max-iterations", "--seed",
		                                         "--ball", "--threads", "-o", "--output", "--max-input",
		                                         "--intervals", "--retries", "--linear"};
		bool known = false;
		for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; ++k)
			known = known || strcmp(a, with_value[k]) == 0;
		if (!known)
			return pool_cli_usage_error(PROGRAM, "unknown option '%s'", pool_cli_arg(a));
		if (i + 1 == argc)
			return pool_cli_usage_error(PROGRAM, "option %s needs a value", a);
		const char *v = argv[++i];
		long count = 0;
		double x = 0.0;
		if (strcmp(a, "--fit") == 0) {
			o->spec = v;
		} else if (strcmp(a, "--intervals") == 0) {
			if (strcmp(v, "auto") == 0)
				o->solver.profile = FIT_INTERVALS_AUTO;
			else if (strcmp(v, "wald") == 0)
				o->solver.profile = FIT_INTERVALS_WALD;
			else if (strcmp(v, "profile") == 0)
				o->solver.profile = FIT_INTERVALS_PROFILE;
			else
				return pool_cli_usage_error(PROGRAM, "--intervals: '%s' is not auto, wald or profile", pool_cli_arg(v));
		} else if (strcmp(a, "--linear") == 0) {
			if (strcmp(v, "auto") == 0)
				o->linear = FIT_LINEAR_AUTO;
			else if (strcmp(v, "dense") == 0)
				o->linear = FIT_LINEAR_DENSE;
			else if (strcmp(v, "blocks") == 0)
				o->linear = FIT_LINEAR_BLOCKS;
			else
				return pool_cli_usage_error(PROGRAM, "--linear: '%s' is not auto, dense or blocks", pool_cli_arg(v));
		} else if (strcmp(a, "--sigma") == 0) {
			if (!pool_cli_parse_double(v, &x) || x <= 0.0 || x > 1.0)
				return pool_cli_usage_error(PROGRAM, "--sigma: '%s' is not a position noise in metres (above 0, "
				                            "at most 1)", pool_cli_arg(v));
			o->solver.sigma = x;
		} else if (strcmp(a, "--starts") == 0) {
			if (!pool_cli_parse_count(v, &count) || count < 1 || count > 1000)
				return pool_cli_usage_error(PROGRAM, "--starts: '%s' is not a number of starts from 1 to 1000",
				                            pool_cli_arg(v));
			o->solver.starts = (int)count;
		} else if (strcmp(a, "--retries") == 0) {
			if (!pool_cli_parse_count(v, &count) || count > 1000)
				return pool_cli_usage_error(PROGRAM, "--retries: '%s' is not a number from 0 to 1000", pool_cli_arg(v));
			o->solver.retries = (int)count;
		} else if (strcmp(a, "--max-iterations") == 0) {
			if (!pool_cli_parse_count(v, &count) || count < 1 || count > 100000)
				return pool_cli_usage_error(PROGRAM, "--max-iterations: '%s' is not a number from 1 to 100000",
				                            pool_cli_arg(v));
			o->solver.max_iterations = (int)count;
		} else if (strcmp(a, "--seed") == 0) {
			if (!pool_cli_parse_count(v, &count) || count < 1 || count > 4294967295L)
				return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number from 1 to 4294967295",
				                            pool_cli_arg(v));
			o->solver.seed = (unsigned long)count;
		} else if (strcmp(a, "--ball") == 0) {
			char *end = NULL;
			long long id = strtoll(v, &end, 10);
			if (!v[0] || *end || id < INT32_MIN || id > INT32_MAX)
				return pool_cli_usage_error(PROGRAM, "--ball: '%s' is not a ball id", pool_cli_arg(v));
			o->have_ball = true;
			o->ball = (int32_t)id;
		} else if (strcmp(a, "--threads") == 0) {
			if (!pool_cli_parse_count(v, &o->threads) || o->threads < 1 || o->threads > FIT_MAX_THREADS)
				return pool_cli_usage_error(PROGRAM, "--threads: '%s' is not a number of threads from 1 to %d",
				                            pool_cli_arg(v), FIT_MAX_THREADS);
		} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
			if (!v[0])
				return pool_cli_usage_error(PROGRAM, "%s: empty PREFIX", a);
			o->prefix = v;
		} else {
			int status = pool_cli_max_input(PROGRAM, v, &o->max_input);
			if (status)
				return status;
		}
	}
	if (o->help)
		return 0;
	if (o->path_count == 0)
		return pool_cli_usage_error(PROGRAM, "%s", "missing SCENARIO.json TRACKS.csv");
	if (o->path_count % 2)
		return pool_cli_usage_error(PROGRAM, "'%s' has no tracks file (give SCENARIO.json TRACKS.csv pairs)",
		                            pool_cli_arg(o->paths[o->path_count - 1]));
	return 0;
}

/// Loads shot k: its scenario, its tracks, its struck ball and starting values.
static int load_shot(const fit_cli *o, fit_shot *sh) {
	char err[512];
	if (pool_scenario_load_file_limit(sh->scenario_path, o->max_input, &sh->scenario, err, sizeof err) != 0) {
		fprintf(stderr, "%s: %s: %s\n", PROGRAM, pool_cli_arg(sh->scenario_path), err);
		return POOL_EXIT_BAD_INPUT;
	}
	char *text = NULL;
	size_t length = 0;
	if (pool_read_input(sh->tracks_path, o->max_input, &text, &length, err, sizeof err) != 0) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return POOL_EXIT_BAD_INPUT;
	}
	int status = fit_tracks_parse(sh->tracks_path, text, length, &sh->scenario, &sh->obs, &sh->obs_count, err,
	                              sizeof err);
	free(text);
	if (status) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return status;
	}
	const pool_scenario *sc = &sh->scenario;
	if (sc->has_strike) {
		sh->ball = sc->strike_ball;
		sh->start[FIT_SPEED] = sc->strike.speed;
		sh->start[FIT_PHI] = sc->strike.phi;
		sh->start[FIT_THETA] = sc->strike.theta;
		sh->start[FIT_A] = sc->strike.a;
		sh->start[FIT_B] = sc->strike.b;
		return 0;
	}
	if (!o->have_ball)
		return pool_cli_usage_error(PROGRAM, "%s: no strike: give one (the starting guess) or the struck ball "
		                            "(--ball ID)", pool_cli_arg(sh->scenario_path));
	sh->ball = o->ball;
	bool found = false;
	for (int k = 0; k < sc->ball_count; ++k)
		found = found || sc->balls[k].id == o->ball;
	if (!found)
		return pool_cli_usage_error(PROGRAM, "--ball: %s has no ball %d", pool_cli_arg(sh->scenario_path),
		                            (int)o->ball);
	if (!fit_guess_from_tracks(sh, &sc->def.params, &sh->start[FIT_PHI], &sh->start[FIT_SPEED])) {
		fprintf(stderr, "%s: %s: ball %d does not move 1 cm in the first 0.1 s of the tracks: give a starting "
		        "strike in the scenario\n", PROGRAM, pool_cli_arg(sh->tracks_path), (int)o->ball);
		return POOL_EXIT_BAD_INPUT;
	}
	return 0;
}

static int write_file(const char *prefix, const char *suffix, const char *text) {
	size_t n = strlen(prefix) + strlen(suffix) + 1;
	char *path = malloc(n);
	if (!path || !text) {
		free(path);
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	snprintf(path, n, "%s%s", prefix, suffix);
	int status = pool_cli_write_output(PROGRAM, path, text);
	free(path);
	return status;
}

int main(int argc, char **argv) {
	fit_cli o;
	int status = parse_options(argc, argv, &o);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	fit_problem pb = {.shot_count = o.path_count / 2};
	pb.shots = calloc((size_t)pb.shot_count, sizeof *pb.shots);
	if (!pb.shots) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	for (int s = 0; s < pb.shot_count && !status; ++s) {
		pb.shots[s].scenario_path = o.paths[2 * s];
		pb.shots[s].tracks_path = o.paths[2 * s + 1];
		status = load_shot(&o, &pb.shots[s]);
	}
	if (!status)
		status = fit_problem_setup(&pb, o.spec);
	long cpus = sysconf(_SC_NPROCESSORS_ONLN);
	pb.threads = o.threads ? o.threads : cpus > 0 ? cpus : 1;
	pb.linear = o.linear;
	fit_solution sol = {0};
	if (!status)
		status = fit_solve(&pb, &o.solver, &sol);
	if (!status) {
		char *json = fit_report_json(&pb, &sol);
		status = json ? pool_cli_write_output(PROGRAM, NULL, json) : POOL_EXIT_INTERNAL;
		if (!status && o.prefix) {
			status = write_file(o.prefix, ".json", json);
			if (!status) {
				char *svg = fit_svg(&pb, &sol);
				status = write_file(o.prefix, ".svg", svg);
				free(svg);
			}
		}
		free(json);
		if (!status && o.summary) {
			char *text = fit_report_text(&pb, &sol);
			if (text)
				fputs(text, stderr);
			free(text);
		}
		if (status == POOL_EXIT_INTERNAL && !json)
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
	}
	fit_solution_free(&sol);
	for (int s = 0; s < pb.shot_count; ++s) {
		pool_scenario_free(&pb.shots[s].scenario);
		free(pb.shots[s].obs);
	}
	free(pb.shots);
	return status;
}
