// pool-fit-trials: does pool-fit find the truth, and are its intervals honest? Seeded synthetic
// trials: a random layout and strike (and, when the table's parameters are fitted, a random
// table), simulated by libpool, recorded at --rate frames/s with Gaussian position noise of each
// --sigma, then fitted from a perturbed start exactly as pool-fit fits. Prints, per parameter and
// noise level, how often the known value lies inside the reported 95 % interval and the median
// interval width; with --min-coverage, exits 1 when a parameter's coverage falls below it, and
// with --shrink-tolerance when the widths do not scale with the noise.
// docs/commands.md "pool-fit", docs/measurements.md "pool-fit".
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "fit/fit.h"

#define PROGRAM "pool-fit-trials"
#define TRIALS_MAX_SIGMAS 8
// A trial whose fit ends with an rms residual above this many sigma found no fit of the tracks (a
// local minimum): it is counted as a failure, and its intervals as misses.
#define TRIALS_FAILED_RMS 1.5

static const char usage_text[] =
	"usage: pool-fit-trials [--trials N] [--first K] [--sigma M[,M...]] [--rate HZ] [--fit NAMES] [--seed S]\n"
	"                       [--models SET] [--threads N] [--min-coverage P] [--shrink-tolerance T]\n"
	"                       [--verbose]\n"
	"\n"
	"Seeded synthetic trials of pool-fit: random shots simulated from known values, recorded with\n"
	"Gaussian position noise, fitted; prints how often each known value lies inside the reported\n"
	"95 % interval, and the median interval width, per noise level.\n"
	"\n"
	"  --trials N        trials (default 200)\n"
	"  --first K         the first trial's number (default 0): trials K to K + N - 1, each the\n"
	"                    same shot whatever K (a trial of a campaign run again alone)\n"
	"  --sigma LIST      position noise sd in m, comma-separated (default 0.001); the same trials\n"
	"                    run at each level\n"
	"  --rate HZ         frames per second of the tracks (default 100)\n"
	"  --fit NAMES       as pool-fit --fit (default strike); fitted table parameters get random\n"
	"                    true values in their measured ranges\n"
	"  --seed S          seed of the trials (default 1)\n"
	"  --models SET      the laws the shots are made and fitted with: default or thesis\n"
	"  --threads N       threads per fit (default: online CPUs)\n"
	"  --min-coverage P  exit 1 when a parameter's coverage is below P (e.g. 0.9)\n"
	"  --shrink-tolerance T  exit 1 when a median width does not scale with sigma: its ratio to\n"
	"                    the previous level's, over the ratio of the sigmas, is off 1 by more than T\n"
	"  --verbose         one line per trial: (fit - truth) / se and [the interval's ends - truth] / se\n";

// ---- one trial --------------------------------------------------------------------------------

typedef struct outcome {
	bool solved;     ///< the fit ran
	bool failed;     ///< its rms is above TRIALS_FAILED_RMS sigma
	double rms;
	double seconds;
	int iterations;
} outcome;

typedef struct trials_options {
	long trials;
	long first; ///< the first trial's number
	double sigmas[TRIALS_MAX_SIGMAS];
	int sigma_count;
	double rate;
	const char *spec;
	unsigned long seed;
	pool_models models;
	const char *models_name;
	long threads;
	double min_coverage;
	double shrink_tolerance;
	bool verbose;
} trials_options;

/// Trial `index` at noise sigma: truth[], the fit's estimates and what each parameter is. Returns
/// the number of parameters, or -1 when the trial could not be set up.
static int run_trial(const trials_options *o, long index, double sigma, double *truth, fit_estimate *est,
                     const fit_param_info **info, outcome *out) {
	memset(out, 0, sizeof *out);
	fit_problem pb = {.shot_count = 1, .threads = o->threads};
	fit_shot shot;
	fit_synthetic made;
	if (fit_parse_spec(o->spec, pb.free_shot, pb.free_table) != 0)
		return -1; // the message is printed
	pool_params table = pool_default_params();
	fit_random_table(o->seed * 0x9E3779B97F4A7C15ULL + (uint64_t)index, pb.free_table, &table);
	if (fit_synthetic_shot(o->seed, index, &table, &o->models, o->rate, sigma, &made, &shot) != 0)
		return -1;
	pb.shots = &shot;
	const pool_strike strike = made.strike;
	const pool_sim_def def = {.params = made.params};
	int status = fit_problem_setup(&pb, o->spec);
	// The true vector, in the problem's order.
	pool_params true_params = def.params;
	double true_shot[FIT_SHOT_PARAMS] = {strike.speed, strike.phi, strike.theta, strike.a, strike.b, 0.0};
	for (int j = 0; status == 0 && j < pb.p; ++j) {
		int s, k;
		info[j] = fit_param_of(&pb, j, &s, &k);
		truth[j] = s < 0 ? *fit_table_field(&true_params, k) : true_shot[k];
		if (s >= 0 && k == FIT_PHI) // pool-fit reports phi in (-180, 180]
			truth[j] = remainder(truth[j], 2.0 * 3.14159265358979323846);
	}
	fit_options fo = {.starts = 6, .max_iterations = 200, .seed = 1, .retries = 8, .quiet = true};
	fit_solution sol = {0};
	if (status == 0 && fit_solve(&pb, &fo, &sol) == 0) {
		out->solved = true;
		out->rms = sol.rms;
		out->failed = sol.rms > TRIALS_FAILED_RMS * sigma;
		out->seconds = sol.seconds;
		out->iterations = sol.iterations;
		memcpy(est, sol.est, (size_t)pb.p * sizeof *est);
	}
	fit_solution_free(&sol);
	free(shot.obs);
	return status ? -1 : pb.p;
}

static int by_value(const void *a, const void *b) {
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static int parse(int argc, char **argv, trials_options *o) {
	*o = (trials_options){.trials = 200, .sigmas = {0.001}, .sigma_count = 1, .rate = 100.0, .spec = "strike",
	                      .seed = 1, .models = pool_default_models(), .models_name = "default",
	                      .min_coverage = -1.0, .shrink_tolerance = -1.0};
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			fputs(usage_text, stdout);
			exit(0);
		}
		if (strcmp(a, "--verbose") == 0) {
			o->verbose = true;
			continue;
		}
		if (!v)
			return pool_cli_usage_error(PROGRAM, "unknown option or missing value: '%s'", pool_cli_arg(a));
		++i;
		long n = 0;
		if (strcmp(a, "--trials") == 0 && pool_cli_parse_count(v, &n) && n >= 1)
			o->trials = n;
		else if (strcmp(a, "--first") == 0 && pool_cli_parse_count(v, &n) && n >= 0)
			o->first = n;
		else if (strcmp(a, "--rate") == 0 && pool_cli_parse_double(v, &o->rate) && o->rate > 0.0)
			continue;
		else if (strcmp(a, "--fit") == 0)
			o->spec = v;
		else if (strcmp(a, "--models") == 0 && pool_models_preset(v, &o->models) == POOL_OK)
			o->models_name = v;
		else if (strcmp(a, "--seed") == 0 && pool_cli_parse_count(v, &n) && n >= 1)
			o->seed = (unsigned long)n;
		else if (strcmp(a, "--threads") == 0 && pool_cli_parse_count(v, &n) && n >= 1 && n <= 1024)
			o->threads = n;
		else if (strcmp(a, "--min-coverage") == 0 && pool_cli_parse_double(v, &o->min_coverage))
			continue;
		else if (strcmp(a, "--shrink-tolerance") == 0 && pool_cli_parse_double(v, &o->shrink_tolerance))
			continue;
		else if (strcmp(a, "--sigma") == 0) {
			o->sigma_count = 0;
			for (const char *p = v; *p && o->sigma_count < TRIALS_MAX_SIGMAS;) {
				char item[64];
				size_t len = strcspn(p, ",");
				snprintf(item, sizeof item, "%.*s", (int)(len < 63 ? len : 63), p);
				if (!pool_cli_parse_double(item, &o->sigmas[o->sigma_count]) || o->sigmas[o->sigma_count] <= 0.0)
					return pool_cli_usage_error(PROGRAM, "--sigma: '%s' is not a list of noise levels in metres",
					                            pool_cli_arg(v));
				o->sigma_count++;
				p += len + (p[len] == ',');
			}
		} else
			return pool_cli_usage_error(PROGRAM, "%s: bad option or value '%s'", pool_cli_arg(a), pool_cli_arg(v));
	}
	if (!o->threads) {
		long cpus = sysconf(_SC_NPROCESSORS_ONLN);
		o->threads = cpus > 0 ? cpus : 1;
	}
	return 0;
}

int main(int argc, char **argv) {
	trials_options o;
	int status = parse(argc, argv, &o);
	if (status)
		return status;
	const int max_p = FIT_TABLE_PARAMS + FIT_SHOT_PARAMS;
	double *truth = malloc((size_t)max_p * sizeof *truth);
	fit_estimate *est = malloc((size_t)max_p * sizeof *est);
	const fit_param_info *info[FIT_TABLE_PARAMS + FIT_SHOT_PARAMS] = {0};
	long *covered = calloc((size_t)(o.sigma_count * max_p), sizeof *covered);
	double *widths = malloc((size_t)(o.sigma_count * max_p) * (size_t)o.trials * sizeof *widths);
	if (!truth || !est || !covered || !widths) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	int p = 0;
	bool below = false;
	double previous_width[FIT_TABLE_PARAMS + FIT_SHOT_PARAMS] = {0};
	for (int level = 0; level < o.sigma_count; ++level) {
		double sigma = o.sigmas[level], seconds = 0.0;
		long failed = 0, unsolved = 0;
		for (long t = 0; t < o.trials; ++t) {
			outcome out;
			p = run_trial(&o, o.first + t, sigma, truth, est, info, &out);
			if (p <= 0)
				return POOL_EXIT_BAD_INPUT;
			seconds += out.seconds;
			unsolved += !out.solved;
			failed += out.solved && out.failed;
			for (int j = 0; j < p; ++j) {
				bool in = out.solved && !out.failed && truth[j] >= est[j].ci_low && truth[j] <= est[j].ci_high;
				covered[level * max_p + j] += in;
				widths[((size_t)level * (size_t)max_p + (size_t)j) * (size_t)o.trials + (size_t)t] =
				    out.solved ? est[j].ci_high - est[j].ci_low : INFINITY;
			}
			if (o.verbose) {
				printf("trial %ld sigma %g: %s rms %.3g mm, %d iterations, %.3f s; (fit - truth) / se:", o.first + t, sigma,
				       !out.solved ? "unsolved" : out.failed ? "FAILED" : "ok", 1e3 * out.rms, out.iterations,
				       out.seconds);
				for (int j = 0; out.solved && j < p; ++j)
					printf(" %s %.2f [%.2f %.2f]%s", info[j]->name, (est[j].value - truth[j]) / est[j].se,
					       (est[j].ci_low - truth[j]) / est[j].se, (est[j].ci_high - truth[j]) / est[j].se,
					       truth[j] >= est[j].ci_low && truth[j] <= est[j].ci_high ? "" : " MISSED");
				printf("\n");
			}
		}
		printf("%s: %ld trials, sigma %g m, %g Hz, --fit %s, models %s: %ld failed (rms > %.1f sigma), %ld "
		       "unsolved, %.3f s per fit\n", PROGRAM, o.trials, sigma, o.rate, o.spec, o.models_name, failed,
		       TRIALS_FAILED_RMS, unsolved, seconds / (double)o.trials);
		printf("  %-12s %9s %16s %12s\n", "parameter", "coverage", "median width", "width ratio");
		for (int j = 0; j < p; ++j) {
			double *w = &widths[((size_t)level * (size_t)max_p + (size_t)j) * (size_t)o.trials];
			qsort(w, (size_t)o.trials, sizeof *w, by_value);
			double median = fit_shown(info[j], w[o.trials / 2]);
			double share = (double)covered[level * max_p + j] / (double)o.trials;
			char ratio[32] = "";
			if (level > 0) {
				double r = median / previous_width[j], expected = sigma / o.sigmas[level - 1];
				snprintf(ratio, sizeof ratio, "%.3f", r);
				below = below || (o.shrink_tolerance >= 0.0 && fabs(r / expected - 1.0) > o.shrink_tolerance);
			}
			printf("  %-12s %8.1f%% %16.4g %12s  (%s)\n", info[j]->name, 100.0 * share, median, ratio, info[j]->unit);
			previous_width[j] = median;
			below = below || (o.min_coverage >= 0.0 && share < o.min_coverage);
		}
	}
	free(truth);
	free(est);
	free(covered);
	free(widths);
	return below ? 1 : 0;
}
