// Mathavan, Jackson & Parkin (2010) cushion impact: the equations of motion over the normal
// impulse, integrated adaptively, the contacts' stick-slip transitions taken where they happen.
//
// Frame of the impact: y towards the cushion (horizontal), z up, x = y × z along the rail. The
// nose touches the ball at r_I = R (0, c, s) from its centre (c = cos θ, s = sin θ; sin θ = 2/5 at
// the paper's h = 7R/5, here taken from the actual normal), the cloth at r_C = (0, 0, −R).
// Units: velocities v, the surface speeds u = R ω, and as the independent variable p = P / M, the
// nose's normal impulse per unit mass; the equations then hold no mass or radius. Per dp:
//   - the nose's normal impulse along −(0, c, s);
//   - friction at the nose f (per unit dp, in its tangent plane: x and y' = (0, −s, c)) against
//     the nose's slip s_I = (v_x + s u_y − c u_z, −s v_y + c v_z + u_x), |f| <= mu_cushion_mathavan;
//   - the cloth's normal impulse n_C = s − c f_y' per unit dp: what holds v_z at zero (the ball
//     stays on the cloth), never pulling; when it would (n_C < 0) the ball leaves the cloth
//     during the impact and lands back when v_z returns to zero;
//   - friction at the cloth g against its slip s_C = (v_x − u_y, v_y + u_x), |g| <= mu_table n_C.
// The paper's equations (12)-(17), written in vector form:
//   v_x' = f_x + g_x, v_y' = −c − s f_y' + g_y, v_z' = 0 on the cloth (−s + c f_y' off it),
//   u_x' = 5/2 (f_y' + g_y), u_y' = 5/2 (s f_x − g_x), u_z' = −5/2 c f_x,
// so the slips move as s_I' = (7/2 f_x + a g_x, (5/2 + s²) f_y' + b g_y + c s) on the cloth,
// s_C' = (a f_x + 7/2 g_x, −c + b f_y' + 7/2 g_y), with a = 1 − 5s/2 and b = 5/2 − s.
// A sliding contact's friction opposes its slip at full strength; a stuck contact's friction is
// whatever keeps its slip zero, solved from the two equations above (both contacts stuck: both
// slips constant, so a 2x2 system), as long as it stays within its cone.
//
// Compression lasts while the nose's normal velocity ż'_I = c v_y + s v_z is positive; the work of
// the normal force W = ∫ ż'_I dp is integrated with the velocities; restitution then runs until the
// work given back is e² W_c (Stronge's energetic coefficient, the paper's (16)).
//
// Between events the system is smooth (the friction directions turn smoothly while both contacts
// slide) and is integrated by Dormand & Prince's 5(4) pair with step control (dopri5.c). Where it
// is not, the integration stops on it:
//   - a stuck contact's friction leaving its cone, the ball leaving or landing on the cloth, the
//     end of compression and of restitution are located on the step's dense output;
//   - a sliding contact's slip reaching zero is landed on: the step is cut to end there (landing)
//     and the small miss cancelled by the impulse that ends it (cancel_slip);
// and the modes are decided again by Coulomb's law (decide_modes: stick where the friction that
// holds the contact fits its cone, else slide the way the slip then grows).
// Near zero slip a sliding contact's friction turns at a rate of about 7/2 mu N / |slip|, a stiff
// mode no explicit step resolves cheaply; where that rate times the step passes QUASI and the
// contact is near sticking, the step takes the slow manifold the slip is drawn to: the friction
// that would hold the contact, cut to its cone.
#include "cushion_mathavan.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "dopri5.h"
#include "vec3.h"

/// A slip below this fraction of the impact's speed scale counts as zero: a sliding contact there
/// opposes the direction it was decided (or last seen) to slide in. Rounding of the state's
/// velocities is about 1e-16 of it.
#define ZERO_SLIP 1e-10
/// A step landing a contact on zero slip holds its direction once its slip is below this
/// fraction of the slip at the step's start. (Holding it longer saves rejected landings where the
/// slip turns as it closes, 4 % of an impact's instructions at 0.2 over 3,000 break impacts, but
/// moves an impact of test_model_fidelity's grid by 3.9e-4 of its speed: the turn is the physics.)
#define LAND_HOLD 1e-3
/// A sliding contact's slip turning faster than this many times over a step: the step follows
/// its slow manifold (contact_forces). A lower bound takes the manifold sooner, where the slip's
/// own direction has not settled on it yet (2.0: p99 error 1e-3 over random impacts); 4 rather
/// than 3 cost 2 % fewer instructions over 3,000 break impacts at a smaller error.
#define QUASI 4.0
/// ... and whose friction that would hold it is within this many times its cone (the slow
/// manifold is then about where that friction is cut to the cone).
#define MARGINAL 1.5
/// A contact sliding from zero slip is consistent when its slip's rate along its direction is
/// above minus this fraction of its friction's own rate, 7/2 mu: at a stick's marginal end it grows
/// from rest, at rate 0 (the end is located to about this).
#define MARGINAL_RATE 1e-5
/// The start direction's length is found to this (relative) ...
#define START_PRECISION 1e-14
/// ... in at most this many tries (bisection alone takes about 60).
#define START_ITERATIONS 100
/// The first step, times tolerance^(1/5) and the frictionless impact's impulse.
#define FIRST_STEP 2.0
/// Gustafsson's predictive step control (Hairer & Wanner II, IV.8): the step after an accepted
/// one is also bounded by (h / h_prev) 0.9 (err_prev / err^2)^PREDICTIVE, which follows an error
/// that grows from step to step, as where a contact's slip shrinks towards zero and its friction
/// turns ever faster (an event or a landing starts the trend afresh). The theory's exponent is 1/5;
/// 0.1 rejected fewer steps over 3,000 impacts of breaks (1.9 an impact, against 4.0 without the
/// bound and 2.4 with 0.15) and left a smaller error (pool-bench-models --accuracy).
#define PREDICTIVE 0.1
/// Step tries before the impact is given up as jammed (Petit's law takes it; random impacts take
/// at most a few hundred: pool-bench-models --accuracy).
#define MAX_TRIES 2000
/// Compression given up as jammed (friction stopping ż'_I's decrease) beyond this many times the
/// normal impulse of the frictionless impact.
#define JAM_IMPULSES 8.0

// The state: v, u = R ω, W, and PAD, which fills the integrator's vectors (always 0). v_z, which
// moves only while the ball is off the cloth, comes after what always moves: steps on the cloth
// integrate the leading components alone (pool_dopri5_take_lead).
enum { VX, VY, UX, UY, UZ, WORK, VZ, PAD, DIM };
_Static_assert(DIM == POOL_DOPRI5_DIM, "the state fills the integrator's vectors");
_Static_assert(WORK < POOL_DOPRI5_LEAD && VZ >= POOL_DOPRI5_LEAD && PAD >= POOL_DOPRI5_LEAD,
               "on the cloth the leading components are those that move");
enum { NOSE, CLOTH };

typedef struct law {
	double c, s, mu_i, mu_c;
} law;

// How each contact behaves until the next event, and the directions sliding contacts oppose
// while their slip is (about) zero.
typedef struct modes {
	bool nose_stuck, cloth_stuck, airborne;
	bool nose_quasi, cloth_quasi; // this step: a sliding contact's slip too small for the step
	double nose_small, cloth_small; // slips this small slide along the contacts' directions
	double nose_dir[2], cloth_dir[2];
} modes;

typedef struct impact {
	law k;
	modes m;
	double zero;  // ZERO_SLIP times the speed scale
	unsigned frozen; // bit i: sliding contact i follows its direction even at zero slip
} impact;

typedef struct forces {
	double f[2], g[2], nc; // per unit dp: friction at the nose (x, y'), at the cloth (x, y); n_C
	bool ok;               // the stuck contacts' friction could be solved
} forces;

static void nose_slip(const law *k, const double *y, double out[2]) {
	out[0] = y[VX] + k->s * y[UY] - k->c * y[UZ];
	out[1] = -k->s * y[VY] + k->c * y[VZ] + y[UX];
}
static void cloth_slip(const double *y, double out[2]) {
	out[0] = y[VX] - y[UY];
	out[1] = y[VY] + y[UX];
}
static double dot2(const double a[2], const double b[2]) { return a[0] * b[0] + a[1] * b[1]; }
static double sq(double x) { return x * x; }
// fmin and fmax for the step control without their library calls (a NaN x gives the bound).
static double at_most(double x, double bound) { return x < bound ? x : bound; }
static double at_least(double x, double bound) { return x > bound ? x : bound; }

// log2 x (x > 0) and 2^y for the step control, to about 1e-3 relative, by polynomials of the
// double's mantissa and exponent read and written in its bits where x and the result are normal
// (frexp and ldexp otherwise: the same values, at the cost of a library call).
static double log2_approx(double x) {
	uint64_t bits;
	memcpy(&bits, &x, sizeof bits);
	const int biased = (int)(bits >> 52 & 0x7ff);
	int ex;
	double m; // in [0.5, 1)
	if (biased > 0 && biased < 0x7ff) {
		ex = biased - 1022;
		bits = (bits & 0x800fffffffffffffull) | 0x3fe0000000000000ull;
		memcpy(&m, &bits, sizeof m);
	} else {
		m = frexp(x, &ex);
	}
	const double t = m - 0.75;
	return ex + (-0.415037 + t * (1.9236 + t * (-1.2825 + t * 1.1398)));
}
static double exp2_approx(double y) {
	const double n = floor(y), f = y - n;
	const double r = 1.0 + f * (0.6931472 + f * (0.2402265 + f * (0.0555041 + f * 0.0096181))); // in [1, 2)
	if (!(n > -1000.0 && n < 1000.0))
		return ldexp(r, (int)n);
	const uint64_t two_n = (uint64_t)((int)n + 1023) << 52;
	double scale;
	memcpy(&scale, &two_n, sizeof scale);
	return r * scale;
}

static void unit_or_keep(const double v[2], double out[2]) {
	const double n = sqrt(dot2(v, v));
	if (n > 0.0) {
		out[0] = v[0] / n;
		out[1] = v[1] / n;
	}
}

// The direction a sliding contact's friction opposes: its slip's, but `ref` while the slip is
// within `zero` (its own direction is lost in the state's rounding or the step's error).
static void slide_direction(const double slip[2], const double ref[2], double zero, double out[2]) {
	const double s2 = dot2(slip, slip);
	if (s2 <= zero * zero) {
		out[0] = ref[0];
		out[1] = ref[1];
		return;
	}
	const double inv = 1.0 / sqrt(s2);
	out[0] = slip[0] * inv;
	out[1] = slip[1] * inv;
}

// The forces per unit dp with the contacts stuck or sliding along dn (nose) and dc (cloth).
static void forces_for(const impact *im, bool nose_stuck, bool cloth_stuck, const double dn[2], const double dc[2],
                       forces *o) {
	const law *k = &im->k;
	const double c = k->c, s = k->s, a = 1.0 - 2.5 * s, b = 2.5 - s;
	o->f[0] = o->f[1] = o->g[0] = o->g[1] = o->nc = 0.0;
	o->ok = true;
	if (!nose_stuck) {
		o->f[0] = -k->mu_i * dn[0];
		o->f[1] = -k->mu_i * dn[1];
	}
	if (im->m.airborne) // the nose alone: a stuck nose's slip is moved by nothing, so needs no friction
		return;
	if (nose_stuck && cloth_stuck) { // both slips constant: f_x = g_x = 0 and a 2x2 system
		const double det = 3.5 * (2.5 + s * s) - b * b;
		if (!(det > 0.0)) { // a nose at the ball's bottom: no solution
			o->ok = false;
			return;
		}
		o->f[1] = -c * (3.5 * s + b) / det;
		o->g[1] = c * (2.5 + s * s + b * s) / det;
		o->nc = s - c * o->f[1];
		return;
	}
	if (nose_stuck) { // the cloth slides along dc; its friction depends on f_y' through n_C
		const double den = 2.5 + s * s + b * k->mu_c * c * dc[1];
		if (!(den > 0.0)) { // friction beyond any cloth: no stick solution
			o->ok = false;
			return;
		}
		o->f[1] = s * (b * k->mu_c * dc[1] - c) / den;
		o->nc = s - c * o->f[1];
		o->g[0] = -k->mu_c * o->nc * dc[0];
		o->g[1] = -k->mu_c * o->nc * dc[1];
		o->f[0] = -a * o->g[0] / 3.5;
		return;
	}
	o->nc = s - c * o->f[1];
	if (cloth_stuck) {
		o->g[0] = -a * o->f[0] / 3.5;
		o->g[1] = (c - b * o->f[1]) / 3.5;
	} else {
		o->g[0] = -k->mu_c * o->nc * dc[0];
		o->g[1] = -k->mu_c * o->nc * dc[1];
	}
}

// The forces at y in the current modes. A sliding contact whose slip is within `zero` (and which a
// step is not landing on zero, where it keeps the direction it arrives in) is held:
// its friction is the one that would keep it stuck, cut to its cone's edge when beyond it (and
// then it slides along that friction). This is Coulomb's law where the slip's own direction is
// lost in rounding: where a contact has just started to slide (its slip growing from zero, at
// first along the direction its stick friction leaves the cone) and where it has just come to rest.
static void contact_forces(const impact *im, const double *y, forces *o) {
	const law *k = &im->k;
	const modes *m = &im->m;
	double slip[2], dn[2] = {0.0, 0.0}, dc[2] = {0.0, 0.0};
	if (!im->frozen && !m->nose_stuck && !m->cloth_stuck && !m->airborne && !m->nose_quasi && !m->cloth_quasi &&
	    m->nose_small <= im->zero && m->cloth_small <= im->zero) { // (derivative_sliding repeats this branch)
		// Both sliding on the cloth (most of an impact): each friction against its slip.
		const double si[2] = {y[VX] + k->s * y[UY] - k->c * y[UZ], -k->s * y[VY] + k->c * y[VZ] + y[UX]};
		const double sc[2] = {y[VX] - y[UY], y[VY] + y[UX]};
		const double ni = dot2(si, si), nc = dot2(sc, sc), z2 = im->zero * im->zero;
		if (ni > z2 && nc > z2) {
			const double gi = k->mu_i / sqrt(ni);
			o->f[0] = -gi * si[0];
			o->f[1] = -gi * si[1];
			o->nc = k->s - k->c * o->f[1];
			const double gc = k->mu_c * o->nc / sqrt(nc);
			o->g[0] = -gc * sc[0];
			o->g[1] = -gc * sc[1];
			o->ok = true;
			return;
		}
	}
	bool nose_held = m->nose_stuck, cloth_held = m->cloth_stuck || m->airborne;
	if (!nose_held) {
		nose_slip(k, y, slip);
		nose_held = !(im->frozen & 1u) &&
		            (m->nose_quasi || (m->nose_small <= im->zero && dot2(slip, slip) <= im->zero * im->zero));
		if (im->frozen & 1u)
			dn[0] = m->nose_dir[0], dn[1] = m->nose_dir[1];
		else
			slide_direction(slip, m->nose_dir, m->nose_small, dn);
	}
	if (!cloth_held) {
		cloth_slip(y, slip);
		cloth_held = !(im->frozen & 2u) &&
		             (m->cloth_quasi || (m->cloth_small <= im->zero && dot2(slip, slip) <= im->zero * im->zero));
		if (im->frozen & 2u)
			dc[0] = m->cloth_dir[0], dc[1] = m->cloth_dir[1];
		else
			slide_direction(slip, m->cloth_dir, m->cloth_small, dc);
	}
	forces_for(im, nose_held, cloth_held, dn, dc, o);
	if (nose_held && !m->nose_stuck && (!o->ok || dot2(o->f, o->f) > k->mu_i * k->mu_i)) {
		if (o->ok) {
			dn[0] = -o->f[0], dn[1] = -o->f[1];
			unit_or_keep(dn, dn);
		}
		nose_held = false;
		forces_for(im, nose_held, cloth_held, dn, dc, o);
	}
	if (cloth_held && !m->cloth_stuck && !m->airborne &&
	    (!o->ok || dot2(o->g, o->g) > k->mu_c * k->mu_c * o->nc * o->nc)) {
		if (o->ok) {
			dc[0] = -o->g[0], dc[1] = -o->g[1];
			unit_or_keep(dc, dc);
		}
		forces_for(im, nose_held, false, dn, dc, o);
	}
}

static void derivative_of(const impact *im, const double *y, const forces *o, double *dy) {
	const law *k = &im->k;
	dy[VX] = o->f[0] + o->g[0];
	dy[VY] = -k->c - k->s * o->f[1] + o->g[1];
	dy[VZ] = im->m.airborne ? -k->s + k->c * o->f[1] : 0.0;
	dy[UX] = 2.5 * (o->f[1] + o->g[1]);
	dy[UY] = 2.5 * (k->s * o->f[0] - o->g[0]);
	dy[UZ] = -2.5 * k->c * o->f[0];
	dy[WORK] = k->c * y[VY] + k->s * y[VZ];
	dy[PAD] = 0.0;
}

static void derivative(const void *ctx, const double *y, double *dy) {
	const impact *im = ctx;
	forces o;
	contact_forces(im, y, &o);
	derivative_of(im, y, &o, dy);
}

// The same while both contacts slide on the cloth and neither is held (both_sliding): the
// common case, without the modes' tests (contact_forces' first branch and derivative_of), and
// without v_z, zero on the cloth.
static void derivative_sliding(const void *ctx, const double *y, double *dy) {
	const impact *im = ctx;
	const law *k = &im->k;
	const double si[2] = {y[VX] + k->s * y[UY] - k->c * y[UZ], -k->s * y[VY] + y[UX]};
	const double sc[2] = {y[VX] - y[UY], y[VY] + y[UX]};
	const double ni = dot2(si, si), nc = dot2(sc, sc), z2 = im->zero * im->zero;
	if (!(ni > z2 && nc > z2)) {
		derivative(ctx, y, dy);
		return;
	}
	const double gi = k->mu_i / sqrt(ni);
	const double f[2] = {-gi * si[0], -gi * si[1]};
	const double n_c = k->s - k->c * f[1];
	const double gc = k->mu_c * n_c / sqrt(nc);
	const double g[2] = {-gc * sc[0], -gc * sc[1]};
	dy[VX] = f[0] + g[0];
	dy[VY] = -k->c - k->s * f[1] + g[1];
	dy[VZ] = 0.0;
	dy[UX] = 2.5 * (f[1] + g[1]);
	dy[UY] = 2.5 * (k->s * f[0] - g[0]);
	dy[UZ] = -2.5 * k->c * f[0];
	dy[WORK] = k->c * y[VY];
	dy[PAD] = 0.0;
}

// Both contacts slide on the cloth along their slips (derivative_sliding applies).
static bool both_sliding(const impact *im) {
	const modes *m = &im->m;
	return !im->frozen && !m->nose_stuck && !m->cloth_stuck && !m->airborne && !m->nose_quasi && !m->cloth_quasi &&
	       m->nose_small <= im->zero && m->cloth_small <= im->zero;
}

// ---------------------------------------------------------------- deciding the modes

// Coulomb's law where a contact's slip is zero: it sticks if the friction that keeps it so fits
// its cone, else it slides along the direction its slip then grows in (start_direction).
typedef struct choice {
	bool zero[2];   // the contact's slip is zero
	bool slide[2];  // the contact was seen to leave stick (or reverse): it may not stick now
	bool airborne;  // the ball must leave the cloth
} choice;

static void slip_rates(const impact *im, const double *y, double nose[2], double cloth[2]) {
	forces o;
	double dy[DIM];
	contact_forces(im, y, &o);
	derivative_of(im, y, &o, dy);
	nose_slip(&im->k, dy, nose); // the slips are linear in the state
	cloth_slip(dy, cloth);
}

// Ends start_direction: the contact's direction is d's (held in dir), the directions no longer
// frozen.
static void take_start_direction(impact *im, const double d[2], double dir[2]) {
	im->frozen = 0u;
	dir[0] = dir[1] = 0.0;
	unit_or_keep(d, dir);
	if (!(dot2(dir, dir) > 0.0))
		dir[0] = 1.0; // nothing moves the slip: any direction (it is not used before it grows)
}

// The direction a contact starts to slide in from zero slip: d with slip' (d) = lambda d,
// lambda > 0. Its slip's rate is affine in its own friction, rate(d) = a + B d (a: with no friction
// there; B's columns from d along the axes), so d = (lambda I − B)^−1 a with lambda found where
// that has unit length (it shrinks as lambda grows; at lambda = 0 it is longer than 1 exactly when
// the contact cannot stick). For the cloth, with the nose sliding, B is −7/2 mu_table n_C I and d
// is a's direction, taken at once; the nose's B is not isotropic on the cloth (its friction moves
// n_C), nor the cloth's with the nose stuck. Sets the contact's direction.
static void start_direction(impact *im, const double *y, int i) {
	double *dir = i == NOSE ? im->m.nose_dir : im->m.cloth_dir;
	double rate[2][2], a[2], B[2][2];
	im->frozen = 3u;
	dir[0] = dir[1] = 0.0;
	slip_rates(im, y, rate[NOSE], rate[CLOTH]);
	a[0] = rate[i][0], a[1] = rate[i][1];
	if (i == CLOTH && !im->m.nose_stuck && !im->m.airborne) { // B isotropic: d is a's direction
		take_start_direction(im, a, dir);
		return;
	}
	for (int j = 0; j < 2; ++j) {
		dir[0] = j == 0, dir[1] = j == 1;
		slip_rates(im, y, rate[NOSE], rate[CLOTH]);
		B[0][j] = rate[i][0] - a[0];
		B[1][j] = rate[i][1] - a[1];
	}
	// |d(lambda)|^2 - 1 falls as lambda grows past B's spectrum: Newton's method from above (hi,
	// where |d| < 1), kept inside the bracket, bisecting where a step leaves it.
	double lo = 0.0, hi = sqrt(dot2(a, a)) + fabs(B[0][0]) + fabs(B[0][1]) + fabs(B[1][0]) + fabs(B[1][1]);
	double d[2] = {a[0], a[1]}, lambda = hi;
	for (int it = 0; it < START_ITERATIONS && hi > lo; ++it) {
		const double m00 = lambda - B[0][0], m01 = -B[0][1], m10 = -B[1][0], m11 = lambda - B[1][1];
		const double det = m00 * m11 - m01 * m10;
		if (!(det != 0.0)) {
			lo = lambda;
			lambda = 0.5 * (lo + hi);
			continue;
		}
		d[0] = (m11 * a[0] - m01 * a[1]) / det;
		d[1] = (m00 * a[1] - m10 * a[0]) / det;
		const double excess = dot2(d, d) - 1.0;
		if (excess > 0.0)
			lo = lambda;
		else
			hi = lambda;
		if (fabs(excess) <= START_PRECISION)
			break;
		// d' = -M^-1 d, so (|d|^2)' = -2 d . M^-1 d.
		const double e0 = (m11 * d[0] - m01 * d[1]) / det, e1 = (m00 * d[1] - m10 * d[0]) / det;
		const double slope = -2.0 * (d[0] * e0 + d[1] * e1);
		double next = slope < 0.0 ? lambda - excess / slope : 0.5 * (lo + hi);
		if (!(next > lo && next < hi))
			next = 0.5 * (lo + hi);
		if (next == lambda)
			break;
		lambda = next;
	}
	take_start_direction(im, d, dir);
}

// Sets the directions of the contacts sliding from zero slip (from_zero[i]); true when each
// one's slip then grows along its direction. Both from zero: each in turn, twice.
static bool directions_from_zero(impact *im, const double *y, const bool from_zero[2]) {
	const int rounds = from_zero[NOSE] && from_zero[CLOTH] ? 3 : 1;
	for (int r = 0; r < rounds; ++r)
		for (int i = 0; i < 2; ++i)
			if (from_zero[i])
				start_direction(im, y, i);
	double rate[2][2];
	slip_rates(im, y, rate[NOSE], rate[CLOTH]);
	const double *dir[2] = {im->m.nose_dir, im->m.cloth_dir};
	for (int i = 0; i < 2; ++i) // at a stick's marginal end the slip grows from rest: rate ~ 0
		if (from_zero[i] && !(dot2(rate[i], dir[i]) > -MARGINAL_RATE * 3.5 * (i == NOSE ? im->k.mu_i : im->k.mu_c)))
			return false;
	return true;
}

// Tries the modes (stick where allowed first, the cloth before the air) and keeps the first that
// is consistent. None (friction beyond any cloth, where Coulomb's law has no solution): all
// sliding, on the cloth unless it would pull.
static void decide_modes(impact *im, const double *y, const choice *ch) {
	const law *k = &im->k;
	modes *m = &im->m;
	double slip[2][2];
	nose_slip(k, y, slip[NOSE]);
	cloth_slip(y, slip[CLOTH]);
	int fallback_air = -1;
	bool cloth_pulls = false; // on the cloth, all sliding, its normal force would be negative
	for (int air = ch->airborne || y[VZ] > 0.0; air < 2 && (air == 0 || ch->airborne || y[VZ] > 0.0 || cloth_pulls);
	     ++air) {
		for (int nose_stick = ch->zero[NOSE] && !ch->slide[NOSE]; nose_stick >= 0; --nose_stick)
			for (int cloth_stick = !air && ch->zero[CLOTH] && !ch->slide[CLOTH]; cloth_stick >= 0; --cloth_stick) {
				m->airborne = air;
				m->nose_stuck = nose_stick;
				m->cloth_stuck = cloth_stick;
				const bool from_zero[2] = {!nose_stick && ch->zero[NOSE], !air && !cloth_stick && ch->zero[CLOTH]};
				for (int i = 0; i < 2; ++i)
					if (!from_zero[i])
						unit_or_keep(slip[i], i == NOSE ? m->nose_dir : m->cloth_dir);
				bool ok = directions_from_zero(im, y, from_zero);
				forces o;
				contact_forces(im, y, &o);
				if (!nose_stick && !cloth_stick && fallback_air < 0 && (air || o.nc >= 0.0))
					fallback_air = air;
				if (!air && !nose_stick && !cloth_stick)
					cloth_pulls = !(o.nc >= 0.0);
				ok = ok && o.ok && (air || o.nc >= 0.0);
				if (nose_stick)
					ok = ok && dot2(o.f, o.f) <= k->mu_i * k->mu_i;
				if (cloth_stick)
					ok = ok && dot2(o.g, o.g) <= k->mu_c * k->mu_c * o.nc * o.nc;
				if (ok)
					return;
			}
	}
	m->airborne = fallback_air == 1 || (fallback_air < 0 && cloth_pulls);
	m->nose_stuck = m->cloth_stuck = false;
	const bool from_zero[2] = {ch->zero[NOSE], !m->airborne && ch->zero[CLOTH]};
	for (int i = 0; i < 2; ++i)
		if (!from_zero[i])
			unit_or_keep(slip[i], i == NOSE ? m->nose_dir : m->cloth_dir);
	directions_from_zero(im, y, from_zero);
}

// ---------------------------------------------------------------- events

typedef enum event {
	EV_NOSE_SLIP_ZERO,
	EV_CLOTH_SLIP_ZERO,
	EV_NOSE_SLIPS,  // a stuck nose's friction leaves its cone
	EV_CLOTH_SLIPS, // a stuck cloth contact's friction leaves its cone
	EV_LIFT_OFF,    // the cloth would have to pull
	EV_LANDING,     // v_z back to zero
	EV_END,         // of compression (ż'_I = 0) or of restitution (W = W_end)
	EV_COUNT
} event;

typedef struct phase {
	bool restitution;
	double work_end; // W at which restitution ends
} phase;

// The event's function: positive before it, zero at it.
static double event_value(const impact *im, const phase *ph, event ev, const double *y) {
	const law *k = &im->k;
	double slip[2];
	forces o;
	switch (ev) {
	case EV_NOSE_SLIP_ZERO:
		nose_slip(k, y, slip);
		return dot2(slip, im->m.nose_dir);
	case EV_CLOTH_SLIP_ZERO:
		cloth_slip(y, slip);
		return dot2(slip, im->m.cloth_dir);
	case EV_NOSE_SLIPS:
		contact_forces(im, y, &o);
		return o.ok ? k->mu_i * k->mu_i - dot2(o.f, o.f) : -1.0;
	case EV_CLOTH_SLIPS:
		contact_forces(im, y, &o);
		return o.ok ? k->mu_c * k->mu_c * o.nc * o.nc - dot2(o.g, o.g) : -1.0;
	case EV_LIFT_OFF:
		contact_forces(im, y, &o);
		return o.ok ? o.nc : -1.0;
	case EV_LANDING:
		return y[VZ];
	case EV_END:
		return ph->restitution ? y[WORK] - ph->work_end : k->c * y[VY] + k->s * y[VZ];
	default:
		return 1.0;
	}
}

static bool event_active(const impact *im, event ev) {
	const modes *m = &im->m;
	switch (ev) {
	case EV_NOSE_SLIP_ZERO: // reached by landing steps, not located
	case EV_CLOTH_SLIP_ZERO:
		return false;
	case EV_NOSE_SLIPS:
		return m->nose_stuck && !m->airborne;
	case EV_CLOTH_SLIPS:
		return m->cloth_stuck && !m->airborne;
	case EV_LIFT_OFF: // n_C = s − c f_y' >= s − c mu: never below zero when that is positive
		return !m->airborne && im->k.s <= im->k.c * im->k.mu_i;
	case EV_LANDING:
		return m->airborne;
	default:
		return true;
	}
}

// The root of the event's function on the step's dense output, between theta 0 (value g0 > 0)
// and 1 (g1 <= 0): the Illinois variant of regula falsi, to the last bits of theta.
static double locate(const impact *im, const phase *ph, event ev, const pool_dopri5_step *st, double g0, double g1) {
	double lo = 0.0, hi = 1.0, glo = g0, ghi = g1, y[DIM];
	const double small = 1e-14 * (g0 > -g1 ? g0 : -g1);
	int side = 0;
	pool_dopri5_linear end = {0.0, 0.0, 0.0, 0.0, 0.0}; // the end's function: linear in the state
	if (ev == EV_END) {
		double w[DIM] = {0.0};
		if (ph->restitution)
			w[WORK] = 1.0;
		else
			w[VY] = im->k.c, w[VZ] = im->k.s;
		end = pool_dopri5_linear_of(st, w);
		if (ph->restitution)
			end.y0 -= ph->work_end;
	}
	for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
		double t = (lo * ghi - hi * glo) / (ghi - glo);
		if (!(t > lo && t < hi))
			t = 0.5 * (lo + hi);
		double g;
		if (ev == EV_END) {
			g = pool_dopri5_linear_at(&end, t);
		} else {
			pool_dopri5_dense(st, t, y);
			g = event_value(im, ph, ev, y);
		}
		if (fabs(g) <= small)
			return t;
		if (g > 0.0) {
			lo = t, glo = g;
			if (side == -1)
				ghi *= 0.5;
			side = -1;
		} else {
			hi = t, ghi = g;
			if (g == 0.0)
				break;
			if (side == 1)
				glo *= 0.5;
			side = 1;
		}
	}
	return hi; // the event has happened there
}

// Applies a tangential impulse J at the nose (x, y') and the cloth's response to it in the
// current modes: its normal impulse holding v_z (−c J_y'), and its friction (sliding: that normal
// impulse's share along the slip; stuck: what keeps its slip).
static void nose_impulse(const impact *im, const double J[2], double *y) {
	const law *k = &im->k;
	const double c = k->c, s = k->s;
	y[VX] += J[0];
	y[VY] -= s * J[1];
	y[VZ] += c * J[1];
	y[UX] += 2.5 * J[1];
	y[UY] += 2.5 * s * J[0];
	y[UZ] -= 2.5 * c * J[0];
	if (im->m.airborne)
		return;
	y[VZ] = 0.0;
	double G[2];
	if (im->m.cloth_stuck) {
		G[0] = -(1.0 - 2.5 * s) * J[0] / 3.5;
		G[1] = -(2.5 - s) * J[1] / 3.5;
	} else {
		G[0] = k->mu_c * c * J[1] * im->m.cloth_dir[0];
		G[1] = k->mu_c * c * J[1] * im->m.cloth_dir[1];
	}
	y[VX] += G[0];
	y[VY] += G[1];
	y[UX] += 2.5 * G[1];
	y[UY] -= 2.5 * G[0];
}

// Applies a tangential impulse G at the cloth and a stuck nose's response (what keeps its slip).
static void cloth_impulse(const impact *im, const double G[2], double *y) {
	const law *k = &im->k;
	const double s = k->s;
	y[VX] += G[0];
	y[VY] += G[1];
	y[UX] += 2.5 * G[1];
	y[UY] -= 2.5 * G[0];
	if (im->m.nose_stuck) {
		const double J[2] = {-(1.0 - 2.5 * s) * G[0] / 3.5, -(2.5 - s) * G[1] / (2.5 + s * s)};
		y[VX] += J[0];
		y[VY] -= s * J[1];
		y[UX] += 2.5 * J[1];
		y[UY] += 2.5 * s * J[0];
		y[UZ] -= 2.5 * k->c * J[0];
	}
}

// Takes a contact's slip to exactly zero by the impulse there that does so with the other
// contact's response in the current modes. Where the slip is a step's small miss of its zero
// (the last of an approach, or the dense output's error at a located crossing), that impulse is
// to first order the friction the integration got wrong: the correction keeps the step's error
// out of the other contact and the velocities.
static void cancel_slip(const impact *im, int contact, double *y) {
	const law *k = &im->k;
	const double c = k->c, s = k->s, a = 1.0 - 2.5 * s, b = 2.5 - s;
	double r[2], J[2];
	if (contact == NOSE) {
		nose_slip(k, y, r);
		if (im->m.airborne) {
			J[0] = -r[0] / 3.5;
			J[1] = -r[1] / 3.5;
		} else if (im->m.cloth_stuck) {
			J[0] = -r[0] / (3.5 - a * a / 3.5);
			J[1] = -r[1] / (2.5 + s * s - b * b / 3.5);
		} else {
			const double *d = im->m.cloth_dir, m = k->mu_c * c;
			const double den = 2.5 + s * s + b * m * d[1];
			J[1] = den > 0.0 ? -r[1] / den : 0.0;
			J[0] = (-r[0] - a * m * d[0] * J[1]) / 3.5;
		}
		nose_impulse(im, J, y);
	} else {
		cloth_slip(y, r);
		if (im->m.nose_stuck && !im->m.airborne) {
			J[0] = -r[0] / (3.5 - a * a / 3.5);
			J[1] = -r[1] / (3.5 - b * b / (2.5 + s * s));
		} else {
			J[0] = -r[0] / 3.5;
			J[1] = -r[1] / 3.5;
		}
		cloth_impulse(im, J, y);
	}
}

// ---------------------------------------------------------------- the impact

static pool_vec3 to_world(pool_vec3 ex, pool_vec3 ey, pool_vec3 ez, double x, double y, double z) {
	return pool_v3_add(pool_v3_add(pool_v3_scale(ex, x), pool_v3_scale(ey, y)), pool_v3_scale(ez, z));
}

// Modes at the start, or after an event at y (`ev` happened; EV_COUNT: the start). A contact
// whose slip counts as zero has it cancelled first.
static void modes_after(impact *im, double *y, event ev) {
	double slip[2];
	choice ch = {{false, false}, {false, false}, ev == EV_LIFT_OFF};
	if (ev == EV_LIFT_OFF || ev == EV_LANDING)
		y[VZ] = 0.0;
	nose_slip(&im->k, y, slip);
	ch.zero[NOSE] = dot2(slip, slip) <= im->zero * im->zero || ev == EV_NOSE_SLIP_ZERO || ev == EV_NOSE_SLIPS;
	if (ch.zero[NOSE])
		cancel_slip(im, NOSE, y);
	cloth_slip(y, slip);
	ch.zero[CLOTH] = dot2(slip, slip) <= im->zero * im->zero || ev == EV_CLOTH_SLIP_ZERO || ev == EV_CLOTH_SLIPS;
	if (ch.zero[CLOTH] && !im->m.airborne)
		cancel_slip(im, CLOTH, y);
	ch.slide[NOSE] = ev == EV_NOSE_SLIPS;
	ch.slide[CLOTH] = ev == EV_CLOTH_SLIPS;
	decide_modes(im, y, &ch);
}

// The impulse after which a sliding contact's slip reaches zero at its present rate (its slip
// `slip`, rate `rate`); INFINITY when it is not closing.
static double closing_distance(const double slip[2], const double rate[2], double zero) {
	const double s2 = dot2(slip, slip), closing = -dot2(slip, rate);
	return s2 > zero * zero && closing > 0.0 ? s2 / closing : INFINITY;
}

// The slip of contact i at y, and its rate in p from the slope dy (in p).
static void slip_and_rate(const impact *im, int i, const double *y, const double *dy, double sl[2], double rate[2]) {
	if (i == NOSE) {
		nose_slip(&im->k, y, sl);
		nose_slip(&im->k, dy, rate);
	} else {
		cloth_slip(y, sl);
		cloth_slip(dy, rate);
	}
}

static bool sliding(const modes *m, int i) { return i == NOSE ? !m->nose_stuck : !m->airborne && !m->cloth_stuck; }

// The landing of sliding contact i on zero slip (its slip s, closing): with every sliding
// direction held, the system's slope is constant, and its slip's rate is affine in i's direction
// d, rate(d) = a + B d; the d for which that rate points straight back at zero, a + B d = −lambda
// s/|s| with |d| = 1, lambda > 0 (a quadratic in lambda), lands the slip on zero after the
// impulse |s| / lambda. That held direction is the mean of the turning one over the rest of the
// approach, to the second order in its turn. Sets i's direction to d and returns the impulse
// (INFINITY: none), the slope in k.
static double landing(impact *im, const double *y, int i, const double s[2], double *k) {
	double *dir = i == NOSE ? im->m.nose_dir : im->m.cloth_dir;
	double sl[2], a[2], B[2][2];
	im->frozen = 3u;
	dir[0] = dir[1] = 0.0;
	derivative(im, y, k);
	slip_and_rate(im, i, y, k, sl, a);
	for (int j = 0; j < 2; ++j) {
		double r[2];
		dir[0] = j == 0, dir[1] = j == 1;
		derivative(im, y, k);
		slip_and_rate(im, i, y, k, sl, r);
		B[0][j] = r[0] - a[0];
		B[1][j] = r[1] - a[1];
	}
	const double det = B[0][0] * B[1][1] - B[0][1] * B[1][0], n = sqrt(dot2(s, s));
	const double u[2] = {(B[1][1] * a[0] - B[0][1] * a[1]) / det, (B[0][0] * a[1] - B[1][0] * a[0]) / det};
	const double w[2] = {(B[1][1] * s[0] - B[0][1] * s[1]) / (det * n), (B[0][0] * s[1] - B[1][0] * s[0]) / (det * n)};
	const double ww = dot2(w, w), uw = dot2(u, w), disc = uw * uw - ww * (dot2(u, u) - 1.0);
	const double lambda = ww > 0.0 && disc >= 0.0 ? (-uw + sqrt(disc)) / ww : -1.0;
	dir[0] = -(u[0] + lambda * w[0]);
	dir[1] = -(u[1] + lambda * w[1]);
	derivative(im, y, k);
	im->frozen = 0u;
	return det != 0.0 && lambda > 0.0 && dot2(dir, s) > 0.0 ? n / lambda : INFINITY;
}

// Both contacts slide on the cloth, neither slip is zero, and the cloth still presses: the modes
// decide_modes takes first (the main loop turns each sliding direction to its slip every step).
static bool still_sliding(const impact *im, const double *y) {
	const modes *m = &im->m;
	if (m->airborne || m->nose_stuck || m->cloth_stuck || y[VZ] > 0.0) // (rising: decide_modes lifts it)
		return false;
	double si[2], sc[2];
	nose_slip(&im->k, y, si);
	cloth_slip(y, sc);
	const double ni = dot2(si, si), z2 = im->zero * im->zero;
	return ni > z2 && dot2(sc, sc) > z2 && im->k.s + im->k.c * im->k.mu_i * si[1] / sqrt(ni) >= 0.0;
}

// At the end of compression (ż'_I = 0): restitution starts, to give back e² of the work; a slip
// reaching zero there too (a stuck nose makes the cloth's slip (1 + s) v_y in a head-on impact)
// is decided. True at the end of restitution (the impact is over).
static bool end_of_phase(impact *im, phase *ph, double *y, double e) {
	if (ph->restitution)
		return true;
	y[VY] = -im->k.s * y[VZ] / im->k.c;
	ph->restitution = true;
	ph->work_end = (1.0 - e * e) * y[WORK];
	if (!(y[WORK] > ph->work_end))
		return true; // e = 0: nothing given back
	if (!still_sliding(im, y)) // (else Coulomb's law decides what it decided before)
		modes_after(im, y, EV_COUNT);
	return false;
}

pool_mathavan_outcome pool_cushion_mathavan(pool_ball_state *st, const pool_params *p, pool_vec3 n,
                                            double tolerance) {
	const pool_vec3 nh = pool_v3_xy(n);
	const double c = pool_v3_len(nh);
	if (!(c > 0.0) || !(tolerance > 0.0))
		return POOL_MATHAVAN_SEPARATING; // a normal straight down: not a rail impact
	const pool_vec3 ey = pool_v3_scale(nh, -1.0 / c), ez = pool_v3(0.0, 0.0, 1.0);
	const pool_vec3 ex = pool_v3_cross(ey, ez);
	const double R = p->ball_radius;
	double y[DIM] = {0.0};
	y[VX] = pool_v3_dot(st->vel, ex), y[VY] = pool_v3_dot(st->vel, ey), y[VZ] = pool_v3_dot(st->vel, ez);
	y[UX] = R * pool_v3_dot(st->omega, ex), y[UY] = R * pool_v3_dot(st->omega, ey);
	y[UZ] = R * pool_v3_dot(st->omega, ez);
	impact im = {{c, -n.z, p->mu_cushion_mathavan, p->mu_table}, {0}, 0.0, 0};
	const double z0 = im.k.c * y[VY] + im.k.s * y[VZ];
	if (!(z0 > 0.0))
		return POOL_MATHAVAN_SEPARATING;
	if (y[VZ] < 0.0)
		y[VZ] = 0.0; // a ball on the cloth does not move into it
	double scale = 0.0; // the speed scale: errors and zero slips are measured against it
	for (int i = 0; i < DIM; ++i)
		if (i != WORK && i != PAD)
			scale = fmax(scale, fabs(y[i]));
	im.zero = ZERO_SLIP * scale;
	double inv_atol[DIM]; // the error's weights: 1 / (tolerance times each component's scale)
	for (int i = 0; i < DIM; ++i)
		inv_atol[i] = i == PAD ? 0.0 : 1.0 / (tolerance * scale * (i == WORK ? z0 : 1.0));
	const double e = p->e_cushion_mathavan, frictionless = (1.0 + e) * z0 / (c * c);
	if (!still_sliding(&im, y)) // (else the modes all-sliding start with, as decide_modes would)
		modes_after(&im, y, EV_COUNT);
	phase ph = {false, 0.0};
	// The first step: about what the control settles on for smooth impacts.
	double h = FIRST_STEP * exp2_approx(0.2 * log2_approx(tolerance)) * frictionless;
	double k1[DIM], log_err_last = log2_approx(1e-4), pp = 0.0; // pp: the impulse so far
	double h_accepted = 0.0, log_err_accepted = 0.0; // the last accepted step (0: none yet)
	bool rejected = false;
	derivative(&im, y, k1);
	pool_dopri5_step step;
	for (int tries = 0;; ++tries) {
		if (tries == MAX_TRIES)
			return POOL_MATHAVAN_JAMMED;
		if (!(event_value(&im, &ph, EV_END, y) > 0.0)) { // a step (a landing) ended on the phase's end
			if (end_of_phase(&im, &ph, y, e))
				break;
			derivative(&im, y, k1);
			continue;
		}
		// Sliding contacts oppose their slip. One that would reach zero slip within the step (at
		// its present rate) is landed there: the step is cut to end where the slip, along the
		// direction held that brings it to zero (landing), reaches it; near there, the direction
		// is held (the slip's own is lost in the step's error). Its small miss is cancelled.
		double hs = h;
		int lands = -1;
		im.m.nose_small = im.m.cloth_small = im.zero;
		for (int i = 0; i < 2; ++i) {
			if (!sliding(&im.m, i))
				continue;
			double sl[2], rate[2], kl[DIM];
			slip_and_rate(&im, i, y, k1, sl, rate);
			if (dot2(sl, sl) <= im.zero * im.zero)
				continue;
			double *dir = i == NOSE ? im.m.nose_dir : im.m.cloth_dir;
			unit_or_keep(sl, dir);
			const double reach = closing_distance(sl, rate, im.zero);
			if (!(reach < hs))
				continue;
			const double keep[2] = {dir[0], dir[1]};
			if (i == NOSE && sliding(&im.m, CLOTH)) { // the landing holds the cloth's direction at y
				double sc[2];
				cloth_slip(y, sc);
				if (dot2(sc, sc) > im.zero * im.zero)
					unit_or_keep(sc, im.m.cloth_dir);
			}
			const double d = landing(&im, y, i, sl, kl);
			if (d < hs) {
				hs = d;
				lands = i;
				*(i == NOSE ? &im.m.nose_small : &im.m.cloth_small) = LAND_HOLD * sqrt(dot2(sl, sl));
			} else {
				dir[0] = keep[0], dir[1] = keep[1];
			}
		}
		// A sliding contact whose slip the step would turn over many times (its friction's turn
		// rate, about 7/2 mu N / |slip|, times the step above QUASI) follows its slow manifold: the
		// friction that would hold it, cut to its cone (the direction its slip turns to at once).
		im.m.nose_quasi = im.m.cloth_quasi = false;
		double sln[2], slc[2];
		nose_slip(&im.k, y, sln);
		cloth_slip(y, slc);
		const double reach_n = 3.5 * im.k.mu_i * hs / QUASI;
		const double reach_c = 3.5 * im.k.mu_c * (im.k.s + im.k.c * im.k.mu_i) * hs / QUASI;
		if ((lands != NOSE && sliding(&im.m, NOSE) && dot2(sln, sln) < reach_n * reach_n) ||
		    (lands != CLOTH && sliding(&im.m, CLOTH) && dot2(slc, slc) < reach_c * reach_c)) {
			forces o, held;
			contact_forces(&im, y, &o);
			double sl[2], dn[2], dc[2];
			nose_slip(&im.k, y, sl);
			if (lands != NOSE && sliding(&im.m, NOSE) && dot2(sl, sl) * QUASI * QUASI < sq(3.5 * im.k.mu_i * hs)) {
				dn[0] = -o.f[0] / im.k.mu_i, dn[1] = -o.f[1] / im.k.mu_i;
				dc[0] = -o.g[0], dc[1] = -o.g[1];
				unit_or_keep(dc, dc);
				forces_for(&im, true, im.m.cloth_stuck || im.m.airborne, dn, dc, &held);
				im.m.nose_quasi = held.ok && dot2(held.f, held.f) < sq(MARGINAL * im.k.mu_i);
			}
			cloth_slip(y, sl);
			if (lands != CLOTH && sliding(&im.m, CLOTH) && dot2(sl, sl) * QUASI * QUASI < sq(3.5 * im.k.mu_c * o.nc * hs)) {
				dn[0] = -o.f[0] / im.k.mu_i, dn[1] = -o.f[1] / im.k.mu_i;
				forces_for(&im, im.m.nose_stuck, true, dn, dn, &held);
				im.m.cloth_quasi = held.ok && dot2(held.g, held.g) < sq(MARGINAL * im.k.mu_c * held.nc);
			}
			if (im.m.nose_quasi || im.m.cloth_quasi)
				derivative(&im, y, k1);
		}
		if (im.m.airborne)
			pool_dopri5_take(derivative, &im, y, k1, hs, &step);
		else // v_z stays zero
			pool_dopri5_take_lead(both_sliding(&im) ? derivative_sliding : derivative, &im, y, k1, hs, &step);
		double err = 0.0;
		for (int i = 0; i < DIM; ++i) {
			const double e_i = fabs(step.err[i]) * inv_atol[i];
			err = at_least(e_i, err);
		}
		// Step control (Hairer's for DOPRI5: the error's trend from the last accepted step
		// damps the growth; no growth right after a rejection).
		const double log_err = log2_approx(at_least(err, 1e-10));
		const double grow = at_most(at_least(0.9 * exp2_approx(-0.17 * log_err + 0.04 * log_err_last), 0.1), 5.0);
		if (err > 1.0 && hs > 1e-12 * frictionless) {
			h = hs * at_most(grow, 1.0);
			rejected = true;
			continue;
		}
		log_err_last = log2_approx(at_least(err, 1e-4));
		// The earliest event inside the step.
		event first = EV_COUNT;
		double theta = 2.0;
		for (int ev = 0; ev < EV_COUNT; ++ev) {
			if (!event_active(&im, (event)ev))
				continue;
			const double g0 = event_value(&im, &ph, (event)ev, y), g1 = event_value(&im, &ph, (event)ev, step.y1);
			const bool crossed = ev == EV_LANDING ? g0 >= 0.0 && g1 < 0.0 : g0 > 0.0 && g1 <= 0.0;
			if (!crossed)
				continue;
			const double t = locate(&im, &ph, (event)ev, &step, g0, g1);
			if (t < theta)
				theta = t, first = (event)ev;
		}
		if (first == EV_COUNT && lands >= 0) { // landed: the slip is zero
			h_accepted = 0.0;
			for (int i = 0; i < DIM; ++i)
				y[i] = step.y1[i];
			im.m.nose_small = im.m.cloth_small = im.zero;
			pp += hs;
			modes_after(&im, y, lands == NOSE ? EV_NOSE_SLIP_ZERO : EV_CLOTH_SLIP_ZERO);
			derivative(&im, y, k1);
			continue;
		}
		if (first == EV_COUNT) {
			for (int i = 0; i < DIM; ++i) {
				y[i] = step.y1[i];
				k1[i] = step.k[6][i];
			}
			if (hs == h) {
				double next = rejected ? at_most(grow, 1.0) : grow;
				if (h_accepted > 0.0) // Gustafsson's predictive control (see PREDICTIVE)
					next = at_most(next, at_least(hs / h_accepted * 0.9 *
					                                      exp2_approx(PREDICTIVE * (log_err_accepted - 2.0 * log_err)),
					                              0.1));
				h = hs * next;
			}
			h_accepted = hs;
			log_err_accepted = log_err_last;
			rejected = false;
			pp += hs;
			if (!ph.restitution && pp > JAM_IMPULSES * frictionless)
				return POOL_MATHAVAN_JAMMED;
			continue;
		}
		pool_dopri5_dense(&step, theta, y);
		pp += theta * hs;
		h_accepted = 0.0;
		if (first == EV_END) {
			if (end_of_phase(&im, &ph, y, e))
				break;
		} else {
			modes_after(&im, y, first);
		}
		derivative(&im, y, k1);
	}
	st->vel = to_world(ex, ey, ez, y[VX], y[VY], y[VZ]);
	st->omega = pool_v3_scale(to_world(ex, ey, ez, y[UX], y[UY], y[UZ]), 1.0 / R);
	return POOL_MATHAVAN_RESOLVED;
}

bool pool_cushion_mathavan_resolve(const pool_sim_def *def, pool_ball_state *s, pool_vec3 n) {
	if (def->models.cushion != POOL_CUSHION_MATHAVAN2010 || s->motion == POOL_MOTION_AIRBORNE ||
	    fabs(s->pos.z - def->params.ball_radius) > POOL_TOUCH_TOLERANCE)
		return false;
	return pool_cushion_mathavan(s, &def->params, n, POOL_MATHAVAN_TOLERANCE) != POOL_MATHAVAN_JAMMED;
}
