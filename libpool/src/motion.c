// Closed-form motion on the cloth: sliding, rolling, spinning, stationary (PHYSICS.md).
#include "motion.h"

#include <math.h>

#include "vec3.h"

// Slip of the contact point on the cloth, u = v + R k x w (horizontal).
static pool_vec3 slip(const pool_params *p, const pool_ball_state *s) {
	return pool_v3_madd(pool_v3_xy(s->vel), p->ball_radius, pool_v3_kcross(s->omega));
}

static int on_cloth(pool_motion m) {
	return m == POOL_MOTION_STATIONARY || m == POOL_MOTION_SPINNING || m == POOL_MOTION_SLIDING ||
	       m == POOL_MOTION_ROLLING;
}

void pool_motion_derive(const pool_params *p, pool_ball_state *s) {
	if (s->motion == POOL_MOTION_POCKETED || s->motion == POOL_MOTION_OFF_TABLE ||
	    s->motion == POOL_MOTION_AIRBORNE || s->motion == POOL_MOTION_LINKED)
		return;
	if (pool_v3_len(slip(p, s)) > POOL_SLIP_EPS) {
		s->motion = POOL_MOTION_SLIDING;
		return;
	}
	if (pool_v3_len(s->vel) > POOL_REST_EPS) {
		s->motion = POOL_MOTION_ROLLING;
		return;
	}
	// No translation and (within POOL_SLIP_EPS / R) no rolling spin: only z-spin may remain.
	s->vel = pool_v3(0.0, 0.0, 0.0);
	s->omega.x = 0.0;
	s->omega.y = 0.0;
	if (fabs(s->omega.z) > POOL_REST_EPS) {
		s->motion = POOL_MOTION_SPINNING;
	} else {
		s->omega.z = 0.0;
		s->motion = POOL_MOTION_STATIONARY;
	}
}

pool_vec3 pool_motion_accel(const pool_params *p, const pool_ball_state *s) {
	if (s->motion == POOL_MOTION_SLIDING) {
		pool_vec3 u = slip(p, s);
		return pool_v3_scale(u, -p->mu_slide * p->g / pool_v3_len(u));
	}
	if (s->motion == POOL_MOTION_ROLLING) {
		pool_vec3 v = pool_v3_xy(s->vel);
		return pool_v3_scale(v, -p->mu_roll * p->g / pool_v3_len(v));
	}
	return pool_v3(0.0, 0.0, 0.0);
}

// Time for a quantity x0 > 0 to reach 0 at rate r >= 0 (INFINITY when r = 0).
static double stop_time(double x0, double rate) { return rate > 0.0 ? x0 / rate : INFINITY; }

static double spin_rate(const pool_params *p) { return 5.0 * p->mu_spin * p->g / (2.0 * p->ball_radius); }

double pool_motion_next_change(const pool_params *p, const pool_ball_state *s,
                               pool_event_type *kind) {
	double best = INFINITY;
	pool_event_type k = POOL_EVENT_SPIN_STOP;
	if (s->motion == POOL_MOTION_SLIDING) {
		best = stop_time(2.0 * pool_v3_len(slip(p, s)), 7.0 * p->mu_slide * p->g);
		k = POOL_EVENT_SLIDE_ROLL;
	} else if (s->motion == POOL_MOTION_ROLLING) {
		best = stop_time(pool_v3_len(pool_v3_xy(s->vel)), p->mu_roll * p->g);
		k = POOL_EVENT_ROLL_STOP;
	}
	if (on_cloth(s->motion) && s->omega.z != 0.0) {
		double ts = stop_time(fabs(s->omega.z), spin_rate(p));
		if (ts < best) {
			best = ts;
			k = POOL_EVENT_SPIN_STOP;
		}
	}
	if (kind)
		*kind = k;
	return best;
}

void pool_motion_evolve(const pool_params *p, const pool_ball_state *s0, double dt,
                        pool_ball_state *out) {
	*out = *s0;
	if (!(dt > 0.0) || !on_cloth(s0->motion))
		return;
	const double R = p->ball_radius;
	if (s0->motion == POOL_MOTION_SLIDING) {
		pool_vec3 u0 = slip(p, s0);
		double ulen = pool_v3_len(u0);
		pool_vec3 uhat = pool_v3_scale(u0, 1.0 / ulen);
		double t = fmin(dt, stop_time(2.0 * ulen, 7.0 * p->mu_slide * p->g));
		double a = p->mu_slide * p->g;
		out->pos = pool_v3_madd(pool_v3_madd(s0->pos, t, s0->vel), -0.5 * a * t * t, uhat);
		out->vel = pool_v3_madd(s0->vel, -a * t, uhat);
		pool_vec3 dw = pool_v3_scale(pool_v3_kcross(uhat), 5.0 * a * t / (2.0 * R));
		out->omega.x = s0->omega.x + dw.x;
		out->omega.y = s0->omega.y + dw.y;
	} else if (s0->motion == POOL_MOTION_ROLLING) {
		pool_vec3 v0 = pool_v3_xy(s0->vel);
		double vlen = pool_v3_len(v0);
		pool_vec3 vhat = pool_v3_scale(v0, 1.0 / vlen);
		double a = p->mu_roll * p->g;
		double t = fmin(dt, stop_time(vlen, a));
		out->pos = pool_v3_madd(pool_v3_madd(s0->pos, t, v0), -0.5 * a * t * t, vhat);
		out->vel = pool_v3_madd(v0, -a * t, vhat);
		pool_vec3 w = pool_v3_scale(pool_v3_kcross(out->vel), 1.0 / R);
		out->omega.x = w.x;
		out->omega.y = w.y;
	}
	if (s0->omega.z != 0.0) {
		double rate = spin_rate(p);
		double t = fmin(dt, stop_time(fabs(s0->omega.z), rate));
		out->omega.z = s0->omega.z - copysign(rate * t, s0->omega.z);
	}
}

void pool_motion_apply_change(const pool_params *p, pool_ball_state *s, pool_event_type kind) {
	const double R = p->ball_radius;
	switch (kind) {
	case POOL_EVENT_SLIDE_ROLL: {
		s->vel.z = 0.0;
		pool_vec3 w = pool_v3_scale(pool_v3_kcross(s->vel), 1.0 / R);
		s->omega.x = w.x;
		s->omega.y = w.y;
		s->motion = pool_v3_len(s->vel) > 0.0 ? POOL_MOTION_ROLLING
		            : s->omega.z != 0.0        ? POOL_MOTION_SPINNING
		                                       : POOL_MOTION_STATIONARY;
		break;
	}
	case POOL_EVENT_ROLL_STOP:
		s->vel = pool_v3(0.0, 0.0, 0.0);
		s->omega.x = 0.0;
		s->omega.y = 0.0;
		s->motion = s->omega.z != 0.0 ? POOL_MOTION_SPINNING : POOL_MOTION_STATIONARY;
		break;
	case POOL_EVENT_SPIN_STOP:
		s->omega.z = 0.0;
		if (s->motion == POOL_MOTION_SPINNING)
			s->motion = POOL_MOTION_STATIONARY;
		break;
	default: break;
	}
}

double pool_motion_energy(const pool_params *p, const pool_ball_state *s) {
	const double m = p->ball_mass, R = p->ball_radius;
	return 0.5 * m * pool_v3_dot(s->vel, s->vel) + 0.5 * (0.4 * m * R * R) * pool_v3_dot(s->omega, s->omega);
}
