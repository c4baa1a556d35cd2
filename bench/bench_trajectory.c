// pool-bench-trajectory: the C reference for Sim.trajectory (python/libpool): every ball of a
// frozen 8-ball break at 8 m/s at N evenly spaced times, by a loop of pool_sim_state_at and by one
// pool_sim_states_at call. Prints the median and minimum of the runs and the machine.
//     pool-bench-trajectory [--times N] [--runs R]
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "pool/pool.h"

int main(int argc, char **argv) {
	int count = 10000, runs = 21;
	for (int i = 1; i + 1 < argc; i += 2) {
		if (strcmp(argv[i], "--times") == 0)
			count = atoi(argv[i + 1]);
		else if (strcmp(argv[i], "--runs") == 0)
			runs = atoi(argv[i + 1]);
	}
	if (count < 1 || runs < 1) {
		fprintf(stderr, "usage: pool-bench-trajectory [--times N] [--runs R]\n");
		return 2;
	}
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim;
	pool_error err;
	if (pool_sim_create(&def, &sim, &err) != POOL_OK)
		return fprintf(stderr, "%s\n", err.message), 1;
	pool_ball_state balls[16];
	int n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 0.0, balls, 16);
	for (int i = 0; i < n; ++i)
		pool_sim_add_ball(sim, &balls[i], NULL);
	pool_strike s = pool_break_strike(8.0);
	if (pool_sim_strike(sim, 0, &s, &err) != POOL_OK || pool_sim_run(sim) != POOL_OK)
		return 1;
	const double end = pool_sim_end_time(sim);
	double *times = malloc((size_t)count * sizeof *times);
	pool_ball_state *out = malloc((size_t)count * (size_t)n * sizeof *out);
	double *loop = malloc((size_t)runs * sizeof *loop), *one = malloc((size_t)runs * sizeof *one);
	if (!times || !out || !loop || !one)
		return 1;
	for (int k = 0; k < count; ++k)
		times[k] = end * k / (count > 1 ? count - 1 : 1);
	double check = 0.0;
	for (int r = 0; r < runs; ++r) {
		double t0 = pool_bench_now_s();
		for (int k = 0; k < count; ++k)
			pool_sim_state_at(sim, times[k], out + (size_t)k * (size_t)n);
		double t1 = pool_bench_now_s();
		pool_sim_states_at(sim, times, count, out, NULL);
		double t2 = pool_bench_now_s();
		loop[r] = t1 - t0;
		one[r] = t2 - t1;
		check += out[(size_t)(count - 1) * (size_t)n].pos.x;
	}
	pool_bench_summary a = pool_bench_summarise(loop, (size_t)runs), b = pool_bench_summarise(one, (size_t)runs);
	int events;
	pool_sim_events(sim, &events);
	char cpu[256];
	printf("machine: %s, %ld CPUs online\n", pool_bench_cpu_model(cpu, sizeof cpu), pool_bench_cpus_online());
	printf("break: %d balls, %d events, %.3f s; %d times, %d runs (check %.6f)\n", n, events, end, count, runs,
	       check / runs);
	printf("C loop of pool_sim_state_at: median %.3f ms, min %.3f ms\n", a.median * 1e3, a.min * 1e3);
	printf("C pool_sim_states_at:        median %.3f ms, min %.3f ms\n", b.median * 1e3, b.min * 1e3);
	free(times), free(out), free(loop), free(one);
	pool_sim_destroy(sim);
	return 0;
}
