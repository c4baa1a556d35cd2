// pool-bench-quartic: times libpool's quartic solver against GSL's gsl_poly_complex_solve on the
// same pre-generated quartics and counts both solvers' failures against a long-double reference.
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_rng.h>

#include <pool/quartic.h>

#include "bench_quartic_ref.h"
#include "bench_util.h"
// libpool-internal: the fast algebraic path alone, to report how often it declines (fallback).
#include "../libpool/src/quartic_fast.h"

#define BQ_MAX_RUNS 100

typedef struct bq_opts {
	long count, runs, ref, show;
} bq_opts;

static long bq_show_left; // --show-failures: how many more failures to print
static bool bq_show_gsl;  // --show-gsl-failures: GSL's too

static void bq_usage(FILE *out) {
	fprintf(out,
	        "usage: pool-bench-quartic [--count N] [--runs N] [--ref N]\n"
	        "  Times pool_quartic_real_roots and GSL's gsl_poly_complex_solve on the same quartics\n"
	        "  (the 2012 thesis's random set and quartics of random ball pairs), prints median and\n"
	        "  minimum ns per call over the runs, and both solvers' failures against a long-double\n"
	        "  reference.\n"
	        "  --count N  quartics per set (default 1000000)\n"
	        "  --runs N   timed runs per solver and set (default 5, at most %d)\n"
	        "  --ref N    cases per set checked against the reference (default 20000)\n"
	        "  --show-failures N  print the first N well-conditioned cases pool gets wrong\n"
	        "  --show-gsl-failures N  the same, for the cases either solver gets wrong\n",
	        BQ_MAX_RUNS);
}

static int bq_parse_long(const char *flag, const char *s, long lo, long hi, long *out) {
	char *end;
	long v = s ? strtol(s, &end, 10) : 0;
	if (!s || *s == '\0' || *end != '\0' || v < lo || v > hi) {
		fprintf(stderr, "pool-bench-quartic: %s needs an integer in [%ld, %ld]\n", flag, lo, hi);
		return -1;
	}
	*out = v;
	return 0;
}

static double bq_now_ns(void) { return 1e9 * pool_bench_now_s(); }

static void bq_machine(void) {
	char model[256];
	printf("machine: %s, %ld logical cores; compiler: gcc %s\n", pool_bench_cpu_model(model, sizeof model),
	       pool_bench_cpus_online(), __VERSION__);
}

// GSL as a user would call it: coefficients in ascending order, exactly-zero leading terms dropped
// (gsl_poly_complex_solve rejects a zero leading coefficient), real roots = those with imaginary
// part exactly 0 (GSL returns real eigenvalues with a zero imaginary part), sorted.
typedef struct bq_gsl {
	gsl_poly_complex_workspace *ws[6]; // by number of coefficients (2 to 5)
} bq_gsl;

static int bq_gsl_solve(bq_gsl *g, const double c[5], double z[8], int *degree) {
	int first = 0;
	while (first < 5 && c[first] == 0.0)
		++first;
	int n = 4 - first; // degree
	*degree = n < 0 ? 0 : n;
	if (n <= 0)
		return 0;
	double a[5];
	for (int k = 0; k <= n; ++k)
		a[k] = c[4 - k];
	if (gsl_poly_complex_solve(a, (size_t)n + 1, g->ws[n + 1], z) != GSL_SUCCESS)
		return -1;
	return n;
}

static int bq_gsl_real_roots(bq_gsl *g, const double c[5], double roots[4]) {
	double z[8];
	int degree;
	int n = bq_gsl_solve(g, c, z, &degree);
	int m = 0;
	for (int k = 0; k < n; ++k) {
		if (z[2 * k + 1] == 0.0) {
			double x = z[2 * k];
			int j = m++;
			while (j > 0 && roots[j - 1] > x) {
				roots[j] = roots[j - 1];
				--j;
			}
			roots[j] = x;
		}
	}
	return m;
}

typedef pool_bench_summary bq_timing;

static bq_timing bq_summarise(double *ns, long runs) { return pool_bench_summarise(ns, (size_t)runs); }

static volatile double bq_sink;

static double bq_time_pool(const double *coeffs, long n) {
	double acc = 0.0, r[4];
	double t0 = bq_now_ns();
	for (long i = 0; i < n; ++i) {
		int m = pool_quartic_real_roots(coeffs + 5 * i, r);
		acc += m > 0 ? r[0] + m : 0.0;
	}
	double t1 = bq_now_ns();
	bq_sink = acc;
	return (t1 - t0) / (double)n;
}

static double bq_time_gsl(bq_gsl *g, const double *coeffs, long n) {
	double acc = 0.0, r[4];
	double t0 = bq_now_ns();
	for (long i = 0; i < n; ++i) {
		int m = bq_gsl_real_roots(g, coeffs + 5 * i, r);
		acc += m > 0 ? r[0] + m : 0.0;
	}
	double t1 = bq_now_ns();
	bq_sink = acc;
	return (t1 - t0) / (double)n;
}

static const double bq_window = 10.0; // smallest_root_in: collisions within the next 10 s

static double bq_time_smallest(const double *coeffs, long n) {
	double acc = 0.0, r;
	double t0 = bq_now_ns();
	for (long i = 0; i < n; ++i)
		if (pool_quartic_smallest_root_in(coeffs + 5 * i, 0.0, bq_window, &r) == 0)
			acc += r;
	double t1 = bq_now_ns();
	bq_sink = acc;
	return (t1 - t0) / (double)n;
}

// Failure tallies of one solver against the reference.
typedef struct bq_fail {
	long count;    // wrong number of real roots (well-conditioned cases)
	long roots;    // right count, a root outside 1e3 kappa u
	long smallest; // smallest non-negative root missed, spurious or outside tolerance
	long ill_count; // ill-conditioned cases whose count differs from the reference (reported only)
} bq_fail;

typedef struct bq_check {
	long checked, well, ill, unverified;
	bq_fail pool, gsl, pool_window; // pool_window: pool_quartic_smallest_root_in on [0, 10 s]
} bq_check;

static void bq_tally(bq_fail *f, const bq_ref *ref, int n, const double *roots) {
	if (ref->ill) {
		f->ill_count += n != ref->n_real;
		return;
	}
	if (n != ref->n_real) {
		++f->count;
	} else if (!bq_roots_match(ref, n, roots)) {
		++f->roots;
	}
	double r_ref, tol;
	bool has_ref = bq_ref_smallest_in(ref, 0.0, INFINITY, &r_ref, &tol);
	bool has = false;
	double r = 0.0;
	for (int i = 0; i < n && !has; ++i)
		if (roots[i] >= 0.0) {
			has = true;
			r = roots[i];
		}
	if (has != has_ref || (has && !(fabs(r - r_ref) <= tol)))
		++f->smallest;
}

static bq_check bq_verify(bq_gsl *g, const double *coeffs, long n) {
	bq_check ck;
	memset(&ck, 0, sizeof ck);
	for (long i = 0; i < n; ++i) {
		const double *c = coeffs + 5 * i;
		double z[8], rp[4], rg[4];
		int degree;
		int nz = bq_gsl_solve(g, c, z, &degree);
		bq_ref ref = bq_reference(c, nz > 0 ? z : NULL, nz);
		++ck.checked;
		if (!ref.ok) {
			++ck.unverified;
			continue;
		}
		if (ref.ill)
			++ck.ill;
		else
			++ck.well;
		int np = pool_quartic_real_roots(c, rp);
		int ng = bq_gsl_real_roots(g, c, rg);
		long before_pool = ck.pool.count + ck.pool.roots + ck.pool.smallest;
		long before_gsl = ck.gsl.count + ck.gsl.roots + ck.gsl.smallest;
		bq_tally(&ck.pool, &ref, np, rp);
		bq_tally(&ck.gsl, &ref, ng, rg);
		bool pool_failed = ck.pool.count + ck.pool.roots + ck.pool.smallest != before_pool;
		bool gsl_failed = ck.gsl.count + ck.gsl.roots + ck.gsl.smallest != before_gsl;
		if (bq_show_left > 0 && (pool_failed || (gsl_failed && bq_show_gsl))) {
			--bq_show_left;
			printf("%s failure: coeffs %.17g %.17g %.17g %.17g %.17g\n  pool:", pool_failed ? "pool" : "GSL", c[0], c[1],
			       c[2], c[3], c[4]);
			for (int k = 0; k < np; ++k)
				printf(" %.17g", rp[k]);
			printf("\n  GSL: ");
			for (int k = 0; k < ng; ++k)
				printf(" %.17g", rg[k]);
			printf("\n  reference:");
			for (int k = 0; k < ref.n_real; ++k)
				printf(" %.17g (kappa %.3g, tol %.3g)", ref.real[k], ref.kappa[k], ref.tol[k]);
			printf("\n");
		}
		if (!ref.ill) {
			double r, r_ref, tol;
			bool has = pool_quartic_smallest_root_in(c, 0.0, bq_window, &r) == 0;
			bool has_ref = bq_ref_smallest_in(&ref, 0.0, bq_window, &r_ref, &tol);
			if (has != has_ref || (has && !(fabs(r - r_ref) <= tol)))
				++ck.pool_window.smallest;
		}
	}
	return ck;
}

int main(int argc, char **argv) {
	bq_opts o = {1000000, 5, 20000, 0};
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		const char *v = i + 1 < argc ? argv[i + 1] : NULL;
		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			bq_usage(stdout);
			return 0;
		} else if (strcmp(a, "--count") == 0) {
			if (bq_parse_long("--count", v, 1, 100000000, &o.count))
				return 2;
			++i;
		} else if (strcmp(a, "--runs") == 0) {
			if (bq_parse_long("--runs", v, 1, BQ_MAX_RUNS, &o.runs))
				return 2;
			++i;
		} else if (strcmp(a, "--show-failures") == 0 || strcmp(a, "--show-gsl-failures") == 0) {
			if (bq_parse_long(a, v, 0, 1000000, &o.show))
				return 2;
			bq_show_gsl = strcmp(a, "--show-gsl-failures") == 0;
			++i;
		} else if (strcmp(a, "--ref") == 0) {
			if (bq_parse_long("--ref", v, 0, 100000000, &o.ref))
				return 2;
			++i;
		} else {
			fprintf(stderr, "pool-bench-quartic: unknown option '%s'\n", a);
			bq_usage(stderr);
			return 2;
		}
	}
	if (o.ref > o.count)
		o.ref = o.count;
	bq_show_left = o.show;
	gsl_set_error_handler_off();
	bq_gsl g;
	for (int k = 2; k <= 5; ++k)
		g.ws[k] = gsl_poly_complex_workspace_alloc((size_t)k);
	g.ws[0] = g.ws[1] = NULL;

	double *sets[2];
	const char *names[2] = {"thesis", "ball pairs"};
	for (int s = 0; s < 2; ++s) {
		sets[s] = malloc(sizeof(double) * 5 * (size_t)o.count);
		if (!sets[s]) {
			fprintf(stderr, "pool-bench-quartic: out of memory for %ld quartics\n", o.count);
			return 1;
		}
	}
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 20120501UL);
	bq_gen_thesis(rng, sets[0], o.count);
	bq_gen_balls(rng, sets[1], o.count);
	gsl_rng_free(rng);

	bq_machine();
	printf("data: %ld pre-generated quartics per set (gsl_rng_mt19937, fixed seed), %ld timed runs each\n"
	       "  thesis: |a_i| log-uniform in [1e-6, 1e6], random signs\n"
	       "  ball pairs: random pairs on a 2.54 x 1.27 m table, sliding/rolling, up to 8 m/s; 5%% touching,\n"
	       "    10%% rolling the same way (5%% a4 = a3 = 0 exactly, 5%% a4 tiny), 10%% one ball at rest\n"
	       "  GSL gets the polynomial without exactly-zero leading coefficients (it rejects a zero\n"
	       "  leading coefficient), and its real roots are those with a zero imaginary part.\n\n",
	       o.count, o.runs);

	double pool_ns[2][BQ_MAX_RUNS], gsl_ns[2][BQ_MAX_RUNS], win_ns[BQ_MAX_RUNS];
	for (long r = 0; r < o.runs; ++r) {
		for (int s = 0; s < 2; ++s) {
			pool_ns[s][r] = bq_time_pool(sets[s], o.count);
			gsl_ns[s][r] = bq_time_gsl(&g, sets[s], o.count);
		}
		win_ns[r] = bq_time_smallest(sets[1], o.count);
	}
	printf("%-11s %-34s %11s %11s %9s\n", "set", "solver", "median ns", "min ns", "GSL/pool");
	for (int s = 0; s < 2; ++s) {
		bq_timing tp = bq_summarise(pool_ns[s], o.runs), tg = bq_summarise(gsl_ns[s], o.runs);
		printf("%-11s %-34s %11.1f %11.1f %9s\n", names[s], "pool_quartic_real_roots", tp.median, tp.min, "");
		printf("%-11s %-34s %11.1f %11.1f %8.2fx\n", names[s], "gsl_poly_complex_solve", tg.median, tg.min,
		       tg.median / tp.median);
	}
	bq_timing tw = bq_summarise(win_ns, o.runs);
	printf("%-11s %-34s %11.1f %11.1f\n\n", names[1], "pool_quartic_smallest_root_in[0,10]", tw.median, tw.min);
	// How often pool_quartic_real_roots's algebraic path declines and the isolation solver runs.
	for (int s = 0; s < 2; ++s) {
		long declined = 0;
		double r[4];
		for (long i = 0; i < o.count; ++i)
			declined += pool_quartic_fast_real_roots(sets[s] + 5 * i, r) < 0;
		printf("%-11s fast path declined (isolation solver used): %ld of %ld (%.2f%%)\n", names[s], declined, o.count,
		       100.0 * (double)declined / (double)o.count);
	}
	printf("\n");

	if (o.ref > 0) {
		printf("failures against the long-double reference (first %ld quartics of each set; a root fails\n"
		       "when its error exceeds 1e3 kappa u; ill-conditioned: kappa u > 1e-9 or a complex pair with\n"
		       "|Im|/|z| < 1e-3, where only a differing root count is reported):\n",
		       o.ref);
		printf("%-11s %7s %6s %6s | %-27s | %-27s | %s\n", "set", "well", "ill", "unver", "pool: count roots smallest",
		       "GSL: count roots smallest", "ill, count differs: pool GSL");
		for (int s = 0; s < 2; ++s) {
			bq_check ck = bq_verify(&g, sets[s], o.ref);
			printf("%-11s %7ld %6ld %6ld | %11ld %5ld %8ld | %10ld %5ld %8ld | %21ld %5ld\n", names[s], ck.well, ck.ill,
			       ck.unverified, ck.pool.count, ck.pool.roots, ck.pool.smallest, ck.gsl.count, ck.gsl.roots,
			       ck.gsl.smallest, ck.pool.ill_count, ck.gsl.ill_count);
			if (s == 1)
				printf("%-11s pool_quartic_smallest_root_in on [0, 10 s]: %ld failures on well-conditioned cases\n",
				       names[s], ck.pool_window.smallest);
		}
	}
	for (int k = 2; k <= 5; ++k)
		gsl_poly_complex_workspace_free(g.ws[k]);
	free(sets[0]);
	free(sets[1]);
	return 0;
}
