// The reference for libpool's mathavan2010 cushion (cushion_mathavan.c): the same equations integrated
// in fixed impulse steps, as libpool did before its adaptive integration (128 steps then). Used by
// pool-bench-models --accuracy and test_model_fidelity at many more steps. What follows is that scheme.
//
// Mathavan, Jackson & Parkin (2010) cushion impact, integrated over the normal impulse.
//
// Frame of the impact: y towards the cushion (horizontal), z up, x = y × z along the rail. The
// nose touches the ball at r_I = R (0, cos θ, sin θ) from its centre (sin θ = 2/5 at the paper's
// h = 7R/5; here taken from the actual normal), the cloth at r_C = (0, 0, −R). Per impulse step
// dP at I (the paper's equations (12)-(17), derived again in vector form):
//   1. the normal impulse dP along −(0, cos θ, sin θ);
//   2. friction at I, in the tangent plane (x, y' = (0, −sin θ, cos θ)), opposing the slip
//      s_I = (v_x + R(ω_y sin θ − ω_z cos θ), −v_y sin θ + v_z cos θ + R ω_x), at most
//      mu_cushion_mathavan dP;
//   3. the cloth's normal impulse dP_C: whatever brings v_z back to 0 (the ball stays on the
//      cloth), never pulling (dP_C >= 0);
//   4. friction at C opposing s_C = (v_x − R ω_y, v_y + R ω_x), at most mu_table dP_C.
// A tangential impulse f at either contact changes that contact's slip by (7/2) f / M (both
// tangent directions are perpendicular to r), so a contact whose slip friction can cancel within
// the step's bound sticks exactly (f = −(2M/7) s): the stick-slip transitions of Coulomb's law
// without the chatter of a fixed-direction step. Sliding friction acts along the slip
// extrapolated to the middle of the step from the last two steps (second order while the
// contacts slide); stick-slip transitions inside a step are first order: so the
// scheme converges to the equations as the steps grow, to the first order where a contact sticks
// or starts to slide (pool-bench-models --accuracy measures it against itself at twice the steps).
// Compression lasts while the nose's normal velocity ż'_I = v_y cos θ + v_z sin θ is positive,
// accumulating the normal force's work W_c = ∫ ż'_I dP (trapezoid, the paper's (16a)); restitution
// then runs until the work given back reaches e² W_c (Stronge). The last step of each phase is
// cut to land on its end: linear in dP for ż'_I = 0, the quadratic of the work for e² W_c.
#include "mathavan_reference.h"

#include <math.h>
#include <string.h>

#include "vec3.h"

typedef struct impact {
	double vx, vy, vz, wx, wy, wz; // impact frame
} impact;

typedef struct contact_law {
	double M, R, c, s, mu_i, mu_c;
	double inv_M;     // 1 / M
	double spin_gain; // 5 / (2 M R): angular velocity change per unit tangential impulse and R
} contact_law;

// ż'_I, the approach speed of the ball at the nose along its normal.
static double approach(const contact_law *k, const impact *b) { return b->vy * k->c + b->vz * k->s; }

// The slips of the nose contact (x, y') and of the cloth contact (x, y).
static void slip_at_nose(const contact_law *k, const impact *b, double out[2]) {
	out[0] = b->vx + k->R * (b->wy * k->s - b->wz * k->c);
	out[1] = -b->vy * k->s + b->vz * k->c + k->R * b->wx;
}
static void slip_at_cloth(const contact_law *k, const impact *b, double out[2]) {
	out[0] = b->vx - k->R * b->wy;
	out[1] = b->vy + k->R * b->wx;
}

// Coulomb friction on a contact's slip: the impulse that cancels it if within `bound` (sticking),
// else `bound` against `dir`, the slip at the middle of the step (sliding). Output: f[2].
static void friction(const double slip[2], const double dir[2], double M, double bound, double f[2]) {
	const double stick = 2.0 * M / 7.0; // impulse per unit slip that stops the slip
	const double s2 = slip[0] * slip[0] + slip[1] * slip[1];
	if (s2 * stick * stick <= bound * bound) {
		f[0] = -stick * slip[0];
		f[1] = -stick * slip[1];
		return;
	}
	const double d = sqrt(dir[0] * dir[0] + dir[1] * dir[1]);
	const double g = d > 0.0 ? bound / d : bound / sqrt(s2);
	f[0] = -g * (d > 0.0 ? dir[0] : slip[0]);
	f[1] = -g * (d > 0.0 ? dir[1] : slip[1]);
}

// One impulse step dP; mid_i / mid_c: the slips the sliding contacts are opposed along (NULL:
// the slips at the start of the step).
// nose_slip: the slip at the nose at the start of the step (the normal impulse leaves it as it is).
static void step(const contact_law *k, impact *b, double dP, const double nose_slip[2], const double *mid_i,
                 const double *mid_c) {
	const double c = k->c, s = k->s, iM = k->inv_M, g = k->spin_gain;
	double slip[2] = {nose_slip[0], nose_slip[1]}, f[2];
	// 1. normal impulse at the nose (no torque: along r_I)
	b->vy -= c * dP * iM;
	b->vz -= s * dP * iM;
	// 2. friction at the nose
	friction(slip, mid_i ? mid_i : slip, k->M, k->mu_i * dP, f);
	b->vx += f[0] * iM;
	b->vy -= f[1] * s * iM;
	b->vz += f[1] * c * iM;
	b->wx += g * f[1];
	b->wy += g * s * f[0];
	b->wz -= g * c * f[0];
	// 3. the cloth holds the ball on it
	const double dPC = b->vz < 0.0 ? -k->M * b->vz : 0.0;
	b->vz = b->vz < 0.0 ? 0.0 : b->vz;
	// 4. friction at the cloth
	slip_at_cloth(k, b, slip);
	friction(slip, mid_c ? mid_c : slip, k->M, k->mu_c * dPC, f);
	b->vx += f[0] * iM;
	b->vy += f[1] * iM;
	b->wx += g * f[1];
	b->wy -= g * f[0];
}

// The impact as integrated: the state and the contacts' slips at the start of the previous
// step, from which the slips at the middle of the next one are extrapolated (the sliding
// friction then acts along them: second order where the contacts slide, at no extra cost).
typedef struct integration {
	impact b;
	double prev_i[2], prev_c[2];
	int has_prev;
} integration;

// Advances `from` by dP into `to` (from unchanged, so a step can be redone shorter).
static void advance(const contact_law *k, const integration *from, integration *to, double dP) {
	double now_i[2], now_c[2], mid_i[2], mid_c[2];
	slip_at_nose(k, &from->b, now_i);
	slip_at_cloth(k, &from->b, now_c);
	for (int j = 0; j < 2; ++j) {
		mid_i[j] = from->has_prev ? 1.5 * now_i[j] - 0.5 * from->prev_i[j] : now_i[j];
		mid_c[j] = from->has_prev ? 1.5 * now_c[j] - 0.5 * from->prev_c[j] : now_c[j];
	}
	*to = *from;
	step(k, &to->b, dP, now_i, from->has_prev ? mid_i : NULL, from->has_prev ? mid_c : NULL);
	for (int j = 0; j < 2; ++j) {
		to->prev_i[j] = now_i[j];
		to->prev_c[j] = now_c[j];
	}
	to->has_prev = 1;
}

static pool_vec3 to_world(pool_vec3 ex, pool_vec3 ey, pool_vec3 ez, double x, double y, double z) {
	return pool_v3_add(pool_v3_add(pool_v3_scale(ex, x), pool_v3_scale(ey, y)), pool_v3_scale(ez, z));
}

pool_mathavan_outcome pool_mathavan_reference(pool_ball_state *st, const pool_params *p, pool_vec3 n, int steps) {
	const pool_vec3 nh = pool_v3_xy(n);
	const double c = pool_v3_len(nh);
	if (!(c > 0.0) || steps < 1)
		return POOL_MATHAVAN_SEPARATING; // a normal straight down: not a rail impact
	const pool_vec3 ey = pool_v3_scale(nh, -1.0 / c), ez = pool_v3(0.0, 0.0, 1.0);
	const pool_vec3 ex = pool_v3_cross(ey, ez);
	const contact_law k = {p->ball_mass, p->ball_radius, c, -n.z, p->mu_cushion_mathavan, p->mu_table,
	                       1.0 / p->ball_mass, 5.0 / (2.0 * p->ball_mass * p->ball_radius)};
	integration it = {{pool_v3_dot(st->vel, ex), pool_v3_dot(st->vel, ey), pool_v3_dot(st->vel, ez),
	                   pool_v3_dot(st->omega, ex), pool_v3_dot(st->omega, ey), pool_v3_dot(st->omega, ez)},
	                  {0.0, 0.0}, {0.0, 0.0}, 0};
	const double z0 = approach(&k, &it.b);
	if (!(z0 > 0.0))
		return POOL_MATHAVAN_SEPARATING;
	const double e = p->e_cushion_mathavan;
	// The impulse of a frictionless impact, (1 + e) M ż'_0 / cos² θ (the cloth takes the vertical
	// part), split into `steps`; friction changes the real total by some per cent.
	const double dP = (1.0 + e) * k.M * z0 / (c * c) / steps;
	const int max_steps = 8 * steps; // beyond: jammed (friction stopping the approach's decrease)
	double work = 0.0;               // ∫ ż'_I dP of the compression
	integration next;
	for (int i = 0; i == 0 || approach(&k, &it.b) > 0.0; ++i) {
		if (i == max_steps)
			return POOL_MATHAVAN_JAMMED;
		const double z = approach(&k, &it.b);
		advance(&k, &it, &next, dP);
		double z1 = approach(&k, &next.b), h = dP;
		if (z1 < 0.0) { // compression ends inside this step: cut it where ż'_I reaches 0
			h = dP * z / (z - z1);
			advance(&k, &it, &next, h);
			z1 = 0.0; // linear in the step's impulse: 0 up to rounding, and compression is over
			next.b.vy -= approach(&k, &next.b) / k.c;
		}
		work += 0.5 * h * (z + z1);
		it = next;
	}
	// Restitution: the normal force gives back e² of the compression's work.
	double remaining = e * e * work;
	for (int j = 0; remaining > 0.0 && j < max_steps; ++j) {
		const double z = approach(&k, &it.b); // <= 0: leaving
		advance(&k, &it, &next, dP);
		const double z1 = approach(&k, &next.b);
		const double given = -0.5 * dP * (z + z1);
		if (given >= remaining) {
			// ż'_I is linear in the step's impulse h: ż' = z + q h with q = (z1 − z)/dP, and the work
			// given back, −(z h + q h²/2), reaches `remaining` at the root below.
			const double q = (z1 - z) / dP;
			const double h = q < 0.0 ? (z + sqrt(fmax(z * z - 2.0 * q * remaining, 0.0))) / -q : dP;
			advance(&k, &it, &next, fmin(h, dP));
			it = next;
			break;
		}
		remaining -= given;
		it = next;
	}
	st->vel = to_world(ex, ey, ez, it.b.vx, it.b.vy, it.b.vz);
	st->omega = to_world(ex, ey, ez, it.b.wx, it.b.wy, it.b.wz);
	return POOL_MATHAVAN_RESOLVED;
}

pool_ball_state pool_mathavan_random_impact(uint64_t *seed, double R) {
	double u[5]; // five draws an impact (the last unused), as test_model_fidelity has always drawn
	for (int k = 0; k < 5; ++k) { // xorshift64; 53 bits to [0, 1)
		*seed ^= *seed << 13;
		*seed ^= *seed >> 7;
		*seed ^= *seed << 17;
		u[k] = (double)(*seed >> 11) * (1.0 / 9007199254740992.0);
	}
	const double deg = 3.14159265358979323846 / 180.0;
	const double V = 0.1 + 7.9 * u[0], a = (178.0 * u[1] - 89.0) * deg;
	const double top = u[2] < 0.6 ? 4.0 * u[2] / 0.6 - 2.0 : u[2] < 0.8 ? 1.0 : 0.0; // any; rolling; stun
	pool_ball_state b;
	memset(&b, 0, sizeof b);
	b.pos = pool_v3(1.0, 1.0, R);
	b.vel = pool_v3(V * sin(a), V * cos(a), 0.0);
	b.omega = pool_v3(-top * b.vel.y / R, top * b.vel.x / R, (6.0 * u[3] - 3.0) * V / R);
	return b;
}

double pool_mathavan_difference(const pool_ball_state *in, const pool_ball_state *a, const pool_ball_state *b, double R) {
	double scale = 0.0, d = 0.0;
	for (int j = 0; j < 3; ++j) {
		scale = fmax(scale, fmax(fabs((&in->vel.x)[j]), R * fabs((&in->omega.x)[j])));
		d = fmax(d, fmax(fabs((&a->vel.x)[j] - (&b->vel.x)[j]), R * fabs((&a->omega.x)[j] - (&b->omega.x)[j])));
	}
	return d / scale;
}
