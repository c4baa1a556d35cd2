// pool-bench-quartic: data sets and the long-double reference roots the solvers are judged by.
#ifndef POOL_BENCH_QUARTIC_REF_H
#define POOL_BENCH_QUARTIC_REF_H

#include <stdbool.h>

#include <gsl/gsl_rng.h>

/// Reference real roots of one polynomial (its double coefficients taken as exact).
typedef struct bq_ref {
	bool ok;         ///< the reference could be built and verified
	bool ill;        ///< ill-conditioned: a real root with kappa u > 1e-9, or a near-real complex pair
	int degree;      ///< after dropping exactly-zero leading coefficients
	int n_real;      ///< real roots by multiplicity
	double real[4];  ///< ascending
	double tol[4];   ///< allowed absolute error of each: 1e3 kappa u |r| (0 for an exact zero root)
	double kappa[4]; ///< condition number sum |a_i| |r|^i / (|r| |p'(r)|)
} bq_ref;

/// Builds the reference for c[0] x^4 + ... + c[4]; start: 0 to 4 approximate complex roots
/// (re, im pairs; may be NULL) used only as starting points of the long-double iteration.
bq_ref bq_reference(const double c[5], const double *start, int n_start);

/// True when a solver's sorted real roots agree with the reference (count and every root).
bool bq_roots_match(const bq_ref *ref, int n, const double *roots);

/// Smallest reference root in [lo, hi]; false when there is none.
bool bq_ref_smallest_in(const bq_ref *ref, double lo, double hi, double *root, double *tol);

/// Fills n quartics (5 coefficients each, a4 first): |a_i| log-uniform in [1e-6, 1e6], random signs.
void bq_gen_thesis(gsl_rng *rng, double *coeffs, long n);

/// Fills n quartics from random ball pairs on a pool table (docs/physics.md, "Predicting events").
void bq_gen_balls(gsl_rng *rng, double *coeffs, long n);

#endif
