// libpool: real roots of polynomials of degree <= 4 by isolation between critical points.
//
// Why this method: collision prediction needs the real roots only, must never lose one (a lost
// root is a missed collision) and must not invent one. The real roots of p are separated by the
// real roots of p' (Rolle): between two consecutive critical points p is monotone, so it has a
// root there exactly when its values at the ends have opposite signs, and then exactly one. The
// critical points come recursively from p'' (a quadratic, closed form) and p' (a cubic, by the
// same isolation). Each bracketed root is found by Newton's method safeguarded by the bracket, so
// the count comes from sign tests and each root is as accurate as evaluating p allows (relative
// error about kappa * u). A critical point where |p| is below the rounding error of evaluating p
// is a multiple root (a grazing contact): reported there with its multiplicity, never dropped.
//
// Scaling: x = 2^e y with e chosen from the coefficients (exact, powers of two), so that huge or
// tiny roots and coefficients do not overflow or underflow while evaluating p. One scaling holds
// p's values at all its roots in the double range only while the roots spread over less than
// about 300 orders of magnitude; coefficients anywhere in the double range allow twice that. So
// an extreme polynomial whose Newton polygon bends sharply (its roots fall into groups of very
// different magnitudes) is split there into two polynomials, one per group, each solved with its
// own scaling (pool_q_solve_split). And the iteration is logarithmic in the bracket's exponent
// range, not linear (the slow-progress rule in pool_q_bracketed). Measured (tests/unit
// test_wide_spread_products): roots spread over up to 600 orders of magnitude, every root
// magnitude and coefficient the double range allows, all well-conditioned roots within 4 kappa u.
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "pool/quartic.h"
#include "quartic_fast.h"

#define POOL_Q_U 0x1p-53
// Multiple of u * sum |a_k x^k| below which p(x) at a critical point counts as zero: covers
// Horner's rounding (about 2n u) plus the rounding of the coefficients themselves.
#define POOL_Q_TOUCH 16.0
#define POOL_Q_MAX_ITER 200

// When Halley's iteration stops: its step is below rel |x| (the error left is of order its cube),
// or its predicted error is below abs_rel |x|. Roots: to rounding. Critical points only need about
// sqrt(u) relative accuracy (an error d in a critical point changes p there by p'' d^2 / 2, below
// the rounding of p).
typedef struct pool_q_stop {
	double rel, abs_rel;
} pool_q_stop;
static const pool_q_stop pool_q_stop_root = {1e-8, 0.25 * POOL_Q_U};
static const pool_q_stop pool_q_stop_crit = {1e-4, 1e-9};

typedef struct pool_q_val {
	double x;  // point
	double f;  // p(x)
	double d1; // p'(x)
	double d2; // p''(x)
	double d3; // p'''(x) (NAN when not computed)
	int sign;  // sign of p(x); 0 when it is zero within rounding (critical points only)
} pool_q_val;

// A polynomial being solved: b[k] is the coefficient of x^k, b[n] != 0. With safe set (extreme
// coefficient ranges), p is evaluated at |x| > 1 through the reversed polynomial q(z) = x^-n p(x),
// z = 1/x, and every value (p, p', p'', the error scale) comes out multiplied by the same factor
// s / |x|^n (s a power of two near |x| / 16, see pool_q_eval_all): no overflow, and the ratios the
// iteration uses (p/p', Halley's step, |p| against its error scale) unchanged.
typedef struct pool_q_p {
	const double *b;
	int n;
	bool safe;
} pool_q_p;

// p(x), p'(x), p''(x), p'''(x) (the first three times s / |x|^n when p->safe and |x| > 1, and
// then p''' is not computed: NAN).
// Horner's scheme for p and its derivatives with the degree a constant (unrolled by the compiler).
#define POOL_Q_HORNER(N)                                                                          \
	do {                                                                                          \
		f = b[N];                                                                                 \
		for (int k = (N)-1; k >= 0; --k) {                                                        \
			g = g * x + e;                                                                        \
			e = e * x + d;                                                                        \
			d = d * x + f;                                                                        \
			f = f * x + b[k];                                                                     \
		}                                                                                         \
	} while (0)

// 2^(ilogb(x) - 4) for finite |x| > 1, from the exponent bits (no library call: this is evaluated
// at every point of an extreme polynomial).
static inline double pool_q_scale_of(double x) {
	uint64_t bits;
	memcpy(&bits, &x, sizeof bits);
	bits = (bits & 0x7FF0000000000000ULL) - (4ULL << 52);
	double s;
	memcpy(&s, &bits, sizeof s);
	return s;
}

static inline double pool_q_eval_all(const pool_q_p *p, double x, double *d1, double *d2, double *d3) {
	const double *b = p->b;
	const int n = p->n;
	double f, d = 0.0, e = 0.0, g = 0.0;
	if (!p->safe || fabs(x) <= 1.0) {
		switch (n) {
		case 4:
			POOL_Q_HORNER(4);
			break;
		case 3:
			POOL_Q_HORNER(3);
			break;
		case 2:
			POOL_Q_HORNER(2);
			break;
		case 1:
			POOL_Q_HORNER(1);
			break;
		default:
			f = b[0];
			break;
		}
		*d1 = d;
		*d2 = 2.0 * e;
		*d3 = 6.0 * g;
		return f;
	}
	*d3 = NAN;
	double z = 1.0 / x, q = b[0];
	for (int k = 1; k <= n; ++k) {
		e = e * z + d;
		d = d * z + q;
		q = q * z + b[k];
	}
	// p = x^n q(z), p' = x^(n-1) (n q - z q'), p'' = x^(n-2) (n(n-1) q - 2(n-1) z q' + z^2 q'').
	// All three times s / |x|^n with s = 2^(ilogb(x) - 4) (exact, about |x| / 16): divided by |x|^n
	// alone, p' would come out near z |b_n| / kappa at a root, subnormal (a few bits, a wrong Newton
	// step) once |x| passes about 1e150, i.e. for roots spread over more than about 300 orders of
	// magnitude around the balance point; with s it is near |b_n| / kappa, and s q cannot overflow
	// (|q| <= sum |b_k| < 10, |x| / 16 * 10 < DBL_MAX).
	double s = pool_q_scale_of(x);
	double sg = (n % 2 == 0 || x > 0.0) ? 1.0 : -1.0, nn = (double)n;
	double zs = sg * (z * s); // sg s / x, in (1/32, 1/16] in magnitude
	*d1 = zs * (nn * q - z * d);
	*d2 = zs * z * (nn * (nn - 1.0) * q - 2.0 * (nn - 1.0) * z * d + z * z * 2.0 * e);
	return sg * (q * s);
}

static pool_q_val pool_q_eval(const pool_q_p *p, double x) {
	double d1, d2, d3;
	double f = pool_q_eval_all(p, x, &d1, &d2, &d3);
	pool_q_val v = {x, f, d1, d2, d3, (f > 0.0) - (f < 0.0)};
	return v;
}

// Sum of |b_k| |x|^k: the scale of the rounding error of p(x) (same scaling as pool_q_eval_all).
static double pool_q_abs_sum(const pool_q_p *p, double x) {
	const double *b = p->b;
	const int n = p->n;
	double s;
	if (!p->safe || fabs(x) <= 1.0) {
		double ax = fabs(x);
		s = fabs(b[n]);
		for (int k = n - 1; k >= 0; --k)
			s = s * ax + fabs(b[k]);
	} else {
		double az = fabs(1.0 / x);
		s = fabs(b[0]);
		for (int k = 1; k <= n; ++k)
			s = s * az + fabs(b[k]);
		s *= pool_q_scale_of(x);
	}
	return s;
}

// A point strictly inside (a, c): the middle, or the geometric middle when the bracket spans
// orders of magnitude on one side of 0 (bisection then still gains a bit of exponent per step).
static double pool_q_split(double a, double c) {
	if (a < 0.0 && c > 0.0)
		return 0.0;
	// One end at 0: the geometric middle with the smallest normal number, so that about eleven
	// splits find the root's exponent.
	if (a == 0.0 && c > 0x1p-1020)
		return sqrt(c) * 0x1p-511;
	if (c == 0.0 && a < -0x1p-1020)
		return -sqrt(-a) * 0x1p-511;
	if (a >= 0.0 && c > 4.0 * a && a > 0.0)
		return sqrt(a) * sqrt(c);
	if (c <= 0.0 && a < 4.0 * c && c < 0.0)
		return -sqrt(-a) * sqrt(-c);
	return 0.5 * a + 0.5 * c;
}

// Distance from point v towards the root of p in direction dir, from the local Taylor terms
// (each one alone would reach the root at about this distance; the smallest is the best guess).
static double pool_q_guess_step(const pool_q_p *p, const pool_q_val *v, int dir) {
	const int n = p->n;
	double af = fabs(v->f), t = INFINITY;
	// Slope term, when moving in dir brings p towards 0.
	if (v->d1 != 0.0 && (v->d1 * dir > 0.0) == (v->f < 0.0))
		t = af / fabs(v->d1);
	if (v->d2 != 0.0) {
		double t2 = sqrt(2.0 * af / fabs(v->d2));
		if (t2 < t)
			t = t2;
	}
	double lead = fabs(p->b[n]);
	bool rescaled = p->safe && fabs(v->x) > 1.0; // |f| is rescaled: no leading-term bound
	double tn_pow = t * t;
	tn_pow = n == 4 ? tn_pow * tn_pow : n == 3 ? tn_pow * t : tn_pow;
	if (!rescaled && (!(t < INFINITY) || lead * tn_pow > af)) {
		// The leading term alone reaches |f| sooner: its distance bounds the root's distance.
		double tn = n == 4 ? sqrt(sqrt(af / lead)) : n == 3 ? cbrt(af / lead) : sqrt(af / lead);
		if (tn < t)
			t = tn;
	}
	if (!(t > 0.0) || !(t < INFINITY))
		t = fmax(1.0, fabs(v->x));
	return t;
}

// The single root of p between a and c (p monotone there, signs at the ends opposite and non-zero).
// a or c may be infinite. Halley's iteration (cubic convergence) safeguarded by the bracket, which
// every evaluation shrinks (a step leaving it is replaced by a bisection); stops per *stop.
// Returns NAN when no finite bracket could be built (overflow).
static double pool_q_bracketed(const pool_q_p *p, pool_q_val a, pool_q_val c, const pool_q_stop *stop) {
	const int sa = a.sign;
	double x;
	if (!isfinite(a.x) || !isfinite(c.x)) {
		// Expand from the finite end until the sign changes: a finite bracket.
		pool_q_val e = isfinite(a.x) ? a : c;
		int dir = isfinite(a.x) ? 1 : -1;
		double t = pool_q_guess_step(p, &e, dir);
		for (int i = 0;; ++i) {
			x = e.x + dir * t;
			if (!isfinite(x) || i > 2100)
				return NAN;
			double d, d2, d3;
			double f = pool_q_eval_all(p, x, &d, &d2, &d3);
			int s = (f > 0.0) - (f < 0.0);
			if (s == 0)
				return x;
			if (s == e.sign) {
				e.x = x; // still on the near side: move the finite end out
				if (dir > 0)
					a.x = x;
				else
					c.x = x;
				t *= 2.0;
				continue;
			}
			if (dir > 0)
				c.x = x;
			else
				a.x = x;
			break;
		}
	} else {
		// Start from the end where |p| is smaller (the root is nearer to it), Taylor guess.
		const pool_q_val *e = fabs(a.f) <= fabs(c.f) ? &a : &c;
		int dir = e == &a ? 1 : -1;
		x = e->x + dir * pool_q_guess_step(p, e, dir);
		if (!(x > a.x && x < c.x))
			x = pool_q_split(a.x, c.x);
	}
	double lo = a.x, hi = c.x;
	// Slow progress. Far from the root, where one term of p dominates (p ~ b_k x^k), Halley's step
	// is the fixed fraction 2 / (k + 1) of x: x shrinks (or grows) by a constant factor per
	// iteration, and a root many orders of magnitude away in a wide bracket (roots spread over more
	// than about 60 orders of magnitude) took more than POOL_Q_MAX_ITER iterations, and the last
	// iterate came back as a wrong root. So from the fourth iteration on (normal convergence needs
	// fewer), two Halley steps in a row above |x| / 4 in the same direction make the next one a
	// split of the bracket (geometric when the bracket spans orders of magnitude: it halves the
	// exponent range), and the iteration count is logarithmic in that range.
	double big = 0.0; // the previous step, when it was a Halley step above |x| / 4 (else 0)
	for (int it = 0; it < POOL_Q_MAX_ITER; ++it) {
		double d, d2, d3;
		double f = pool_q_eval_all(p, x, &d, &d2, &d3);
		if (f == 0.0)
			return x;
		if ((f > 0.0) - (f < 0.0) == sa)
			lo = x;
		else
			hi = x;
		double dx;
		if (p->safe) {
			// Halley's step written with ratios: no products that could underflow or overflow.
			double newton = f / d;
			double den = 1.0 - 0.5 * newton * (d2 / d);
			dx = den > 0.5 ? newton / den : newton;
		} else {
			// Halley's step f d / (d^2 - f d2 / 2); Newton's where Halley's is far from it.
			double dd = d * d, den = dd - 0.5 * f * d2;
			dx = den > 0.5 * dd ? f * d / den : f / d;
		}
		double xn = x - dx;
		double adx = fabs(dx);
		if (adx <= stop->rel * fabs(x))
			return fmin(fmax(xn, lo), hi); // the root is in [lo, hi]: never return outside
		// Halley's error after this step is about K dx^3 with K = |3 p''^2 - 2 p' p'''| / (12 p'^2):
		// stop when that is below the target (saves the confirming iteration). Only for a step
		// small against |x|: p evaluated far from the root (|x| >> |root|) carries a rounding error
		// of the larger scale, which the next iteration, evaluated at the root's scale, removes.
		if (!p->safe && adx <= 1e-3 * fabs(xn) && fabs(3.0 * d2 * d2 - 2.0 * d3 * d) * (adx * adx * adx) <= 12.0 * d * d * stop->abs_rel * fabs(xn))
			return fmin(fmax(xn, lo), hi);
		bool slow = false;
		if (it >= 3) {
			bool large = adx > 0.25 * fabs(x);
			slow = large && dx * big > 0.0;
			big = large ? dx : 0.0;
		}
		if (!(xn > lo && xn < hi) || slow) {
			// The step left the bracket (or p' vanished), or is slow (above): bisect instead.
			xn = pool_q_split(lo, hi);
			big = 0.0;
			if (!(xn > lo && xn < hi))
				return x; // the bracket holds no other double: x is the root to rounding
		}
		x = xn;
	}
	return x;
}

// Roots of a degree-n polynomial b (b[n] != 0, coefficient of x^k in b[k]) in [lo, hi], ascending,
// by multiplicity, at most n. lo/hi may be infinite. With first_only, stops at the first root.
static int pool_q_roots_in(const pool_q_p *p, double lo, double hi, double *out, bool first_only, const pool_q_stop *stop);

static int pool_q_quadratic(const pool_q_p *p, double lo, double hi, double *out) {
	const double *b = p->b;
	double b0 = b[0], b1 = b[1], b2 = b[2];
	if (p->safe) {
		// Largest coefficient to about 1 (a power of two: exact), so b1^2 cannot overflow.
		double m = fmax(fabs(b0), fmax(fabs(b1), fabs(b2)));
		int e;
		frexp(m, &e);
		b0 = ldexp(b0, -e);
		b1 = ldexp(b1, -e);
		b2 = ldexp(b2, -e);
	}
	double disc = b1 * b1 - 4.0 * b2 * b0;
	double r[2];
	if (disc >= 0.0) {
		double q = -0.5 * (b1 + copysign(sqrt(disc), b1));
		if (q == 0.0) {
			r[0] = r[1] = 0.0; // b1 = 0 and disc = 0: b0 = 0
		} else {
			double r1 = q / b2, r2 = b0 / q;
			r[0] = fmin(r1, r2);
			r[1] = fmax(r1, r2);
		}
	} else {
		// p at its vertex is -disc / (4 b2); it touches 0 within rounding of evaluating p there
		// when |disc| <= 4 |b2| * TOUCH u (|b0| + 3 b1^2 / (4 |b2|)).
		double tol = POOL_Q_TOUCH * POOL_Q_U * (4.0 * fabs(b2 * b0) + 3.0 * b1 * b1);
		if (-disc > tol)
			return 0;
		r[0] = r[1] = -b1 / (2.0 * b2);
	}
	int m = 0;
	for (int i = 0; i < 2; ++i)
		if (r[i] >= lo && r[i] <= hi)
			out[m++] = r[i] + 0.0; // + 0.0: no -0
	return m;
}

static int pool_q_roots_in(const pool_q_p *p, double lo, double hi, double *out, bool first_only, const pool_q_stop *stop) {
	const double *b = p->b;
	const int n = p->n;
	if (n <= 0)
		return 0;
	if (n == 1) {
		double r = -b[0] / b[1] + 0.0;
		if (r >= lo && r <= hi) {
			out[0] = r;
			return 1;
		}
		return 0;
	}
	if (n == 2)
		return pool_q_quadratic(p, lo, hi, out);

	// Critical points in the window, with multiplicity.
	double d[4];
	for (int k = 0; k < n; ++k)
		d[k] = (double)(k + 1) * b[k + 1];
	double crit[3];
	pool_q_p dp = {d, n - 1, p->safe};
	int ncrit = pool_q_roots_in(&dp, lo, hi, crit, false, &pool_q_stop_crit);

	int count = 0;
	const int cap = first_only ? 1 : n;
	if (ncrit == 0 && lo == -INFINITY && hi == INFINITY) {
		// Monotone on the whole line (odd degree): split at the inflection point, whose value
		// tells which side the single root is on.
		double xi = -b[n - 1] / ((double)n * b[n]);
		pool_q_val v = pool_q_eval(p, xi);
		if (v.sign == 0) {
			out[0] = xi + 0.0;
			return 1;
		}
		pool_q_val inf = {v.sign == (b[n] > 0.0 ? 1 : -1) ? -INFINITY : INFINITY, NAN, NAN, NAN, NAN, -v.sign};
		double r = inf.x < 0.0 ? pool_q_bracketed(p, inf, v, stop) : pool_q_bracketed(p, v, inf, stop);
		if (r == r) {
			out[0] = r;
			return 1;
		}
		return 0;
	}
	// Left end of the window.
	pool_q_val prev;
	if (lo == -INFINITY) {
		prev.x = -INFINITY;
		prev.f = prev.d1 = prev.d2 = prev.d3 = NAN;
		prev.sign = ((b[n] > 0.0) == (n % 2 == 0)) ? 1 : -1;
	} else {
		prev = pool_q_eval(p, lo);
		if (prev.sign == 0) {
			out[count++] = lo;
			if (first_only)
				return count;
		}
	}
	for (int i = 0; i < ncrit;) {
		double cx = crit[i];
		int mult = 1;
		while (i + mult < ncrit && crit[i + mult] == cx)
			++mult;
		i += mult;
		if (!(cx > prev.x))
			continue; // coincides with the window's left end, already evaluated
		pool_q_val v = pool_q_eval(p, cx);
		if (fabs(v.f) <= POOL_Q_TOUCH * POOL_Q_U * pool_q_abs_sum(p, cx)) {
			// A multiple root: the critical point is now reported as a root, so polish it to full
			// accuracy (it was only computed to what bracketing needs) by Newton on p'.
			v.sign = 0;
			for (int it = 0; it < 4; ++it) {
				double g1, g2, g3;
				double g = pool_q_eval_all(&dp, cx, &g1, &g2, &g3);
				double step = g / g1;
				if (!(fabs(step) < 1e-6 * fabs(cx)))
					break; // p'' ~ 0 too (a higher multiplicity), or no progress: keep cx
				cx -= step;
				if (fabs(step) <= 2.0 * POOL_Q_U * fabs(cx))
					break;
			}
		}
		if (prev.sign != 0 && v.sign != 0 && prev.sign != v.sign) {
			double r = pool_q_bracketed(p, prev, v, stop);
			if (r == r && count < cap) {
				out[count++] = r;
				if (first_only)
					return count;
			}
		}
		if (v.sign == 0) {
			for (int k = 0; k <= mult && count < cap; ++k)
				out[count++] = cx;
			if (first_only)
				return count;
		}
		prev = v;
	}
	// Right end.
	pool_q_val last;
	if (hi == INFINITY) {
		last.x = INFINITY;
		last.f = last.d1 = last.d2 = last.d3 = NAN;
		last.sign = b[n] > 0.0 ? 1 : -1;
	} else {
		if (!(hi > prev.x))
			return count;
		last = pool_q_eval(p, hi);
	}
	if (prev.sign != 0 && last.sign != 0 && prev.sign != last.sign) {
		double r = pool_q_bracketed(p, prev, last, stop);
		if (r == r && count < cap)
			out[count++] = r;
	} else if (last.sign == 0 && count < cap) {
		out[count++] = hi;
	}
	return count;
}

// The polynomial ready for the core: degree, coefficients by ascending power with no zero root
// (factored out exactly), leading coefficient positive, and x = 2^scale y.
typedef struct pool_q_poly {
	int n;
	int deg;   // degree without the zero roots, before the underflow check (n may be lower)
	int zeros; // multiplicity of the root x = 0
	int scale;
	bool safe; // extreme coefficients: evaluate through the reversed polynomial at |x| > 1
	double b[5];
} pool_q_poly;

// Returns false for non-finite input.
static bool pool_q_prepare(const double c[5], pool_q_poly *p) {
	double a[5];
	for (int k = 0; k < 5; ++k) {
		a[k] = c[4 - k];
		if (!isfinite(a[k]))
			return false;
	}
	int n = 4;
	while (n >= 0 && a[n] == 0.0)
		--n;
	p->n = 0;
	p->deg = 0;
	p->zeros = 0;
	p->scale = 0;
	p->safe = false;
	if (n <= 0)
		return true; // zero polynomial or a non-zero constant: no roots
	int z = 0;
	while (a[z] == 0.0)
		++z;
	p->zeros = z;
	p->n = n - z;
	p->deg = p->n;
	n = p->n;
	if (n == 0)
		return true; // a monomial: only the exact zero roots
	double sgn = a[n + z] > 0.0 ? 1.0 : -1.0;
	// Fast path: coefficients in [2^-60, 2^60] cannot overflow Horner (nor Halley's products) at
	// any root.
	bool moderate = true;
	for (int k = 0; k <= n; ++k) {
		double m = fabs(a[k + z]);
		if (m != 0.0 && (m < 0x1p-60 || m > 0x1p60))
			moderate = false;
	}
	if (moderate) {
		for (int k = 0; k <= n; ++k)
			p->b[k] = sgn * a[k + z];
		return true;
	}
	// Balance: x = 2^e y with 2^(e n) |a_n| ~ |a_0| (the roots' geometric mean near 1), then
	// divide by a power of two so the largest coefficient is near 1. Exact apart from underflow.
	int e0 = ilogb(a[z]), en = ilogb(a[n + z]);
	int diff = e0 - en;
	int e = diff >= 0 ? (diff + n / 2) / n : -((-diff + n / 2) / n);
	int emax = -100000;
	for (int k = 0; k <= n; ++k) {
		if (a[k + z] == 0.0)
			continue;
		int ek = ilogb(a[k + z]) + k * e;
		if (ek > emax)
			emax = ek;
	}
	for (int k = 0; k <= n; ++k)
		p->b[k] = sgn * ldexp(a[k + z], k * e - emax);
	p->scale = e;
	p->safe = true;
	while (p->n > 0 && p->b[p->n] == 0.0)
		--p->n; // the leading term underflowed: its roots are beyond the double range
	return true;
}

// y * 2^e without overflow in an intermediate power (x = 2^e y).
static double pool_q_unscale(double y, int e) {
	return e == 0 ? y : ldexp(y, e);
}

// Newton-polygon split. The roots of p group by magnitude along the upper convex hull of the
// points (k, log2 |a_k|): an edge of slope s carries as many roots as its width, of magnitude
// about 2^-s. Where the hull bends by G bits at a vertex k (the slopes on its two sides differ by
// G), p's roots below the bend are those of a_0 + ... + a_k x^k and the ones above it those of
// a_k + ... + a_n x^(n-k), up to relative perturbations of order 2^-G (the terms dropped are that
// much smaller than the ones kept, at every root of the group). One scaling x = 2^e y cannot keep
// p's values at every root in the double range once its roots spread over more than about 300
// orders of magnitude (coefficients anywhere in the double range allow over 600): the values at
// the smallest roots fall into the subnormal range or below, signs and roots are lost. So an
// extreme polynomial (not moderate, see pool_q_prepare) whose hull bends by at least
// POOL_Q_SPLIT_BITS is split at its largest bend and each part solved with its own scaling;
// a part spreads its roots over at most 3 * POOL_Q_SPLIT_BITS bits, well inside what one scaling
// handles. The perturbation 2^-100 is far below the rounding of the coefficients.
#define POOL_Q_SPLIT_BITS 100.0

// ilogb(x) for x != 0 finite, inline for normal x.
static inline int pool_q_ilogb(double x) {
	uint64_t bits;
	memcpy(&bits, &x, sizeof bits);
	int e = (int)((bits >> 52) & 0x7FF);
	return e != 0 ? e - 1023 : ilogb(x);
}

// a[0..n] ascending, a[0] and a[n] non-zero: the interior hull vertex with the largest bend, its
// bend in bits in *bend (0 and 0 when there is none). Slopes in twelfths of a bit, integers (12 is
// a multiple of every width 1 .. 4).
static int pool_q_split_vertex(const double *a, int n, double *bend) {
	int e[5], best = 0, gbest = 0;
	for (int k = 0; k <= n; ++k)
		e[k] = a[k] != 0.0 ? pool_q_ilogb(a[k]) : 0;
	for (int k = 1; k < n; ++k) {
		if (a[k] == 0.0)
			continue;
		int left = INT_MAX, right = INT_MIN;
		for (int j = 0; j < k; ++j) {
			int sl = a[j] != 0.0 ? 12 * (e[k] - e[j]) / (k - j) : INT_MAX;
			left = sl < left ? sl : left;
		}
		for (int l = k + 1; l <= n; ++l) {
			int sr = a[l] != 0.0 ? 12 * (e[l] - e[k]) / (l - k) : INT_MIN;
			right = sr > right ? sr : right;
		}
		if (left - right > gbest) {
			gbest = left - right;
			best = k;
		}
	}
	*bend = gbest / 12.0;
	return best;
}

static int pool_q_solve_split(const pool_q_poly *p, const double c[5], double lo, double hi, double *out, bool first_only);

// Real roots in [lo, hi] (x, not scaled) of the polynomial c[0] x^4 + ... + c[4] (finite), prepared
// as *p, other than its exact zero roots, ascending by multiplicity; with first_only only the
// smallest one. Roots that overflow when unscaled are dropped.
static inline int pool_q_solve(const pool_q_poly *p, const double c[5], double lo, double hi, double *out, bool first_only) {
	// (The bend at any hull vertex is at most -B_0 - B_n, with B_k = ilogb(b_k) for the balanced,
	// normalised coefficients, max B_k = 0: no split unless the end coefficients are small.)
	if (p->safe && p->deg >= 2 && fabs(p->b[0]) * fabs(p->b[p->deg]) < 0x1p-90) {
		int m = pool_q_solve_split(p, c, lo, hi, out, first_only);
		if (m >= 0)
			return m;
	}
	double y[4];
	double ylo = pool_q_unscale(lo, -p->scale), yhi = pool_q_unscale(hi, -p->scale);
	pool_q_p pp = {p->b, p->n, p->safe};
	int m = pool_q_roots_in(&pp, ylo, yhi, y, first_only, &pool_q_stop_root);
	// (A quadratic gives both its roots even with first_only: out holds one root then.)
	int count = 0;
	for (int i = 0; i < m && !(first_only && count > 0); ++i) {
		double x = pool_q_unscale(y[i], p->scale);
		if (isfinite(x) && x >= lo && x <= hi)
			out[count++] = x;
	}
	return count;
}

// pool_q_solve by the split at the largest bend of the Newton polygon when it bends by at least
// POOL_Q_SPLIT_BITS; -1 when it does not (the caller solves p whole).
static int pool_q_solve_split(const pool_q_poly *p, const double c[5], double lo, double hi, double *out, bool first_only) {
	const int n = p->deg;
	double a[5]; // ascending, the zero roots divided out
	for (int k = 0; k <= n; ++k)
		a[k] = c[4 - p->zeros - k];
	double bend;
	int k = pool_q_split_vertex(a, n, &bend);
	if (k == 0 || !(bend >= POOL_Q_SPLIT_BITS))
		return -1;
	// The parts, highest degree first: a_k x^k + ... + a_0 and a_n x^(n-k) + ... + a_k.
	double low[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, high[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
	for (int i = 0; i <= k; ++i)
		low[4 - i] = a[i];
	for (int i = k; i <= n; ++i)
		high[4 - (i - k)] = a[i];
	pool_q_poly pl, ph;
	(void)pool_q_prepare(low, &pl);
	(void)pool_q_prepare(high, &ph);
	double rl[4], rh[4];
	int ml = pool_q_solve(&pl, low, lo, hi, rl, first_only);
	int mh = pool_q_solve(&ph, high, lo, hi, rh, first_only);
	// Merged ascending; out holds one root only with first_only.
	const int cap = first_only ? 1 : 4;
	int m = 0, i = 0, j = 0;
	while ((i < ml || j < mh) && m < cap) {
		if (j >= mh || (i < ml && rl[i] <= rh[j]))
			out[m++] = rl[i++];
		else
			out[m++] = rh[j++];
	}
	return m;
}

int pool_quartic_real_roots(const double c[5], double roots[4]) {
	if (!c || !roots)
		return 0;
	// The verified algebraic path first; it declines (-1) whatever it cannot answer for sure.
	int fast = pool_quartic_fast_real_roots(c, roots);
	if (fast >= 0)
		return fast;
	pool_q_poly p;
	if (!pool_q_prepare(c, &p))
		return 0;
	double x[4];
	int m = p.n > 0 ? pool_q_solve(&p, c, -INFINITY, INFINITY, x, false) : 0;
	// Merge the exact zero roots in ascending order.
	int count = 0, zeros = p.zeros;
	for (int i = 0; i < m; ++i) {
		while (zeros > 0 && x[i] > 0.0) {
			roots[count++] = 0.0;
			--zeros;
		}
		roots[count++] = x[i];
	}
	while (zeros-- > 0)
		roots[count++] = 0.0;
	return count;
}

int pool_quartic_smallest_root_in(const double c[5], double lo, double hi, double *root) {
	if (!c || !root || !(lo <= hi))
		return -1;
	// Isolation inside [lo, hi] only, not the algebraic fast path: most collision windows hold no
	// root, and isolation proves that from a few signs, while the fast path always finds all four
	// roots. Measured on the engine's own workload (pool-bench-shot): frozen break 104 us with
	// isolation, 124 us with the fast path, although the fast path wins on pool-bench-quartic's
	// [0, 10 s] windows, which mostly do hold a root.
	pool_q_poly p;
	if (!pool_q_prepare(c, &p))
		return -1;
	bool zero_in = p.zeros > 0 && lo <= 0.0 && 0.0 <= hi;
	double x;
	// Only roots below 0 can beat an exact zero root.
	if (p.n > 0 && pool_q_solve(&p, c, lo, zero_in && hi > 0.0 ? 0.0 : hi, &x, true) > 0 && !(zero_in && x > 0.0)) {
		*root = x;
		return 0;
	}
	if (zero_in) {
		*root = 0.0;
		return 0;
	}
	return -1;
}
