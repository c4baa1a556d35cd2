// Closed-form motion on the cloth against docs/validation.md section 1 (items 1-3) and docs/physics.md.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "motion.h"
#include "pool/pool.h"
#include "vec3.h"

#define REL 1e-9

static void near_rel(double got, double want) {
	double tol = REL * fmax(fabs(want), 1e-300);
	if (!(fabs(got - want) <= tol))
		fail_msg("got %.17g, want %.17g", got, want);
}

static pool_ball_state make(const pool_params *p, pool_vec3 v, pool_vec3 w) {
	pool_ball_state s = {0};
	s.pos = pool_v3(1.0, 0.5, p->ball_radius);
	s.vel = v;
	s.omega = w;
	pool_motion_derive(p, &s);
	return s;
}

// Runs a sliding state to its slide_roll and returns the rolling state there.
static pool_ball_state to_roll(const pool_params *p, const pool_ball_state *s, double *t) {
	pool_event_type kind;
	pool_ball_state r = *s;
	*t = 0.0;
	do { // a spin_stop may come first: it ends the segment but not the slide
		double dt = pool_motion_next_change(p, &r, &kind);
		pool_ball_state e;
		pool_motion_evolve(p, &r, dt, &e);
		pool_motion_apply_change(p, &e, kind);
		r = e;
		*t += dt;
	} while (kind == POOL_EVENT_SPIN_STOP);
	assert_int_equal(kind, POOL_EVENT_SLIDE_ROLL);
	return r;
}

// 1. Stun: rolling at 2 v0 / (7 mu g), after 12 v0^2 / (49 mu g), at 5 v0 / 7.
static void test_stun(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	for (double v0 = 0.1; v0 < 9.0; v0 *= 2.3) {
		pool_ball_state s = make(&p, pool_v3(v0, 0, 0), pool_v3(0, 0, 0));
		assert_int_equal(s.motion, POOL_MOTION_SLIDING);
		double t;
		pool_ball_state r = to_roll(&p, &s, &t);
		near_rel(t, 2.0 * v0 / (7.0 * p.mu_slide * p.g));
		near_rel(r.pos.x - s.pos.x, 12.0 * v0 * v0 / (49.0 * p.mu_slide * p.g));
		near_rel(r.vel.x, 5.0 * v0 / 7.0);
		assert_int_equal(r.motion, POOL_MOTION_ROLLING);
		// Exactly rolling: zero slip.
		pool_vec3 u = pool_v3_madd(r.vel, p.ball_radius, pool_v3_kcross(r.omega));
		assert_true(pool_v3_len(u) == 0.0);
	}
}

// 2. Top/back spin k = R w / v0: final speed v0 (5 + 2k) / 7, slide time 2 |1 - k| v0 / (7 mu g).
static void test_top_back_spin(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	const double ks[] = {-3.0, -1.0, -0.4, 0.0, 0.5, 0.99, 1.7, 4.0};
	const double v0 = 2.0, R = p.ball_radius;
	for (size_t i = 0; i < sizeof ks / sizeof ks[0]; ++i) {
		double k = ks[i];
		// Ball moving +x; natural roll is w = (0, v0 / R, 0).
		pool_ball_state s = make(&p, pool_v3(v0, 0, 0), pool_v3(0, k * v0 / R, 0));
		double t;
		pool_ball_state r = to_roll(&p, &s, &t);
		near_rel(t, 2.0 * fabs(1.0 - k) * v0 / (7.0 * p.mu_slide * p.g));
		near_rel(r.vel.x, v0 * (5.0 + 2.0 * k) / 7.0);
		assert_true(fabs(r.vel.y) <= 1e-15);
	}
	// k = 1 is natural roll already: rolling, no slide.
	pool_ball_state s = make(&p, pool_v3(v0, 0, 0), pool_v3(0, v0 / R, 0));
	assert_int_equal(s.motion, POOL_MOTION_ROLLING);
}

// 3. Masse: the ball ends rolling with v0 - (2/7) u0 whatever the friction.
static void test_masse(void **state) {
	(void)state;
	const double mus[] = {0.05, 0.2, 0.4};
	uint64_t x = 12345;
	for (int rep = 0; rep < 60; ++rep) {
		pool_params p = pool_default_params();
		p.mu_slide = mus[rep % 3];
		double r[6];
		for (int i = 0; i < 6; ++i) {
			x = x * 6364136223846793005ull + 1442695040888963407ull;
			r[i] = ((double)(x >> 11) / 9007199254740992.0) * 2.0 - 1.0;
		}
		pool_vec3 v0 = pool_v3(3 * r[0], 3 * r[1], 0), w0 = pool_v3(150 * r[2], 150 * r[3], 40 * r[4]);
		pool_ball_state s = make(&p, v0, w0);
		pool_vec3 u0 = pool_v3_madd(v0, p.ball_radius, pool_v3_kcross(w0));
		double t;
		pool_ball_state e = to_roll(&p, &s, &t);
		pool_vec3 want = pool_v3_madd(v0, -2.0 / 7.0, u0);
		double scale = pool_v3_len(v0) + pool_v3_len(u0);
		assert_true(fabs(e.vel.x - want.x) <= REL * scale);
		assert_true(fabs(e.vel.y - want.y) <= REL * scale);
	}
}

// Rolling: stops after v0 / (mu_roll g) having covered v0^2 / (2 mu_roll g).
static void test_roll_stop(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	const double v0 = 1.3, R = p.ball_radius;
	pool_vec3 dir = pool_v3(0.6, -0.8, 0);
	pool_ball_state s = make(&p, pool_v3_scale(dir, v0), pool_v3_scale(pool_v3_kcross(dir), v0 / R));
	assert_int_equal(s.motion, POOL_MOTION_ROLLING);
	pool_event_type kind;
	double t = pool_motion_next_change(&p, &s, &kind);
	assert_int_equal(kind, POOL_EVENT_ROLL_STOP);
	near_rel(t, v0 / (p.mu_roll * p.g));
	pool_ball_state e;
	pool_motion_evolve(&p, &s, t, &e);
	near_rel(pool_v3_len(pool_v3_sub(e.pos, s.pos)), v0 * v0 / (2.0 * p.mu_roll * p.g));
	pool_motion_apply_change(&p, &e, kind);
	assert_int_equal(e.motion, POOL_MOTION_STATIONARY);
	assert_true(pool_v3_len(e.vel) == 0.0 && pool_v3_len(e.omega) == 0.0);
	// Halfway in time: speed v0 / 2 and spin still exactly rolling.
	pool_motion_evolve(&p, &s, 0.5 * t, &e);
	near_rel(pool_v3_len(e.vel), 0.5 * v0);
	assert_true(pool_v3_len(pool_v3_madd(e.vel, R, pool_v3_kcross(e.omega))) <= 1e-15);
}

// z-spin decays at 5 mu_spin g / (2R) (10.9 rad/s^2 by default) in every on-cloth state.
static void test_spin_decay(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	const double rate = 5.0 * p.mu_spin * p.g / (2.0 * p.ball_radius);
	assert_true(fabs(rate - 10.9) < 0.01);
	pool_ball_state s = make(&p, pool_v3(0, 0, 0), pool_v3(0, 0, -25.0));
	assert_int_equal(s.motion, POOL_MOTION_SPINNING);
	pool_event_type kind;
	double t = pool_motion_next_change(&p, &s, &kind);
	assert_int_equal(kind, POOL_EVENT_SPIN_STOP);
	near_rel(t, 2.0 * p.ball_radius * 25.0 / (5.0 * p.mu_spin * p.g));
	pool_ball_state e;
	pool_motion_evolve(&p, &s, 0.25 * t, &e);
	near_rel(e.omega.z, -25.0 * 0.75);
	pool_motion_evolve(&p, &s, 2.0 * t, &e); // clamped at the stop
	assert_true(e.omega.z == 0.0);
	pool_motion_apply_change(&p, &e, kind);
	assert_int_equal(e.motion, POOL_MOTION_STATIONARY);
	// Same decay while sliding: independent of the slip.
	pool_ball_state sl = make(&p, pool_v3(1, 0, 0), pool_v3(0, 0, 8.0));
	pool_motion_evolve(&p, &sl, 0.1, &e);
	near_rel(e.omega.z, 8.0 - rate * 0.1);
}

// State derivation: slip tolerance POOL_SLIP_EPS, rest tolerance POOL_REST_EPS.
static void test_derive(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	const double R = p.ball_radius;
	assert_int_equal(make(&p, pool_v3(0, 0, 0), pool_v3(0, 0, 0)).motion, POOL_MOTION_STATIONARY);
	assert_int_equal(make(&p, pool_v3(0, 0, 0), pool_v3(0, 0, 1)).motion, POOL_MOTION_SPINNING);
	assert_int_equal(make(&p, pool_v3(1, 0, 0), pool_v3(0, 1 / R, 0)).motion, POOL_MOTION_ROLLING);
	assert_int_equal(make(&p, pool_v3(1, 0, 0), pool_v3(0, 1 / R + 1e-10 / R, 0)).motion, POOL_MOTION_ROLLING);
	assert_int_equal(make(&p, pool_v3(1, 0, 0), pool_v3(0, 1 / R + 1e-8 / R, 0)).motion, POOL_MOTION_SLIDING);
	assert_int_equal(make(&p, pool_v3(0, 0, 0), pool_v3(3, 0, 0)).motion, POOL_MOTION_SLIDING);
}

// z-spin through the state changes: slide_roll keeps wz (it only snaps w_perp = k x v / R),
// roll_stop zeroes v and w_perp but keeps wz, which decays on at 5 mu_spin g / (2R) until
// spin_stop, whatever the state, from its value at the segment start.
static void test_spin_through_changes(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	const double R = p.ball_radius, rate = 5.0 * p.mu_spin * p.g / (2.0 * R), v0 = 0.3, wz0 = 30.0;
	pool_ball_state s = make(&p, pool_v3(v0, 0, 0), pool_v3(0, 0, wz0)); // stun with side spin
	assert_int_equal(s.motion, POOL_MOTION_SLIDING);
	pool_event_type kind;
	double t1 = pool_motion_next_change(&p, &s, &kind);
	assert_int_equal(kind, POOL_EVENT_SLIDE_ROLL);
	near_rel(t1, 2.0 * v0 / (7.0 * p.mu_slide * p.g));
	pool_ball_state r;
	pool_motion_evolve(&p, &s, t1, &r);
	pool_motion_apply_change(&p, &r, kind);
	assert_int_equal(r.motion, POOL_MOTION_ROLLING);
	near_rel(r.omega.z, wz0 - rate * t1);
	near_rel(r.omega.y, 5.0 * v0 / (7.0 * R));
	double t2 = pool_motion_next_change(&p, &r, &kind);
	assert_int_equal(kind, POOL_EVENT_ROLL_STOP);
	near_rel(t2, 5.0 * v0 / 7.0 / (p.mu_roll * p.g));
	pool_ball_state q;
	pool_motion_evolve(&p, &r, t2, &q);
	pool_motion_apply_change(&p, &q, kind);
	assert_int_equal(q.motion, POOL_MOTION_SPINNING);
	assert_true(q.vel.x == 0.0 && q.omega.x == 0.0 && q.omega.y == 0.0);
	near_rel(q.omega.z, wz0 - rate * (t1 + t2));
	double t3 = pool_motion_next_change(&p, &q, &kind);
	assert_int_equal(kind, POOL_EVENT_SPIN_STOP);
	near_rel(t1 + t2 + t3, wz0 / rate);
	pool_motion_evolve(&p, &q, t3, &r);
	pool_motion_apply_change(&p, &r, kind);
	assert_int_equal(r.motion, POOL_MOTION_STATIONARY);
	assert_true(r.omega.z == 0.0);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_stun),       cmocka_unit_test(test_top_back_spin), cmocka_unit_test(test_masse),
		cmocka_unit_test(test_roll_stop),  cmocka_unit_test(test_spin_decay),    cmocka_unit_test(test_derive),
		cmocka_unit_test(test_spin_through_changes),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
