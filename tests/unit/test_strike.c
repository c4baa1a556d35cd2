// The cue strike (docs/physics.md "Cue strike", docs/validation.md item 4).
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

// General offsets, checked against mechanics rather than the formula: the cue-ball impact of
// Leckie & Greenspan is elastic, so the cue's kinetic energy before equals the cue's after
// (momentum: it loses F = m |v|, V' = V - F/M) plus the ball's translation and spin; the
// angular impulse is perpendicular to the linear one (w . v = 0); with a level cue the line of
// action passes sqrt(a^2 + b^2) from the centre, so I |w| = m |v| sqrt(a^2 + b^2). Right english
// (a > 0) pushes the ball's right side forward: counter-clockwise seen from above (w_z > 0).
static void test_offsets(void **state) {
	(void)state;
	const pool_params p = pool_default_params();
	const double R = p.ball_radius, m = p.ball_mass, M = p.cue_mass, I = 0.4 * m * R * R;
	const double offsets[][2] = {{0.5, -0.3}, {-0.2, 0.6}, {0.0, -0.7}, {0.69, 0.0}, {0.1, 0.1}};
	for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; ++k)
		for (double theta = 0.0; theta < 1.5; theta += 0.3) {
			const double V = 4.0;
			pool_strike s = {V, 1.0, theta, offsets[k][0] * R, offsets[k][1] * R};
			pool_vec3 v, w;
			assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, NULL), POOL_OK);
			const double F = m * pool_v3_len(v), V1 = V - F / M;
			const double ball = 0.5 * m * pool_v3_dot(v, v) + 0.5 * I * pool_v3_dot(w, w);
			near_rel(0.5 * M * V1 * V1 + ball, 0.5 * M * V * V, 1e-13);
			assert_true(fabs(pool_v3_dot(w, v)) <= 1e-12 * pool_v3_len(w) * pool_v3_len(v));
			if (theta == 0.0)
				near_rel(I * pool_v3_len(w), m * pool_v3_len(v) * hypot(s.a, s.b), 1e-12);
		}
	pool_vec3 v, w;
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
	// POOL_MAX_SPEED: a cue at 100 m/s is the limit; faster is refused, and so is a strike whose
	// ball would leave faster than the limit (a light ball under a heavy cue: up to 2 V).
	s = (pool_strike){POOL_MAX_SPEED, 0.0, 0.0, 0.0, 0.0};
	pool_params light = p;
	light.ball_mass = 0.01;
	assert_int_equal(pool_strike_velocities(&light, &s, &v, &w, &err), POOL_ERR_BAD_STRIKE);
	assert_non_null(strstr(err.message, "strike.speed"));
	s.speed = 0.5 * POOL_MAX_SPEED;
	assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, &err), POOL_OK);
	assert_true(pool_v3_len(v) <= POOL_MAX_SPEED);
	const double absurd[] = {POOL_MAX_SPEED * (1.0 + 1e-15), 1e200, 1e308};
	for (size_t k = 0; k < sizeof absurd / sizeof absurd[0]; ++k) {
		s.speed = absurd[k];
		assert_int_equal(pool_strike_velocities(&p, &s, &v, &w, &err), POOL_ERR_BAD_STRIKE);
		assert_non_null(strstr(err.message, "strike.speed"));
	}
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
