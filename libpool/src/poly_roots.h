// First roots of polynomials of degree up to 8 on an interval, by Bernstein subdivision: the
// contacts whose gap function is of higher degree than the quartic solver takes (a flying ball
// against a jaw, a torus: degree 8; docs/physics.md "Table geometry").
//
// On an interval the polynomial is written in the Bernstein basis; its value lies within the
// convex hull of its Bernstein coefficients, so coefficients all of one sign prove there is no
// root there, and a single sign change in them proves exactly one (Descartes' rule for the
// Bernstein basis). Intervals that prove neither are halved (de Casteljau), left half first, so
// the first root where the polynomial falls through zero is never skipped: a crossing changes the
// sign of the value at the two ends of every interval that holds it, and no interval with a
// sign change between its ends is dropped. What subdivision cannot resolve, below
// POOL_POLY_MIN_WIDTH of the interval, is a pair of roots closer than that with no sign change
// between them: a graze whose overlap is within the rounding of the coefficients.
#ifndef POOL_POLY_ROOTS_H
#define POOL_POLY_ROOTS_H

/// Highest degree pool_poly_first_falling_root takes.
#define POOL_POLY_MAX_DEGREE 8

/// Relative width (of [lo, hi]) below which an interval is not halved again: 2^-52, the
/// resolution of a double; a root is then bisected to the last bit on the polynomial itself.
#define POOL_POLY_MIN_WIDTH 0x1p-52

/// First root in [lo, hi] of p[0] + p[1] t + ... + p[deg] t^deg (deg <= POOL_POLY_MAX_DEGREE)
/// where p falls through zero (>= 0 before it, < 0 after); INFINITY when none.
double pool_poly_first_falling_root(const double *p, int deg, double lo, double hi);

/// p(t), Horner.
double pool_poly_eval(const double *p, int deg, double t);

/// c = a * b (degrees da, db; c has da + db + 1 coefficients).
void pool_poly_mul(const double *a, int da, const double *b, int db, double *c);

#endif
