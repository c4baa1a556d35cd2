// When two bodies meet next, from their gap polynomial (docs/physics.md "Predicting events").
//
// Every contact prediction reduces to one question about a gap function f(tau), a polynomial
// of degree <= 4 in the time tau from now that is positive while the bodies are apart, zero at
// contact and negative when they interpenetrate: |p(tau)|^2 - (2R)^2 for two balls, the
// distance of the centre to a cushion's contact line for a ball and a rail (and, with airborne
// motion and LINK, the height above the cloth and the pairs of a cluster). The answer depends
// on the sign and size of nothing but the gap, its rate and its curvature now, so every kind of
// contact inherits the same treatment of touching bodies:
//
// - Apart (gap > POOL_TOUCH_TOLERANCE): the first root of f where the bodies approach (f' < 0),
//   however slowly. A root where they separate (a graze) is stepped over.
// - Touching or interpenetrating (gap <= POOL_TOUCH_TOLERANCE, of either sign): the contact is
//   live. The bodies collide now when they approach faster than POOL_APPROACH_EPS; when the
//   normal speed is smaller than that, in either direction, rounding cannot tell its sign and
//   the normal acceleration decides: pressed together means now (a pair leaving at 1e-10 m/s
//   while friction pulls it back has no later root the solver could see: it would pass
//   through), and so does a slow drift in that nothing stops before the bodies interpenetrate
//   by more than the tolerance.
//   Otherwise the gap is taken as exactly zero (f(0) = 0, so f = tau q(tau)) and the next
//   meeting is the first root of q where the bodies approach: the return of a pair that leaves
//   and is pulled back, found exactly however small the separation in between. A pair creeping
//   in whose acceleration parts it only now (the higher terms may turn it in again before it
//   opens) meets also where its true gap passes -POOL_TOUCH_TOLERANCE, if that comes first.
// In every case the bodies never pass through each other between events: a crossing the root
// solver missed is caught by f's sign at the end of the window and bisected.
#ifndef POOL_CONTACT_H
#define POOL_CONTACT_H

#include <math.h>

/// Normal approach speed (m/s) that counts as approaching for bodies already in contact.
/// Every accepted collision reverses the normal relative velocity (times the restitution), so
/// a pair cannot be found colliding again at the same instant unless it approaches faster than
/// this: this is what ends chains of simultaneous contacts (frozen racks). Below it the sign of
/// the speed is within the rounding of velocities (~1e-15 m/s) and accumulated positions, and
/// the acceleration decides. 1e-9 m/s over a whole shot moves a ball by nanometres.
#define POOL_APPROACH_EPS 1e-9

/// A contact's gap polynomial and its state now.
typedef struct pool_contact_gap {
	double f[5];  ///< f(tau) = f[0] + f[1] tau + ... + f[4] tau^4: > 0 apart, 0 touching
	double gap;   ///< m, distance between the surfaces now (< 0: interpenetrating)
	double speed; ///< m/s, normal approach speed now (> 0: approaching)
	double accel; ///< m/s^2, normal approach acceleration now (> 0: pressed together); read only
	              ///< when |speed| <= POOL_APPROACH_EPS
} pool_contact_gap;

/// Earliest tau in [0, T] at which the bodies meet while approaching (rules above); INFINITY
/// when none.
double pool_contact_next(const pool_contact_gap *g, double T);

/// First root in [0, T] of p[0] + p[1] t + ... + p[deg] t^deg (deg <= 4) where it falls (the
/// gap closes), INFINITY when none: the rule for bodies apart, when the caller knows they are.
double pool_contact_first_falling_root(const double *p, int deg, double T);

/// First root in [lo, T] of the same polynomial where it falls, INFINITY when none: the search
/// past a root that was no contact (a ghost: the contact point outside the part's span).
double pool_contact_first_falling_root_from(const double *p, int deg, double lo, double T);

/// Relative margin of pool_contact_quadratic_apart: a gap quadratic whose least value over the
/// window exceeds this fraction of the size of its terms (|f0| + |f1| T + |f2| T^2) is positive
/// however its evaluation rounds (a few ulps, 1e-16), and its roots lie so far outside the window
/// that no rounding of the closed form brings one in: the root finder would report none.
#define POOL_CONTACT_APART_REL 1e-9

/// 1 when f0 + f1 t + f2 t^2 stays above zero, by POOL_CONTACT_APART_REL, over [0, T] (T finite):
/// its least value there, at an end or at its vertex, is that far above zero. The bodies cannot
/// meet in the window; the callers then leave out the root finder (the same answer, INFINITY).
/// Inline: most of the cushion predictions of a segment end here.
static inline int pool_contact_quadratic_apart(double f0, double f1, double f2, double T) {
	if (!(T >= 0.0 && T < INFINITY))
		return 0;
	const double scale = fabs(f0) + (fabs(f1) + fabs(f2) * T) * T, margin = POOL_CONTACT_APART_REL * scale;
	double least = f0 + (f1 + f2 * T) * T;
	least = f0 < least ? f0 : least;
	if (f2 > 0.0 && f1 < 0.0 && -f1 < 2.0 * f2 * T) { // the vertex -f1 / (2 f2) inside (0, T)
		const double vertex = f0 - f1 * f1 / (4.0 * f2);
		least = vertex < least ? vertex : least;
	}
	return least > margin;
}

/// 1 when bodies in contact (gap <= POOL_TOUCH_TOLERANCE) collide now by the rules above.
int pool_contact_now(double gap, double speed, double accel);

/// pool_contact_now over a window of T seconds: a drift in counts only if it can pass the
/// tolerance within the window (at most speed T deeper).
int pool_contact_now_within(double gap, double speed, double accel, double T);

#endif
