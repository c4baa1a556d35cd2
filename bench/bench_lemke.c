// pool-bench-lemke: how long libpool's lexicographic Lemke (libpool/src/lemke.h) takes on the
// friction LCPs of LINK steps (random clusters with the real structure: K contacts, n = 16 K,
// tests/unit/lemke_friction_lcp.h). For each K: the median and minimum time of a cold solve over
// several random problems, the median pivots, the largest residual, and the warm start: the
// next step of the same cluster (velocities changed by 1e-6 relative) solved from the first
// step's basis. Prints the machine. Usage: pool-bench-lemke [problems per K, default 9].
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "lemke.h"
#include "lemke_friction_lcp.h"

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

// Time of one solve in seconds: the minimum of at least 3 runs, repeated until 20 ms have passed
// (small K; the minimum also filters out other work on a shared machine).
static double time_solve(int n, const double *A, const double *b, double *z, int *basis, const int *basis0,
                         void *ws, pool_lemke_stats *st, pool_lemke_status *status) {
	double best = 1e300, spent = 0.0;
	int runs = 0;
	do {
		if (basis0)
			for (int i = 0; i < n; ++i)
				basis[i] = basis0[i];
		double t0 = pool_bench_now_s();
		*status = pool_lemke_solve(n, A, b, z, basis0 ? basis : NULL, 0, ws, st);
		double t = pool_bench_now_s() - t0;
		best = t < best ? t : best;
		spent += t;
		++runs;
	} while (spent < 0.02 || runs < 3);
	return best;
}

int main(int argc, char **argv) {
	int problems = argc > 1 ? atoi(argv[1]) : 9;
	if (problems < 1 || problems > 1000) {
		fprintf(stderr, "pool-bench-lemke: problems per K must be 1..1000\n");
		return 2;
	}
	char model[256];
	printf("machine: %s, %ld cores online\n", pool_bench_cpu_model(model, sizeof model), pool_bench_cpus_online());
	printf("lexicographic Lemke on random LINK friction LCPs (eta = 14), %d problems per K\n", problems);
	printf("%4s %5s %6s | %10s %10s | %7s %6s | %9s | %10s %9s\n", "K", "n", "balls", "cold med", "cold min",
	       "pivots", "basic", "max resid", "warm med", "warm used");
	const int Ks[] = {1, 2, 5, 10, 20, 50, 100};
	int failed = 0;
	for (size_t a = 0; a < sizeof Ks / sizeof *Ks; ++a) {
		int K = Ks[a], n = 16 * K, balls = flcp_balls_for(K);
		int count = K >= 100 ? (problems + 2) / 3 : problems;
		double *A = malloc((size_t)n * (size_t)n * sizeof *A), *b = malloc((size_t)n * sizeof *b);
		double *b2 = malloc((size_t)n * sizeof *b2), *z = malloc((size_t)n * sizeof *z);
		double *A2 = malloc((size_t)n * (size_t)n * sizeof *A2);
		flcp_dir *dirs = malloc((size_t)(15 * K) * sizeof *dirs);
		int *basis = malloc((size_t)n * sizeof *basis), *basis0 = malloc((size_t)n * sizeof *basis0);
		void *ws = malloc(pool_lemke_workspace_bytes(n));
		double *cold = malloc((size_t)count * sizeof *cold), *warm = malloc((size_t)count * sizeof *warm);
		int *pivots = malloc((size_t)count * sizeof *pivots);
		if (!A || !b || !b2 || !z || !A2 || !dirs || !basis || !basis0 || !ws || !cold || !warm || !pivots) {
			fprintf(stderr, "pool-bench-lemke: out of memory at K = %d\n", K);
			return 1;
		}
		double max_res = 0.0;
		int used = 0, basic = 0;
		for (int p = 0; p < count; ++p) {
			uint64_t seed = 9000 + (uint64_t)p;
			flcp_generate(K, balls, seed, 0, 0.0, A, b, dirs, NULL);
			flcp_generate(K, balls, seed, 0, 1e-6, A2, b2, dirs, NULL); // the next step: same A
			pool_lemke_stats st;
			pool_lemke_status s;
			cold[p] = time_solve(n, A, b, z, basis, NULL, ws, &st, &s);
			pivots[p] = st.pivots;
			max_res = st.residual > max_res ? st.residual : max_res;
			if (s != POOL_LEMKE_SOLVED) {
				fprintf(stderr, "pool-bench-lemke: K = %d problem %d: status %d\n", K, p, s);
				++failed;
				warm[p] = cold[p];
				continue;
			}
			pool_lemke_solve(n, A, b, z, basis0, 0, ws, &st); // the first step's basis
			for (int i = 0; i < n; ++i)
				basic += basis0[i];
			warm[p] = time_solve(n, A2, b2, z, basis, basis0, ws, &st, &s);
			used += st.warm;
			max_res = st.residual > max_res ? st.residual : max_res;
			if (s != POOL_LEMKE_SOLVED) {
				fprintf(stderr, "pool-bench-lemke: K = %d problem %d (warm): status %d\n", K, p, s);
				++failed;
			}
		}
		pool_bench_summary c = pool_bench_summarise(cold, (size_t)count);
		pool_bench_summary w = pool_bench_summarise(warm, (size_t)count);
		qsort(pivots, (size_t)count, sizeof *pivots, cmp_int);
		printf("%4d %5d %6d | %7.3f ms %7.3f ms | %7d %6d | %9.1e | %7.3f ms %5d/%-3d\n", K, n, balls, 1e3 * c.median,
		       1e3 * c.min, pivots[count / 2], basic / count, max_res, 1e3 * w.median, used, count);
		fflush(stdout);
		free(A), free(b), free(b2), free(z), free(A2), free(dirs), free(basis), free(basis0), free(ws);
		free(cold), free(warm), free(pivots);
	}
	return failed ? 1 : 0;
}
