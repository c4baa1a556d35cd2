// When two bodies meet next, from their gap polynomial (the rules are in contact.h).
#include "contact.h"

#include <math.h>

#include "pool/quartic.h"
#include "pool/sim.h"

/// Relative step past a root where the bodies separate before the next root is searched: the
/// solver's roots are accurate to a few ulps, so 1e-13 (1 + t) cannot find the same root again,
/// and a second root that close to it is the other half of a graze (overlap < 1e-20 m).
#define CONTACT_ROOT_STEP 1e-13

int pool_contact_now(double gap, double speed, double accel) { return pool_contact_now_within(gap, speed, accel, INFINITY); }

int pool_contact_now_within(double gap, double speed, double accel, double T) {
	if (speed > POOL_APPROACH_EPS)
		return 1; // approaching
	if (speed < -POOL_APPROACH_EPS)
		return 0; // leaving at a speed rounding cannot fake: the polynomial says when they return
	// The speed's sign is within rounding: pressed together means in contact now, ...
	if (accel > 0.0)
		return 1;
	// ... and so does drifting in when nothing stops the drift before the bodies interpenetrate
	// by more than the tolerance (a drift at speed v against a separating acceleration a goes
	// v^2 / 2|a| deeper before it turns).
	if (!(speed > 0.0))
		return 0;
	// Within the window the drift goes at most speed T deeper (the acceleration only slows it):
	// a drift of 1e-30 m/s, the rounding of a linked ball's velocity, reaches no overlap in the
	// milliseconds to the next event, where v^2 / 2|a| (|a| 6.5e-60 m/s^2) called it 8.6 cm deep
	// and a contact now (soak seed 45, cluster shot 1988: a contact at a step's start that cut it
	// after no time, again and again). What the window holds is pool_contact_next's.
	if (!(gap - speed * T < -POOL_TOUCH_TOLERANCE))
		return 0;
	return accel == 0.0 || gap - speed * speed / (-2.0 * accel) < -POOL_TOUCH_TOLERANCE;
}

// p(t) for p[0] + p[1] t + ... + p[deg] t^deg (Horner).
static double eval(const double *p, int deg, double t) {
	double v = p[deg];
	for (int k = deg - 1; k >= 0; --k)
		v = v * t + p[k];
	return v;
}

// p'(t).
static double eval_slope(const double *p, int deg, double t) {
	double v = deg * p[deg];
	for (int k = deg - 1; k >= 1; --k)
		v = v * t + k * p[k];
	return deg >= 1 ? v : 0.0;
}

// Insurance against a root the solver lost: not closing now (p(0) >= 0), interpenetrating at
// the end of the window means a crossing in between; bisect for the last instant still apart.
// INFINITY when there is none.
static double lost_crossing(const double *p, int deg, double T) {
	if (!(p[0] >= 0.0 && isfinite(T) && eval(p, deg, T) < 0.0))
		return INFINITY;
	double a = 0.0, b = T;
	for (int i = 0; i < 200; ++i) {
		const double mid = 0.5 * (a + b);
		if (mid <= a || mid >= b)
			break;
		if (eval(p, deg, mid) >= 0.0)
			a = mid;
		else
			b = mid;
	}
	return a;
}

/// Coefficient magnitudes within which the quadratic formula neither overflows nor underflows
/// (b^2 and 4ac stay normal); outside, the scaled general solver takes the case (a subnormal
/// velocity such as 5e-324 m/s once gave a "root" at 0 from an underflowed discriminant).
#define CONTACT_CLOSED_FORM_MIN 1e-150
#define CONTACT_CLOSED_FORM_MAX 1e150

static int closed_form_safe(const double *p, int deg) {
	for (int k = 0; k <= deg; ++k) {
		const double m = fabs(p[k]);
		if (m != 0.0 && !(m >= CONTACT_CLOSED_FORM_MIN && m <= CONTACT_CLOSED_FORM_MAX))
			return 0;
	}
	return 1;
}

// First root in [0, T] of a + b t + c t^2 where it falls, INFINITY when none: the closed form
// (the numerically stable pair of roots), for the contacts of a ball with a line.
static double first_falling_root_quadratic(double a, double b, double c, double T) {
	double r[2];
	int n = 0;
	if (c == 0.0) {
		if (b != 0.0)
			r[n++] = -a / b;
	} else {
		const double disc = b * b - 4.0 * c * a;
		if (disc >= 0.0) {
			const double q = -0.5 * (b + copysign(sqrt(disc), b));
			if (q != 0.0) {
				r[n++] = q / c;
				r[n++] = a / q;
			} else if (a == 0.0) {
				r[n++] = 0.0; // a = b = 0: a double root at 0
			}
		}
	}
	if (n == 2 && r[1] < r[0]) {
		const double t = r[0];
		r[0] = r[1];
		r[1] = t;
	}
	for (int i = 0; i < n; ++i)
		if (r[i] >= 0.0 && r[i] <= T && b + 2.0 * c * r[i] < 0.0)
			return r[i];
	const double p[3] = {a, b, c};
	return lost_crossing(p, 2, T);
}

double pool_contact_first_falling_root(const double *p, int deg, double T) {
	while (deg > 0 && p[deg] == 0.0)
		--deg;
	if (deg <= 2 && closed_form_safe(p, deg))
		return first_falling_root_quadratic(p[0], deg >= 1 ? p[1] : 0.0, deg >= 2 ? p[2] : 0.0, T);
	if (p[0] > 0.0 && isfinite(T)) {
		// Apart by more than the falling terms can take over the window: for t in [0, T] a term
		// p_k t^k with p_k >= 0 only adds, and one with p_k < 0 takes at most |p_k| T^k (summed,
		// with a margin for that sum's rounding). No root then, without the quartic solver. Most
		// pairs the schedule asks about over a short window (a linked ball's step) end here, and
		// so do touching pairs moving apart (p_1 > 0) that nothing brings back in the window.
		double reach = 0.0, power = 1.0;
		for (int k = 1; k <= deg; ++k) {
			power *= T;
			if (p[k] < 0.0)
				reach -= p[k] * power;
		}
		if (reach * (1.0 + 1e-12) < p[0])
			return INFINITY;
	}
	double c[5] = {0.0, 0.0, 0.0, 0.0, 0.0}; // the solver's order: highest degree first
	for (int k = 0; k <= deg; ++k)
		c[4 - k] = p[k];
	if (!isfinite(T)) {
		// An endless window (both segments endless: no friction, or an infinite max_time) is
		// outside the window solver's scaling: take every real root.
		double roots[4];
		const int n = pool_quartic_real_roots(c, roots);
		for (int i = 0; i < n; ++i)
			if (roots[i] >= 0.0 && eval_slope(p, deg, roots[i]) < 0.0)
				return roots[i];
		return INFINITY;
	}
	double lo = 0.0, t;
	for (int it = 0; it <= deg && pool_quartic_smallest_root_in(c, lo, T, &t) == 0; ++it) {
		if (eval_slope(p, deg, t) < 0.0)
			return t;
		lo = t + CONTACT_ROOT_STEP * (1.0 + t);
		if (!(lo <= T))
			break;
	}
	return lost_crossing(p, deg, T);
}

double pool_contact_first_falling_root_from(const double *p, int deg, double lo, double T) {
	if (!(lo <= T))
		return INFINITY;
	// q(u) = p(lo + u): a Taylor shift, then the window [0, T - lo].
	double q[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
	for (int k = 0; k <= deg; ++k)
		q[k] = p[k];
	for (int i = 0; i < deg; ++i)
		for (int k = deg - 1; k >= i; --k)
			q[k] += lo * q[k + 1];
	const double u = pool_contact_first_falling_root(q, deg, T - lo);
	return u < INFINITY ? lo + u : INFINITY;
}

// A pair creeping in (q(0) < 0) that the drift test let go, the acceleration now parting it,
// may still go deeper: the acceleration is f's curvature at this instant only, and the higher
// terms can turn it before q ever rises (two balls rolling side by side at 2.5e-11 m/s, the
// tangential speed parting them by 6e-9 m/s^2 while their friction turns them together: 1.04e-9
// m deep 0.19 s later, soak seed 29, nose shot 34885). So the contact is q's next meeting, or
// where the gap, from its true value now, passes -POOL_TOUCH_TOLERANCE if that comes first: the
// first falling root of f + POOL_TOUCH_TOLERANCE df/dgap (df/dgap = -f'(0) / speed: 1 for a
// line, 2 |p| for a sphere). In the common creeping pair the overlap turns within rounding and
// that root does not exist.
static double creeping_next(const pool_contact_gap *g, const double *q, double T) {
	const double next = pool_contact_first_falling_root(q, 3, T);
	const double per_gap = -g->f[1] / g->speed;
	if (!(per_gap > 0.0 && per_gap < INFINITY))
		return next;
	const double deep[5] = {g->f[0] + per_gap * POOL_TOUCH_TOLERANCE, g->f[1], g->f[2], g->f[3], g->f[4]};
	const double t = pool_contact_first_falling_root(deep, 4, next < T ? next : T);
	return t < next ? t : next;
}

double pool_contact_next(const pool_contact_gap *g, double T) {
	if (!(T >= 0.0))
		return INFINITY;
	if (g->gap > POOL_TOUCH_TOLERANCE)
		return T > 0.0 ? pool_contact_first_falling_root(g->f, 4, T) : INFINITY;
	if (pool_contact_now_within(g->gap, g->speed, g->accel, T))
		return 0.0;
	// Touching, not colliding now: the gap is exactly zero, f = tau q(tau), and for tau > 0 q
	// has the sign of the gap (a root of q where it falls is one where f falls: f' = tau q').
	// A pair creeping together too slowly to matter (q(0) < 0) first separates: that root of q
	// rises and is stepped over, unless the pair goes deeper first (creeping_next).
	const double q[4] = {g->f[1], g->f[2], g->f[3], g->f[4]};
	if (g->f[1] < 0.0 && g->speed > 0.0)
		return creeping_next(g, q, T);
	return pool_contact_first_falling_root(q, 3, T);
}
