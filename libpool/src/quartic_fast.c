// libpool: fast real roots of a quartic by factorisation into two real quadratics, verified.
//
// Why: the isolation solver (quartic.c) never fails but evaluates p, p' and p'' many times. A
// quartic with a4 != 0 factors as (x^2 + al1 x + be1)(x^2 + al2 x + be2) with real coefficients
// (Ferrari), built from the largest root y of the resolvent cubic; Newton's method on the four
// factor coefficients then makes the factorisation accurate to rounding, each quadratic is solved
// without cancellation and each real root gets one Newton step on the original p (final accuracy
// about kappa u, the same as the isolation solver). Every step that could make the answer wrong
// is checked, and then -1 sends the case to the isolation solver:
// - a4 = 0 or a0 = 0 (lower degree or an exact zero root), coefficients of extreme range;
// - the factor refinement not converging to rounding (the factors have nearly common roots);
// - for factors of very different scales, a residual of the factorisation above 2^-40 of its
//   terms (a correction lost to rounding at the larger factor's scale: roots spread over many
//   orders of magnitude);
// - a quadratic factor whose discriminant is within the error of the factor coefficients (plus a
//   relative margin) of 0: the number of real roots is ambiguous (grazing contact, near-double
//   root or nearly real complex pair);
// - a real root that Newton's first step on p moves by more than 1e-6 relative (not a root of p to
//   the factor's accuracy) or that does not converge to rounding in three steps, or two real
//   roots closer than 1e-7 relative (a near-multiple root).
// Only the mathematics of Ferrari's resolvent and of Newton's method is used; no code of other
// projects.
#include <math.h>
#include <stdbool.h>

#include "quartic_fast.h"

// cos(acos(x) / 3) = g(s) with s = sqrt((1 + x) / 2) in [0, 1] (g is analytic there): a least-
// squares polynomial fit, error below 4e-7; the resolvent root is then polished by Newton.
static double pool_qf_cos_third(double s) {
	return 0.50000039 +
	       s * (0.57732735 + s * (-0.1107795 + s * (0.05142129 + s * (-0.02636776 + s * (0.01051999 + s * -0.00212205)))));
}

// fmax / fmin without the library call (no NaN can reach them: inputs are checked first).
static inline double pool_qf_max(double x, double y) {
	return x > y ? x : y;
}
static inline double pool_qf_min(double x, double y) {
	return x < y ? x : y;
}

// y^3 + b2 y^2 + b1 y + b0 and its derivative at y.
static inline double pool_qf_cubic(double b2, double b1, double b0, double y, double *d) {
	*d = (3.0 * y + 2.0 * b2) * y + b1;
	return ((y + b2) * y + b1) * y + b0;
}

// Newton's iteration on the cubic from y (at most three steps, until a step is below 1e-6 |y|:
// the error left is then of order 1e-12, which the factor refinement removes).
static double pool_qf_cubic_newton(double b2, double b1, double b0, double y) {
	for (int it = 0; it < 3; ++it) {
		double d, f = pool_qf_cubic(b2, b1, b0, y, &d);
		if (!(d != 0.0))
			break;
		double dy = f / d;
		y -= dy;
		if (!(fabs(dy) > 1e-6 * fabs(y)))
			break;
	}
	return y;
}

// Largest real root of y^3 + b2 y^2 + b1 y + b0 (a closed form, then Newton's iteration).
// Every root is computed where it is not the difference of two near-equal numbers: y = t - b2 / 3
// cancels when the largest root is small against b2 > 0; then the most negative root (no
// cancellation) is computed and the largest comes from the remaining quadratic (Vieta).
static double pool_qf_cubic_largest(double b2, double b1, double b0) {
	// Depressed: y = t - b2 / 3, t^3 + P t + Q = 0.
	double s3 = b2 * (1.0 / 3.0);
	double P = b1 - b2 * s3;
	double Q = (2.0 / 27.0) * b2 * b2 * b2 - b1 * s3 + b0;
	double m = -P * (1.0 / 3.0), hq = 0.5 * Q;
	double disc = hq * hq - m * m * m;
	if (disc > 0.0) {
		// One real root (Cardano), the cube root taken on the side without cancellation.
		double A = -copysign(cbrt(fabs(hq) + sqrt(disc)), Q);
		double t = A != 0.0 ? A + m / A : 0.0;
		return pool_qf_cubic_newton(b2, b1, b0, t - s3);
	}
	if (!(m > 0.0))
		return pool_qf_cubic_newton(b2, b1, b0, -s3); // triple root
	// Three real roots: t = 2 sqrt(m) cos((acos(x) + 2 pi k) / 3), x = -Q / (2 m^1.5).
	double sm = sqrt(m);
	double x = -hq / (m * sm);
	x = pool_qf_min(pool_qf_max(x, -1.0), 1.0);
	if (s3 <= 0.0) {
		double t = 2.0 * sm * pool_qf_cos_third(sqrt(0.5 + 0.5 * x)); // largest t, y = t + |s3|
		return pool_qf_cubic_newton(b2, b1, b0, t - s3);
	}
	// The smallest root (t = -largest root of the cubic with -Q), y = -(|t| + s3).
	double t = -2.0 * sm * pool_qf_cos_third(sqrt(0.5 - 0.5 * x));
	double y1 = pool_qf_cubic_newton(b2, b1, b0, t - s3);
	if (!(y1 != 0.0))
		return y1;
	// The other two: y^2 - sig y + pi with pi = -b0 / y1 and sig = -b2 - y1 = (b1 - pi) / y1, each
	// form taken where its rounding error is smaller.
	double pi = -b0 / y1;
	double sig = fabs(b2) + fabs(y1) <= (fabs(b1) + fabs(pi)) / fabs(y1) ? -b2 - y1 : (b1 - pi) / y1;
	double q = 0.5 * (sig + copysign(sqrt(pool_qf_max(sig * sig - 4.0 * pi, 0.0)), sig));
	double y = q != 0.0 ? pool_qf_max(q, pi / q) : 0.0;
	return pool_qf_cubic_newton(b2, b1, b0, pool_qf_max(y, y1));
}

// Newton's iteration for a root of p(x) = c0 x^4 + ... + c4 from x, returning false when the
// first step is above 1e-6 |x| (x was not a root of p to the factor's accuracy) or no converged
// step within three. Converged: the error left after a step dx, about |p''| dx^2 / (2 |p'|), is
// below u sum |c_k| |x|^k / |p'| = kappa u |x|, the rounding error of evaluating p there.
static inline bool pool_qf_polish(const double c[5], double *xp) {
	double x = *xp;
	for (int it = 0; it < 3; ++it) {
		double f = c[0], d = 0.0, e = 0.0, s = fabs(c[0]), ax = fabs(x);
		for (int k = 1; k < 5; ++k) {
			e = e * x + d;
			d = d * x + f;
			f = f * x + c[k];
			s = s * ax + fabs(c[k]);
		}
		double dx = f / d;
		if (!(fabs(dx) <= 1e-6 * ax))
			return false; // also p' = 0 or NaN
		x -= dx;
		// p'' = 2 e.
		if (fabs(e) * dx * dx <= 0x1p-54 * s) {
			*xp = x;
			return true;
		}
	}
	return false;
}

int pool_quartic_fast_real_roots(const double c[5], double roots[4]) {
	if (!(c[0] != 0.0) || !(c[4] != 0.0))
		return -1; // lower degree, exact zero root, or NaN
	double inv = 1.0 / c[0];
	double a = c[1] * inv, b = c[2] * inv, cc = c[3] * inv, d = c[4] * inv;
	double fa = fabs(a), fb = fabs(b), fc = fabs(cc), fd = fabs(d);
	// Root scale max(|a|, |b|^1/2, |c|^1/3, |d|^1/4) in [2^-60, 2^60]: no overflow or underflow in
	// the resolvent (degree 6 in the roots); also rejects infinities and NaN.
	if (!(fa <= 0x1p60 && fb <= 0x1p120 && fc <= 0x1p180 && fd <= 0x1p240))
		return -1;
	if (!(fa >= 0x1p-60 || fb >= 0x1p-120 || fc >= 0x1p-180 || fd >= 0x1p-240))
		return -1;
	if (fd < 0x1p-600 || (fa != 0.0 && fa < 0x1p-600) || (fb != 0.0 && fb < 0x1p-600) || (fc != 0.0 && fc < 0x1p-600))
		return -1;

	// Ferrari: p = (x^2 + a x / 2 + y / 2)^2 - (e x + f)^2 when y solves the resolvent
	// y^3 - b y^2 + (a c - 4 d) y + (4 b d - a^2 d - c^2) = 0; its largest root gives e^2 >= 0.
	double y = pool_qf_cubic_largest(-b, a * cc - 4.0 * d, d * (4.0 * b - a * a) - cc * cc);
	double e2 = 0.25 * a * a - b + y, f2 = 0.25 * y * y - d, g = 0.5 * a * y - cc; // g = 2 e f
	double e, f;
	// Take the square root of the one with less cancellation, the other from g = 2 e f.
	if (e2 * (0.25 * y * y + fd) >= f2 * (0.25 * a * a + fb + fabs(y))) {
		e = sqrt(pool_qf_max(e2, 0.0));
		f = e > 0.0 ? g / (2.0 * e) : 0.0;
	} else {
		f = copysign(sqrt(pool_qf_max(f2, 0.0)), g);
		e = f != 0.0 ? g / (2.0 * f) : 0.0;
	}
	double al1 = 0.5 * a - e, al2 = 0.5 * a + e;
	double be1 = 0.5 * y - f, be2 = 0.5 * y + f;
	// The smaller constant term from be1 be2 = d (no cancellation).
	if (fabs(be1) < fabs(be2))
		be1 = d / be2;
	else
		be2 = d / be1;

	// Newton on the coefficient equations al1 + al2 = a, be1 + be2 + al1 al2 = b,
	// al1 be2 + al2 be1 = c, be1 be2 = d (the Jacobian's determinant is the resultant of the two
	// factors). dal2 is eliminated by the first equation, the 3x3 rest solved by Cramer's rule.
	double dal1 = 0.0, dbe1 = 0.0, dal2 = 0.0, dbe2 = 0.0, s1 = 0.0, s2 = 0.0;
	bool converged = false;
	for (int it = 0; it < 4; ++it) {
		double F1 = al1 + al2 - a;
		double F2 = be1 + be2 + al1 * al2 - b;
		double F3 = al1 * be2 + al2 * be1 - cc;
		double F4 = be1 * be2 - d;
		double r2 = al1 * F1 - F2, r3 = be1 * F1 - F3, r4 = -F4;
		double A = al2 - al1, B = be2 - be1, G = al2 * be1 - al1 * be2;
		double det = A * G + B * B;
		if (!(det != 0.0) || !isfinite(det))
			return -1;
		double id = 1.0 / det;
		dal1 = (r2 * G + r3 * B - r4 * A) * id;
		dbe1 = (A * (r3 * be1 - al1 * r4) - r2 * B * be1 + B * r4) * id;
		dbe2 = (A * (al2 * r4 - r3 * be2) - B * r4 + r2 * B * be2) * id;
		dal2 = -F1 - dal1;
		al1 += dal1;
		al2 += dal2;
		be1 += dbe1;
		be2 += dbe2;
		// Converged when the correction is small against each factor's scale s (s^2 = max(al^2,
		// |be|); the larger root is about s) for al, and against |be| itself for be (the smaller
		// root is be / q: it needs be to relative accuracy).
		s1 = pool_qf_max(al1 * al1, fabs(be1));
		s2 = pool_qf_max(al2 * al2, fabs(be2));
		double tol = 1e-9;
		if (dal1 * dal1 <= tol * tol * s1 && fabs(dbe1) <= tol * fabs(be1) && dal2 * dal2 <= tol * tol * s2 &&
		    fabs(dbe2) <= tol * fabs(be2)) {
			converged = true;
			break;
		}
	}
	if (!converged)
		return -1;
	// The test above bounds the corrections, not the residuals, and a correction can be lost to
	// rounding. The smaller |al| comes out of Ferrari as a / 2 +- e with cancellation, and the
	// elimination dal2 = -F1 - dal1 (and Cramer's dal1) carry rounding at the scale of F1's terms:
	// either al is right only to about u (|al1| + |al2|) absolute. With factors of very different
	// scales (roots spread over about 60 orders of magnitude) the small roots' al lay below that,
	// al and its corrections were rounding noise (even 0) while only F3 fixes that al, and two real
	// roots were lost to a factor judged complex. That error changes a factor's discriminant by
	// at most about 2 u (|al1| + |al2|) / sqrt(s) of its scale al^2 + 4 |be| (s as above); while
	// (|al1| + |al2|)^2 <= 2^26 s it stays 100 times below the margin (1e-10 of that scale) used
	// below. Otherwise (tested on a superset: (|al1| + |al2|)^2 <= 2 (al1^2 + al2^2)) the product of
	// the factors must reproduce b, c and d to 2^-40 of the sum of each one's terms (a = al1 + al2
	// holds to rounding by the elimination): the factors are then exactly those of a polynomial
	// within 2^-40 of p's terms, their coefficients as accurate as the factorisation's conditioning
	// allows, which the corrections (in the margin) measure. Converged factorisations have
	// residuals below 2^16 u = 2^-37 in both pool-bench-quartic sets (almost all below 2 u); the
	// lost corrections, of order 1. The test runs on 26% of the thesis set and 4.6% of the ball
	// pairs (mostly a tiny a4: one huge root).
	if (al1 * al1 + al2 * al2 > 0x1p25 * pool_qf_min(s1, s2)) {
		double t12 = al1 * al2, t3a = al1 * be2, t3b = al2 * be1, t4 = be1 * be2;
		const double rtol = 0x1p-40;
		int backward_ok = (fabs(be1 + be2 + t12 - b) <= rtol * (fabs(be1) + fabs(be2) + fabs(t12))) &
		                  (fabs(t3a + t3b - cc) <= rtol * (fabs(t3a) + fabs(t3b))) & (fabs(t4 - d) <= rtol * fabs(t4));
		if (!backward_ok)
			return -1;
	}

	// Roots of each factor; the root count must be unambiguous.
	const double al[2] = {al1, al2}, be[2] = {be1, be2}, dal[2] = {dal1, dal2}, dbe[2] = {dbe1, dbe2};
	double r[4];
	int n = 0;
	for (int k = 0; k < 2; ++k) {
		double disc = al[k] * al[k] - 4.0 * be[k];
		double margin = 1e-10 * (al[k] * al[k] + 4.0 * fabs(be[k])) + 64.0 * (2.0 * fabs(al[k] * dal[k]) + 4.0 * fabs(dbe[k]));
		if (!(fabs(disc) > margin))
			return -1;
		if (disc < 0.0)
			continue;
		double q = -0.5 * (al[k] + copysign(sqrt(disc), al[k]));
		r[n++] = q;
		r[n++] = be[k] / q;
	}
	// One Newton step on the original polynomial each: the final accuracy, and a check that each
	// is a root of p.
	for (int i = 0; i < n; ++i)
		if (!pool_qf_polish(c, &r[i]))
			return -1;
	// Sort (at most four) and reject near-multiple roots.
	for (int i = 1; i < n; ++i) {
		double x = r[i];
		int j = i;
		while (j > 0 && r[j - 1] > x) {
			r[j] = r[j - 1];
			--j;
		}
		r[j] = x;
	}
	for (int i = 0; i < n; ++i) {
		if (i > 0 && !(r[i] - r[i - 1] > 1e-7 * pool_qf_max(fabs(r[i]), fabs(r[i - 1]))))
			return -1;
		roots[i] = r[i];
	}
	return n;
}
