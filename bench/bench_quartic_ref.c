// pool-bench-quartic: long-double reference roots, independent of the solvers under test.
//
// How the reference is built (and why it can be trusted for well-conditioned cases):
// 1. The double coefficients are the exact problem (docs/quartic.md: reference roots are those of the
//    rounded coefficients). Exactly-zero leading coefficients lower the degree; an exactly-zero
//    constant term gives an exact root 0 (factored out exactly).
// 2. All remaining complex roots are found together by the Aberth-Ehrlich iteration in long
//    double (64-bit mantissa, u_ld = 2^-64), a method unrelated to both solvers under test. The
//    solvers' output is only used as starting points; the iteration converges from any start.
// 3. A root with |Im z| <= 1e-9 |z| is real (a well-conditioned real root, kappa <= 1e-9 / u,
//    gets |Im z| of order kappa u_ld |z| <= 1e-12 |z|); one with |Im z| >= 1e-3 |z| is complex;
//    in between the case is ill-conditioned (docs/quartic.md) and only reported.
// 4. Each real root is polished by Newton's method in long double and then VERIFIED: p changes
//    sign (evaluated in long double) between r - h and r + h with h = 100 kappa u |r|, ten times
//    tighter than the tolerance solvers are judged by, and neighbouring brackets do not overlap.
//    So for a well-conditioned case the reference count and roots are certain: each real root
//    is isolated by an exact-enough sign change, and every other root is off the real axis by at
//    least 1e-3 |z|. A case whose verification fails is counted as "reference unverified".
#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_quartic_ref.h"

typedef long double complex bq_lcx;

static const double bq_u = 0x1p-53;

static void bq_eval_c(const long double *a, int n, bq_lcx z, bq_lcx *p, bq_lcx *dp) {
	bq_lcx f = a[n], d = 0.0L;
	for (int k = n - 1; k >= 0; --k) {
		d = d * z + f;
		f = f * z + a[k];
	}
	*p = f;
	*dp = d;
}

static long double bq_eval_r(const long double *a, int n, long double x, long double *dp, long double *abs_sum) {
	long double f = a[n], d = 0.0L, s = fabsl(a[n]), ax = fabsl(x);
	for (int k = n - 1; k >= 0; --k) {
		d = d * x + f;
		f = f * x + a[k];
		s = s * ax + fabsl(a[k]);
	}
	if (dp)
		*dp = d;
	if (abs_sum)
		*abs_sum = s;
	return f;
}

// Aberth-Ehrlich simultaneous iteration for all n roots of a (coefficient of x^k in a[k]).
static void bq_aberth(const long double *a, int n, bq_lcx *z) {
	for (int it = 0; it < 400; ++it) {
		long double worst = 0.0L;
		for (int k = 0; k < n; ++k) {
			bq_lcx p, dp;
			bq_eval_c(a, n, z[k], &p, &dp);
			if (p == 0.0L)
				continue;
			bq_lcx w = p / dp;
			bq_lcx s = 0.0L;
			for (int j = 0; j < n; ++j)
				if (j != k && z[j] != z[k])
					s += 1.0L / (z[k] - z[j]);
			bq_lcx corr = w / (1.0L - w * s);
			if (!isfinite(creall(corr)) || !isfinite(cimagl(corr)))
				continue;
			z[k] -= corr;
			long double rel = cabsl(corr) / fmaxl(cabsl(z[k]), LDBL_MIN);
			if (rel > worst)
				worst = rel;
		}
		if (worst < 1e-18L)
			break;
	}
}

static int bq_cmp_ld(const void *x, const void *y) {
	long double a = *(const long double *)x, b = *(const long double *)y;
	return (a > b) - (a < b);
}

bq_ref bq_reference(const double c[5], const double *start, int n_start) {
	bq_ref ref;
	memset(&ref, 0, sizeof ref);
	long double a[5];
	for (int k = 0; k < 5; ++k)
		a[k] = c[4 - k];
	int n = 4;
	while (n >= 0 && a[n] == 0.0L)
		--n;
	ref.degree = n < 0 ? 0 : n;
	ref.ok = true;
	if (n <= 0)
		return ref;
	int zeros = 0;
	while (a[zeros] == 0.0L)
		++zeros;
	int m = n - zeros;
	const long double *b = a + zeros;

	long double real[4];
	int n_real = 0;
	if (m > 0) {
		bq_lcx z[4];
		bool use_start = start && n_start == m;
		for (int k = 0; use_start && k < m; ++k)
			use_start = isfinite(start[2 * k]) && isfinite(start[2 * k + 1]);
		long double radius = powl(fabsl(b[0] / b[m]), 1.0L / m);
		for (int k = 0; k < m; ++k) {
			// Starting points slightly apart (Aberth needs distinct ones).
			bq_lcx nudge = cexpl(I * (0.7L + 2.0L * k));
			if (use_start) {
				bq_lcx s0 = start[2 * k] + I * (long double)start[2 * k + 1];
				z[k] = s0 + 1e-7L * (cabsl(s0) + radius) * nudge;
			} else {
				z[k] = radius * cexpl(I * (0.4L + 6.283185307179586L * k / m));
			}
		}
		bq_aberth(b, m, z);
		int n_complex = 0;
		for (int k = 0; k < m; ++k) {
			long double az = cabsl(z[k]), im = fabsl(cimagl(z[k]));
			if (!(az > 0.0L) || !isfinite(az)) {
				ref.ok = false;
				return ref;
			}
			if (im <= 1e-9L * az) {
				real[n_real++] = creall(z[k]);
			} else {
				++n_complex;
				if (im < 1e-3L * az)
					ref.ill = true;
			}
		}
		if (n_complex % 2) {
			ref.ok = false;
			return ref;
		}
		qsort(real, n_real, sizeof real[0], bq_cmp_ld);
		long double lo_prev = -INFINITY;
		for (int i = 0; i < n_real; ++i) {
			long double r = real[i], dp, s;
			for (int it = 0; it < 8; ++it) {
				long double f = bq_eval_r(b, m, r, &dp, &s);
				if (f == 0.0L || dp == 0.0L)
					break;
				long double step = f / dp;
				r -= step;
				if (fabsl(step) <= 1e-19L * fabsl(r))
					break;
			}
			real[i] = r;
			// Condition number and tolerance on the full polynomial (zero roots included).
			long double s_full;
			bq_eval_r(a, n, r, &dp, &s_full);
			long double kappa = s_full / (fabsl(r) * fabsl(dp));
			ref.kappa[i] = (double)kappa;
			if (!(kappa * bq_u <= 1e-9L))
				ref.ill = true;
			long double h = 100.0L * bq_u * kappa * fabsl(r);
			if (!ref.ill) {
				long double fl = bq_eval_r(b, m, r - h, NULL, NULL);
				long double fr = bq_eval_r(b, m, r + h, NULL, NULL);
				if (!((fl < 0.0L && fr > 0.0L) || (fl > 0.0L && fr < 0.0L)) || r - h <= lo_prev)
					ref.ok = false;
			}
			lo_prev = r + h;
		}
	}
	// Merge the exact zero roots (kappa 0, tolerance 0: they must come out exactly 0).
	int k = 0, nz = zeros;
	double kap[4];
	for (int i = 0; i < n_real; ++i)
		kap[i] = ref.kappa[i];
	for (int i = 0; i < n_real; ++i) {
		while (nz > 0 && real[i] > 0.0L) {
			ref.real[k] = 0.0;
			ref.kappa[k] = 0.0;
			ref.tol[k++] = 0.0;
			--nz;
		}
		ref.real[k] = (double)real[i];
		ref.kappa[k] = kap[i];
		ref.tol[k++] = 1e3 * bq_u * kap[i] * fabs((double)real[i]);
	}
	while (nz-- > 0) {
		ref.real[k] = 0.0;
		ref.kappa[k] = 0.0;
		ref.tol[k++] = 0.0;
	}
	ref.n_real = k;
	return ref;
}

bool bq_roots_match(const bq_ref *ref, int n, const double *roots) {
	if (n != ref->n_real)
		return false;
	for (int i = 0; i < n; ++i)
		if (!(fabs(roots[i] - ref->real[i]) <= fmax(ref->tol[i], DBL_TRUE_MIN)))
			return false;
	return true;
}

bool bq_ref_smallest_in(const bq_ref *ref, double lo, double hi, double *root, double *tol) {
	for (int i = 0; i < ref->n_real; ++i)
		if (ref->real[i] >= lo && ref->real[i] <= hi) {
			*root = ref->real[i];
			*tol = fmax(ref->tol[i], DBL_TRUE_MIN);
			return true;
		}
	return false;
}
