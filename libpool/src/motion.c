// Motion states: classification from the velocities, the exact snaps of state changes, energy;
// the closed forms of each state are segment models (segment.c).
#include "motion.h"

#include <math.h>

#include "contact.h"
#include "handlers.h"
#include "segment.h"
#include "vec3.h"

// Slip of the contact point on the cloth, u = v + R k x w (horizontal).
static pool_vec3 slip(const pool_params *p, const pool_ball_state *s) {
	return pool_v3_madd(pool_v3_xy(s->vel), p->ball_radius, pool_v3_kcross(s->omega));
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
	return pool_segment_model_of(s->motion)->accel(p, s);
}

double pool_motion_next_change(const pool_params *p, const pool_ball_state *s, pool_event_type *kind) {
	pool_segment seg;
	pool_segment_begin(&seg, p, s, 0.0);
	return pool_segment_next_change(&seg, kind);
}

void pool_motion_evolve(const pool_params *p, const pool_ball_state *s0, double dt, pool_ball_state *out) {
	pool_segment seg;
	pool_segment_begin(&seg, p, s0, 0.0);
	pool_segment_state(&seg, p, dt, out);
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

int pool_handle_state_change(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count) {
	(void)count;
	pool_motion_apply_change(&ctx->def->params, &s[0], type);
	return 0;
}

void pool_motion_after_impulse(const pool_sim_def *def, pool_ball_state *s) {
	const pool_params *p = &def->params;
	if (s->motion == POOL_MOTION_POCKETED || s->motion == POOL_MOTION_OFF_TABLE)
		return;
	if (!def->airborne) {
		s->vel.z = 0.0;
		pool_motion_derive(p, s);
		return;
	}
	const double R = p->ball_radius;
	if (s->pos.z > R + POOL_TOUCH_TOLERANCE || fabs(s->vel.z) > POOL_APPROACH_EPS) {
		s->motion = POOL_MOTION_AIRBORNE;
		return;
	}
	s->pos.z = R;
	s->vel.z = 0.0;
	if (s->motion == POOL_MOTION_AIRBORNE || s->motion == POOL_MOTION_LINKED)
		s->motion = POOL_MOTION_STATIONARY; // re-derived from the velocities below
	pool_motion_derive(p, s);
}
