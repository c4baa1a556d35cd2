// Mathavan, Jackson & Parkin (2010) cushion impact, integrated over the nose's normal impulse.
//
// Frame of the impact: y towards the cushion (horizontal), z up, x = y × z along the rail. The
// nose touches the ball at r_I = R (0, c, s) from its centre (c = cos θ, s = sin θ; sin θ = 2/5 at
// the paper's h = 7R/5, here taken from the actual normal), the cloth at r_C = (0, 0, −R).
// Units: velocities v, the surface speeds u = R ω, and impulses per unit mass, so the equations
// hold neither mass nor radius. Per impulse step dp at the nose (the paper's equations (12)-(17),
// derived again in vector form):
//   1. the normal impulse dp along −(0, c, s): v_y −= c dp, v_z −= s dp;
//   2. friction f at the nose, in its tangent plane (x, y' = (0, −s, c)), against its slip
//      s_I = (v_x + s u_y − c u_z, −s v_y + c v_z + u_x), |f| <= mu_cushion_mathavan dp;
//   3. the cloth's normal impulse: whatever brings v_z back to 0 (the ball stays on the cloth),
//      never pulling;
//   4. friction g at the cloth against its slip s_C = (v_x − u_y, v_y + u_x), |g| <= mu_table
//      times the cloth's normal impulse.
// A tangential impulse at either contact changes that contact's slip by 7/2 of itself, so a
// contact whose slip friction can cancel within the step's bound sticks exactly (f = −s / 7/2):
// Coulomb's stick-slip without the chatter of a fixed direction. Sliding friction acts along the
// slip extrapolated to the middle of the step from the last two steps: second order while the
// contacts slide. A step where a contact changes between sticking and sliding is taken again in
// POOL_MATHAVAN_SUBSTEPS substeps: the scheme's error there is of the first order in the step.
// Compression lasts while the nose's normal velocity ż'_I = c v_y + s v_z is positive; the work of
// the normal force W_c = ∫ ż'_I dp (trapezoid, the paper's (16a)) is given back e² of it in
// restitution (Stronge). The last step of each phase is cut to land on its end: linear in dp for
// ż'_I = 0, the quadratic of the work for e² W_c.
//
// The state lives in locals of one loop and a step costs about 2 square roots and 2 divisions per
// sliding contact: pool-bench-models measures it.
#include "cushion_mathavan.h"

#include <math.h>

#include "vec3.h"

enum { VX, VY, VZ, UX, UY, UZ, DIM };

typedef struct law {
	double c, s, mu_i, mu_c;
} law;

// The state and the contacts' slips at the start of the previous step (for the extrapolation).
typedef struct impact {
	double y[DIM];
	double prev_i[2], prev_c[2];
	int has_prev;
	unsigned stuck; // bit 0: the nose stuck in the last step, bit 1: the cloth
} impact;

static double approach(const law *k, const double *y) { return k->c * y[VY] + k->s * y[VZ]; }

// Coulomb friction on a contact's slip over a step: the impulse that cancels the slip if within
// `bound` (sticking: returns 1), else `bound` against `dir` (sliding along the slip at the middle
// of the step), or against the slip itself when dir is zero. Output f.
static unsigned friction(const double slip[2], const double dir[2], double bound, double f[2]) {
	const double s2 = slip[0] * slip[0] + slip[1] * slip[1];
	if (s2 <= (3.5 * bound) * (3.5 * bound)) {
		f[0] = -slip[0] / 3.5;
		f[1] = -slip[1] / 3.5;
		return 1u;
	}
	const double d2 = dir[0] * dir[0] + dir[1] * dir[1];
	const double *along = d2 > 0.0 ? dir : slip;
	const double g = bound / sqrt(d2 > 0.0 ? d2 : s2);
	f[0] = -g * along[0];
	f[1] = -g * along[1];
	return 0u;
}

// One step of impulse h from `from` into `to`. Returns which contacts stuck.
static unsigned advance(const law *k, const impact *from, impact *to, double h) {
	const double c = k->c, s = k->s;
	const double *y0 = from->y;
	double now_i[2] = {y0[VX] + s * y0[UY] - c * y0[UZ], -s * y0[VY] + c * y0[VZ] + y0[UX]};
	double now_c[2] = {y0[VX] - y0[UY], y0[VY] + y0[UX]};
	double mid_i[2] = {0.0, 0.0}, mid_c[2] = {0.0, 0.0}, f[2];
	if (from->has_prev)
		for (int j = 0; j < 2; ++j) {
			mid_i[j] = 1.5 * now_i[j] - 0.5 * from->prev_i[j];
			mid_c[j] = 1.5 * now_c[j] - 0.5 * from->prev_c[j];
		}
	double *y = to->y;
	for (int j = 0; j < DIM; ++j)
		y[j] = y0[j];
	// 1. the normal impulse at the nose (along r_I: no torque, the nose's slip unchanged)
	y[VY] -= c * h;
	y[VZ] -= s * h;
	// 2. friction at the nose
	unsigned stuck = friction(now_i, mid_i, k->mu_i * h, f);
	y[VX] += f[0];
	y[VY] -= s * f[1];
	y[VZ] += c * f[1];
	y[UX] += 2.5 * f[1];
	y[UY] += 2.5 * s * f[0];
	y[UZ] -= 2.5 * c * f[0];
	// 3. the cloth holds the ball on it
	const double n_c = y[VZ] < 0.0 ? -y[VZ] : 0.0;
	y[VZ] += n_c;
	// 4. friction at the cloth
	const double slip_c[2] = {y[VX] - y[UY], y[VY] + y[UX]};
	stuck |= friction(slip_c, mid_c, k->mu_c * n_c, f) << 1;
	y[VX] += f[0];
	y[VY] += f[1];
	y[UX] += 2.5 * f[1];
	y[UY] -= 2.5 * f[0];
	for (int j = 0; j < 2; ++j) {
		to->prev_i[j] = now_i[j];
		to->prev_c[j] = now_c[j];
	}
	to->has_prev = 1;
	to->stuck = stuck;
	return stuck;
}

// A step of impulse h; one where a contact changes between sticking and sliding (against the
// step before) is taken again in POOL_MATHAVAN_SUBSTEPS substeps.
static void step(const law *k, const impact *from, impact *to, double h) {
	const unsigned stuck = advance(k, from, to, h);
	if (!from->has_prev || stuck == from->stuck)
		return;
	impact sub = *from;
	for (int i = 0; i < POOL_MATHAVAN_SUBSTEPS; ++i) {
		advance(k, &sub, to, h / POOL_MATHAVAN_SUBSTEPS);
		sub = *to;
	}
}

static pool_vec3 to_world(pool_vec3 ex, pool_vec3 ey, pool_vec3 ez, double x, double y, double z) {
	return pool_v3_add(pool_v3_add(pool_v3_scale(ex, x), pool_v3_scale(ey, y)), pool_v3_scale(ez, z));
}

pool_mathavan_outcome pool_cushion_mathavan(pool_ball_state *st, const pool_params *p, pool_vec3 n, int steps) {
	const pool_vec3 nh = pool_v3_xy(n);
	const double c = pool_v3_len(nh);
	if (!(c > 0.0) || steps < 1)
		return POOL_MATHAVAN_SEPARATING; // a normal straight down: not a rail impact
	const pool_vec3 ey = pool_v3_scale(nh, -1.0 / c), ez = pool_v3(0.0, 0.0, 1.0);
	const pool_vec3 ex = pool_v3_cross(ey, ez);
	const double R = p->ball_radius;
	const law k = {c, -n.z, p->mu_cushion_mathavan, p->mu_table};
	impact it = {{pool_v3_dot(st->vel, ex), pool_v3_dot(st->vel, ey), pool_v3_dot(st->vel, ez),
	              R * pool_v3_dot(st->omega, ex), R * pool_v3_dot(st->omega, ey), R * pool_v3_dot(st->omega, ez)},
	             {0.0, 0.0},
	             {0.0, 0.0},
	             0,
	             0u};
	const double z0 = approach(&k, it.y);
	if (!(z0 > 0.0))
		return POOL_MATHAVAN_SEPARATING;
	const double e = p->e_cushion_mathavan;
	// The impulse of a frictionless impact, (1 + e) ż'_0 / cos² θ (the cloth takes the vertical
	// part), split into `steps`; friction changes the real total by some per cent.
	const double dp = (1.0 + e) * z0 / (c * c) / steps;
	const int max_steps = 8 * steps; // beyond: jammed (friction stopping the approach's decrease)
	double work = 0.0;               // ∫ ż'_I dp of the compression
	impact next;
	for (int i = 0; i == 0 || approach(&k, it.y) > 0.0; ++i) {
		if (i == max_steps)
			return POOL_MATHAVAN_JAMMED;
		const double z = approach(&k, it.y);
		step(&k, &it, &next, dp);
		double z1 = approach(&k, next.y), h = dp;
		if (z1 < 0.0) { // compression ends inside this step: cut it where ż'_I reaches 0
			h = dp * z / (z - z1);
			step(&k, &it, &next, h);
			z1 = 0.0; // linear in the step's impulse: 0 up to rounding, and compression is over
			next.y[VY] -= approach(&k, next.y) / c;
		}
		work += 0.5 * h * (z + z1);
		it = next;
	}
	// Restitution: the normal force gives back e² of the compression's work.
	double remaining = e * e * work;
	for (int j = 0; remaining > 0.0 && j < max_steps; ++j) {
		const double z = approach(&k, it.y); // <= 0: leaving
		step(&k, &it, &next, dp);
		const double z1 = approach(&k, next.y);
		const double given = -0.5 * dp * (z + z1);
		if (given >= remaining) {
			// ż'_I is linear in the step's impulse h: ż' = z + q h with q = (z1 − z)/dp, and the work
			// given back, −(z h + q h²/2), reaches `remaining` at the root below.
			const double q = (z1 - z) / dp;
			const double h = q < 0.0 ? (z + sqrt(fmax(z * z - 2.0 * q * remaining, 0.0))) / -q : dp;
			step(&k, &it, &next, fmin(h, dp));
			it = next;
			break;
		}
		remaining -= given;
		it = next;
	}
	st->vel = to_world(ex, ey, ez, it.y[VX], it.y[VY], it.y[VZ]);
	st->omega = pool_v3_scale(to_world(ex, ey, ez, it.y[UX], it.y[UY], it.y[UZ]), 1.0 / R);
	return POOL_MATHAVAN_RESOLVED;
}

bool pool_cushion_mathavan_resolve(const pool_sim_def *def, pool_ball_state *s, pool_vec3 n) {
	if (def->models.cushion != POOL_CUSHION_MATHAVAN2010 || s->motion == POOL_MOTION_AIRBORNE ||
	    fabs(s->pos.z - def->params.ball_radius) > POOL_TOUCH_TOLERANCE)
		return false;
	return pool_cushion_mathavan(s, &def->params, n, POOL_MATHAVAN_STEPS) != POOL_MATHAVAN_JAMMED;
}
