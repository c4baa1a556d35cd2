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
POOL_API int pool_quartic_real_roots(const double c[5], double roots[4]);

/// Smallest real root of the same polynomial in [lo, hi], or a negative return when there is
/// none; the root is written to *root. The hot path of collision prediction.
POOL_API int pool_quartic_smallest_root_in(const double c[5], double lo, double hi, double *root);

#ifdef __cplusplus
}
#endif

#endif
