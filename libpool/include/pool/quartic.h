// libpool: real roots of polynomials of degree <= 4 (collision times).
#ifndef POOL_QUARTIC_H
#define POOL_QUARTIC_H

#include "pool/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Real roots of c[0] x^4 + c[1] x^3 + c[2] x^2 + c[3] x + c[4], ascending, repeated by
/// multiplicity; returns how many (0 to 4). c[0] (and further leading terms) may be 0, then the
/// cubic, quadratic or linear equation is solved. Non-finite input gives 0 roots.
///
/// Any finite coefficients, roots spread over any number of orders of magnitude. Accuracy, for
/// the roots of the coefficients as given: a root r with condition number
/// kappa = sum |c_i| |r|^(4-i) / (|r| |p'(r)|) and kappa u <= 1e-9 (u = 2^-53) is reported, and
/// the root count is right, unless a complex pair lies within 1e-3 (relative) of the real axis;
/// each such root within 1e3 kappa u relative (tested for 2^53 DBL_MIN <= |r| <= DBL_MAX / 4,
/// about 2e-292 to 4e307; at most about 3 kappa u seen). Roots above DBL_MAX in magnitude are
/// not reported; roots below DBL_MIN (subnormal) are accurate in absolute terms only (error
/// below DBL_MIN; one subnormal spacing seen). Ill-conditioned roots (near-multiple, grazing
/// contacts) are reported with their multiplicity when p vanishes at a critical point within its
/// rounding.
POOL_API int pool_quartic_real_roots(const double c[5], double roots[4]);

/// Smallest real root of the same polynomial in [lo, hi], or a negative return when there is
/// none; the root is written to *root. The hot path of collision prediction. Same accuracy as
/// pool_quartic_real_roots (a root within rounding of lo or hi may be taken as in or out).
POOL_API int pool_quartic_smallest_root_in(const double c[5], double lo, double hi, double *root);

#ifdef __cplusplus
}
#endif

#endif
