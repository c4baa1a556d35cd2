// pool-bench-fit: seconds for pool-fit on one shot and on 20 shots together. The shots are
// pool-fit-trials' synthetic ones (fit/synthetic.c: 3 balls, 1-3 m/s, tracks at 100 Hz with 1 mm
// of noise); one shot fits its strike (speed, phi, a, b), 20 shots their strikes and a shared
// cloth and cushion (mu_slide, mu_roll and the cushion's restitution: 83 parameters). Median and
// minimum of --runs fits each (default 3; --shots: other than 20 shots together), on every core, with the machine, under --models (default
// or thesis: the default cushion integrates each impact in 128 steps, so its shots cost more).
// docs/measurements.md "pool-fit".
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "fit/fit.h"

#define RUNS_MAX 20

static void bench(const char *name, int shots, const char *spec, const pool_models *models, int runs) {
	fit_synthetic *truth = calloc((size_t)shots, sizeof *truth);
	fit_problem pb = {.shot_count = shots, .threads = pool_bench_cpus_online() > 0 ? pool_bench_cpus_online() : 1};
	pb.shots = calloc((size_t)shots, sizeof *pb.shots);
	if (!truth || !pb.shots || fit_parse_spec(spec, pb.free_shot, pb.free_table) != 0)
		exit(1);
	pool_params table = pool_default_params();
	fit_random_table(7, pb.free_table, &table);
	for (int k = 0; k < shots; ++k)
		if (fit_synthetic_shot(7, k, &table, models, 100.0, 0.001, &truth[k], &pb.shots[k]) != 0)
			exit(1);
	if (fit_problem_setup(&pb, spec) != 0)
		exit(1);
	fit_options o = {.starts = 6, .max_iterations = 200, .seed = 1, .retries = 8, .quiet = getenv("POOL_BENCH_FIT_VERBOSE") == NULL};
	double seconds[RUNS_MAX], cpu[RUNS_MAX];
	fit_solution sol = {0};
	long observations = (long)(pb.n_obs / 2);
	for (int r = 0; r < runs; ++r) {
		fit_solution_free(&sol);
		double t0 = pool_bench_now_s(), c0 = pool_bench_cpu_s();
		if (fit_solve(&pb, &o, &sol) != 0)
			exit(1);
		seconds[r] = pool_bench_now_s() - t0;
		cpu[r] = pool_bench_cpu_s() - c0;
	}
	pool_bench_summary s = pool_bench_summarise(seconds, (size_t)runs), c = pool_bench_summarise(cpu, (size_t)runs);
	printf("%-22s %3d parameters, %6ld observations: median %.3f s, min %.3f s (CPU: median %.3f s, min %.3f "
	       "s); rms %.3f mm, %d starts, %s intervals\n", name, pb.p, observations, s.median, s.min, c.median,
	       c.min, 1e3 * sol.rms, sol.starts, sol.profiled ? "profile" : "wald");
	fit_solution_free(&sol);
	for (int k = 0; k < shots; ++k)
		free(pb.shots[k].obs);
	free(pb.shots);
	free(truth);
}

int main(int argc, char **argv) {
	int runs = 3, many = 20;
	const char *models_name = "default", *only = "both";
	for (int i = 1; i < argc; i += 2) {
		const char *v = i + 1 < argc ? argv[i + 1] : "";
		if (strcmp(argv[i], "--runs") == 0 && atoi(v) >= 1 && atoi(v) <= RUNS_MAX)
			runs = atoi(v);
		else if (strcmp(argv[i], "--models") == 0 && (strcmp(v, "default") == 0 || strcmp(v, "thesis") == 0))
			models_name = v;
		else if (strcmp(argv[i], "--shots") == 0 && atoi(v) >= 2 && atoi(v) <= 100)
			many = atoi(v);
		else if (strcmp(argv[i], "--only") == 0 && (strcmp(v, "one") == 0 || strcmp(v, "many") == 0))
			only = v;
		else {
			fprintf(stderr, "usage: pool-bench-fit [--runs 1-%d] [--models default|thesis] [--only one|many] [--shots 2-100]\n",
			        RUNS_MAX);
			return 2;
		}
	}
	pool_models models;
	pool_models_preset(models_name, &models);
	setvbuf(stdout, NULL, _IOLBF, 0); // each figure as it is measured: the 20-shot fit takes minutes
	char cpu[256];
	printf("pool-bench-fit: %s, %ld CPUs online, load %.2f; models %s; tracks at 100 Hz, sigma 1 mm; %d runs; "
	       "wall time, and the CPU time of every thread\n", pool_bench_cpu_model(cpu, sizeof cpu),
	       pool_bench_cpus_online(), pool_bench_load(), models_name, runs);
	if (strcmp(only, "many") != 0)
		bench("one shot, strike", 1, "strike", &models, runs);
	char many_name[64];
	snprintf(many_name, sizeof many_name, "%d shots, one table", many);
	if (strcmp(only, "one") != 0)
		bench(many_name, many, models.cushion == POOL_CUSHION_PETIT ? "strike,mu_slide,mu_roll,e_cushion"
		                                                                       : "strike,mu_slide,mu_roll,e_cushion_mathavan",
		      &models, runs);
	return 0;
}
