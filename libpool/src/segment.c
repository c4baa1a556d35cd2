// Motion segments: the closed forms of each motion state (docs/physics.md "Motion between events").
#include "segment.h"

#include <math.h>

#include "vec3.h"

// Slip of the contact point on the cloth, u = v + R k x w (horizontal).
static pool_vec3 slip(const pool_params *p, const pool_ball_state *s) {
	return pool_v3_madd(pool_v3_xy(s->vel), p->ball_radius, pool_v3_kcross(s->omega));
}

// Time for a quantity x0 > 0 to reach 0 at rate r >= 0 (INFINITY when r = 0).
static double stop_time(double x0, double rate) { return rate > 0.0 ? x0 / rate : INFINITY; }

static pool_vec3 no_accel(const pool_params *p, const pool_ball_state *s) {
	(void)p;
	(void)s;
	return pool_v3(0.0, 0.0, 0.0);
}

static double no_end(const pool_params *p, const pool_ball_state *s, pool_event_type *kind) {
	(void)p;
	(void)s;
	(void)kind;
	return INFINITY;
}

static void spin_kept(const pool_params *p, const pool_ball_state *s0, double tau, pool_vec3 vel, pool_vec3 *w) {
	(void)p;
	(void)tau;
	(void)vel;
	*w = s0->omega;
}

// Sliding: friction mu_slide m g against the slip u0: a = -mu_slide g u0/|u0|; the slip
// shrinks 7/2 times as fast, w_perp(t) = w0_perp + (5 mu_slide g / 2R) t (k x u_hat).
static pool_vec3 sliding_accel(const pool_params *p, const pool_ball_state *s) {
	const pool_vec3 u = slip(p, s);
	return pool_v3_scale(u, -p->mu_slide * p->g / pool_v3_len(u));
}

static double sliding_end(const pool_params *p, const pool_ball_state *s, pool_event_type *kind) {
	*kind = POOL_EVENT_SLIDE_ROLL;
	return stop_time(2.0 * pool_v3_len(slip(p, s)), 7.0 * p->mu_slide * p->g);
}

static void sliding_spin(const pool_params *p, const pool_ball_state *s0, double tau, pool_vec3 vel, pool_vec3 *w) {
	(void)vel;
	const pool_vec3 u0 = slip(p, s0);
	const pool_vec3 uhat = pool_v3_scale(u0, 1.0 / pool_v3_len(u0));
	const pool_vec3 dw = pool_v3_scale(pool_v3_kcross(uhat), 5.0 * p->mu_slide * p->g * tau / (2.0 * p->ball_radius));
	*w = s0->omega;
	w->x += dw.x;
	w->y += dw.y;
}

// Rolling: resistance mu_roll g against v; the spin stays w_perp = k x v / R.
static pool_vec3 rolling_accel(const pool_params *p, const pool_ball_state *s) {
	const pool_vec3 v = pool_v3_xy(s->vel);
	return pool_v3_scale(v, -p->mu_roll * p->g / pool_v3_len(v));
}

static double rolling_end(const pool_params *p, const pool_ball_state *s, pool_event_type *kind) {
	*kind = POOL_EVENT_ROLL_STOP;
	return stop_time(pool_v3_len(pool_v3_xy(s->vel)), p->mu_roll * p->g);
}

static void rolling_spin(const pool_params *p, const pool_ball_state *s0, double tau, pool_vec3 vel, pool_vec3 *w) {
	(void)tau;
	const pool_vec3 r = pool_v3_scale(pool_v3_kcross(vel), 1.0 / p->ball_radius);
	*w = s0->omega;
	w->x = r.x;
	w->y = r.y;
}

// Airborne: no friction, gravity only (r(t) = r0 + v0 t - g t^2 k / 2), w constant.
static pool_vec3 airborne_accel(const pool_params *p, const pool_ball_state *s) {
	(void)s;
	return pool_v3(0.0, 0.0, -p->g);
}

static const pool_segment_model resting = {0, 1, no_accel, no_end, spin_kept};
static const pool_segment_model sliding = {1, 1, sliding_accel, sliding_end, sliding_spin};
static const pool_segment_model rolling = {1, 1, rolling_accel, rolling_end, rolling_spin};
static const pool_segment_model airborne = {1, 0, airborne_accel, no_end, spin_kept};
static const pool_segment_model out_of_play = {0, 0, no_accel, no_end, spin_kept};
// Linked (a LINK cluster): over one link step the velocities are the step's LCP solution, held
// constant (positions advance by dt v, link.c), so the segment is uniform motion.
static const pool_segment_model linked = {1, 0, no_accel, no_end, spin_kept};

const pool_segment_model *pool_segment_model_of(pool_motion motion) {
	switch (motion) {
	case POOL_MOTION_STATIONARY:
	case POOL_MOTION_SPINNING: return &resting;
	case POOL_MOTION_SLIDING: return &sliding;
	case POOL_MOTION_ROLLING: return &rolling;
	case POOL_MOTION_AIRBORNE: return &airborne;
	case POOL_MOTION_LINKED: return &linked;
	default: return &out_of_play;
	}
}

static double spin_rate(const pool_params *p) { return 5.0 * p->mu_spin * p->g / (2.0 * p->ball_radius); }

void pool_segment_begin(pool_segment *seg, const pool_params *p, const pool_ball_state *s, double t0) {
	const pool_segment_model *m = pool_segment_model_of(s->motion);
	seg->start = *s;
	seg->t0 = t0;
	seg->model = m;
	seg->acc = m->accel(p, s);
	seg->move_kind = POOL_EVENT_SPIN_STOP;
	seg->move_end = m->move_end(p, s, &seg->move_kind);
	seg->spin_end = m->on_cloth && s->omega.z != 0.0 ? stop_time(fabs(s->omega.z), spin_rate(p)) : INFINITY;
}

void pool_segment_state(const pool_segment *seg, const pool_params *p, double tau, pool_ball_state *out) {
	const pool_ball_state *s0 = &seg->start;
	*out = *s0;
	if (!(tau > 0.0))
		return;
	pool_segment_path(seg, tau, &out->pos, &out->vel);
	// The model sets the spin perpendicular to z and keeps the start's z-spin, which on the
	// cloth decays linearly until spin_end.
	seg->model->spin(p, s0, pool_earlier(tau, seg->move_end), out->vel, &out->omega);
	if (seg->model->on_cloth && s0->omega.z != 0.0)
		out->omega.z = s0->omega.z - copysign(spin_rate(p) * pool_earlier(tau, seg->spin_end), s0->omega.z);
}
