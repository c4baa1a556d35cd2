// The cue strike (PHYSICS.md "Cue strike", VALIDATION.md item 4).
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "motion.h"
#include "pool/pool.h"
#include "vec3.h"

static void near_rel(double got, double want, double rel) {
	if (!(fabs(got - want) <= rel * fmax(fabs(want), 1e-300)))
		fail_msg("got %.17g, want %.17g", got, want);
}

// 4. A level cue b = 2R/5 above centre gives natural roll, in any direction.
static void test_natural_roll(void **state) {
	(void)state;
	const pool_params p = pool_default_params();
	const double R = p.ball_radius;
	for (int i = 0; i < 12; ++i) {
		pool_strike s = {3.0, i * 0.5236, 0.0, 0.0, 0.4 * R};
		pool_vec3 v, w;
		assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, NULL), POOL_OK);
		pool_vec3 u = pool_v3_madd(v, R, pool_v3_kcross(w));
		assert_true(pool_v3_len(u) <= 1e-12 * pool_v3_len(v));
		pool_ball_state b = {0};
		b.vel = v;
		b.omega = w;
		pool_motion_derive(&p, &b);
		assert_int_equal(b.motion, POOL_MOTION_ROLLING);
		// Off the 2R/5 height the ball slides.
		s.b = 0.3 * R;
		pool_strike_velocities(&p, &s, &v, &w, NULL);
		assert_true(pool_v3_len(pool_v3_madd(v, R, pool_v3_kcross(w))) > 1e-3);
	}
}

// The Leckie & Greenspan impulse: centre hit F = 2 m V / (1 + m/M), v = F/m along the cue.
static void test_centre_hit(void **state) {
	(void)state;
	const pool_params p = pool_default_params();
	const double m = p.ball_mass, M = p.cue_mass;
	pool_strike s = {2.0, 0.3, 0.0, 0.0, 0.0};
	pool_vec3 v, w;
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, NULL), POOL_OK);
	near_rel(pool_v3_len(v), 2.0 * 2.0 / (1.0 + m / M), 1e-14);
	near_rel(atan2(v.y, v.x), 0.3, 1e-14);
	assert_true(pool_v3_len(w) <= 1e-12);
	// Elevated cue: v along d = cos(theta) j - sin(theta) k (v_z < 0: into the cloth); the line of
	// action misses the centre by R sin(theta), so |Q x d|^2 = R^2 sin^2(theta).
	s.theta = 0.5;
	pool_strike_velocities(&p, &s, &v, &w, NULL);
	near_rel(v.z / pool_v3_len(v), -sin(0.5), 1e-14);
	near_rel(pool_v3_len(v), 2.0 * 2.0 / (1.0 + m / M + 2.5 * sin(0.5) * sin(0.5)), 1e-14);
}

// General offsets: F formula with |Q x d|, w = Q x F d / I; right english (a > 0) pushes the
// ball's right side forward: counter-clockwise seen from above (w_z > 0).
static void test_offsets(void **state) {
	(void)state;
	const pool_params p = pool_default_params();
	const double R = p.ball_radius, m = p.ball_mass, M = p.cue_mass, I = 0.4 * m * R * R;
	pool_strike s = {4.0, 1.0, 0.3, 0.5 * R, -0.3 * R};
	pool_vec3 v, w;
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, NULL), POOL_OK);
	pool_vec3 j = pool_v3(cos(1.0), sin(1.0), 0), k = pool_v3(0, 0, 1), r = pool_v3_cross(j, k);
	pool_vec3 d = pool_v3_madd(pool_v3_scale(j, cos(0.3)), -sin(0.3), k);
	double c = sqrt(R * R - s.a * s.a - s.b * s.b);
	pool_vec3 Q = pool_v3_madd(pool_v3_madd(pool_v3_scale(r, s.a), s.b, k), -c, j);
	pool_vec3 qd = pool_v3_cross(Q, d);
	double F = 2 * m * 4.0 / (1 + m / M + 5.0 / (2 * R * R) * pool_v3_dot(qd, qd));
	near_rel(pool_v3_len(v), F / m, 1e-14);
	near_rel(w.x, pool_v3_scale(qd, F / I).x, 1e-12);
	near_rel(w.z, pool_v3_scale(qd, F / I).z, 1e-12);
	pool_strike right = {2.0, 0.0, 0.0, 0.5 * R, 0.0};
	pool_strike_velocities(&p, &right, &v, &w, NULL);
	assert_true(w.z > 0.0);
}

static void test_bad_strikes(void **state) {
	(void)state;
	const pool_params p = pool_default_params();
	const double R = p.ball_radius;
	pool_vec3 v, w;
	pool_error err;
	pool_strike s = {2.0, 0.0, 0.0, 0.8 * R, 0.6 * R};
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, &err), POOL_ERR_BAD_STRIKE);
	assert_string_equal(err.message, "strike.a: a^2 + b^2 must be < R^2");
	s = (pool_strike){0.0, 0.0, 0.0, 0.0, 0.0};
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, &err), POOL_ERR_BAD_STRIKE);
	assert_non_null(strstr(err.message, "strike.speed"));
	s = (pool_strike){1.0, NAN, 0.0, 0.0, 0.0};
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, &err), POOL_ERR_NON_FINITE);
	assert_non_null(strstr(err.message, "strike.phi"));
	s = (pool_strike){1.0, 0.0, 1.6, 0.0, 0.0};
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, &err), POOL_ERR_BAD_STRIKE);
	assert_non_null(strstr(err.message, "strike.theta"));
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_natural_roll),
		cmocka_unit_test(test_centre_hit),
		cmocka_unit_test(test_offsets),
		cmocka_unit_test(test_bad_strikes),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
