// Event prediction: ball-ball contact times (quartic), touching pairs, cushion and pocket contacts.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "pool/pool.h"
#include "predict.h"
#include "vec3.h"

static const double R = 0.028575;

static void near_rel(double got, double want, double rel) {
	if (!(fabs(got - want) <= rel * fmax(fabs(want), 1e-300)))
		fail_msg("got %.17g, want %.17g", got, want);
}

// Constant relative velocity: contact when |dp + dv t| = 2R, a closed form.
static void test_linear_approach(void **state) {
	(void)state;
	pool_vec3 zero = pool_v3(0, 0, 0);
	// Head-on from 0.5 m at 2 m/s.
	near_rel(pool_predict_ball_ball(pool_v3(-0.5, 0, 0), pool_v3(2, 0, 0), zero, R, 10.0), (0.5 - 2 * R) / 2.0, 1e-12);
	// Offset b: t = (x0 - sqrt(4R^2 - b^2)) / v.
	double b = 1.3 * R;
	near_rel(pool_predict_ball_ball(pool_v3(-0.5, b, 0), pool_v3(2, 0, 0), zero, R, 10.0),
	         (0.5 - sqrt(4 * R * R - b * b)) / 2.0, 1e-12);
	// Miss.
	assert_true(isinf(pool_predict_ball_ball(pool_v3(-0.5, 2.01 * R, 0), pool_v3(2, 0, 0), zero, R, 10.0)));
	// Moving apart.
	assert_true(isinf(pool_predict_ball_ball(pool_v3(0.5, 0, 0), pool_v3(2, 0, 0), zero, R, 10.0)));
	// Window too short.
	assert_true(isinf(pool_predict_ball_ball(pool_v3(-0.5, 0, 0), pool_v3(2, 0, 0), zero, R, 0.2)));
}

// Decelerating: x(t) = -d + v t - a t^2 / 2 relative; contact when that reaches -2R.
static void test_decelerating(void **state) {
	(void)state;
	double d = 0.4, v = 1.5, a = 1.962; // sliding deceleration
	double want = (v - sqrt(v * v - 2 * a * (d - 2 * R))) / a;
	near_rel(pool_predict_ball_ball(pool_v3(-d, 0, 0), pool_v3(v, 0, 0), pool_v3(-a / 2, 0, 0), R, 10.0), want, 1e-10);
	// Stops short: no contact even over a long window clipped at the stop.
	assert_true(isinf(pool_predict_ball_ball(pool_v3(-d, 0, 0), pool_v3(0.5, 0, 0), pool_v3(-a / 2, 0, 0), R, 0.5 / a)));
	// Equal accelerations (a4 = a3 = 0): two balls rolling the same way, the rear one faster.
	pool_vec3 da = pool_v3(0, 0, 0);
	near_rel(pool_predict_ball_ball(pool_v3(-0.3, 0.01, 0), pool_v3(0.5, 0, 0), da, R, 10.0),
	         (0.3 - sqrt(4 * R * R - 1e-4)) / 0.5, 1e-12);
}

// Touching pairs (a0 = 0): approaching collide now, separating or sliding past do not.
static void test_touching(void **state) {
	(void)state;
	pool_vec3 zero = pool_v3(0, 0, 0);
	pool_vec3 dp = pool_v3(-2 * R, 0, 0);
	assert_true(pool_predict_ball_ball(dp, pool_v3(1e-3, 0, 0), zero, R, 1.0) == 0.0);
	assert_true(isinf(pool_predict_ball_ball(dp, pool_v3(-1e-3, 0, 0), zero, R, 1.0)));
	assert_true(isinf(pool_predict_ball_ball(dp, pool_v3(0, 1.0, 0), zero, R, 1.0)));
	assert_true(isinf(pool_predict_ball_ball(dp, pool_v3(1e-12, 0, 0), zero, R, 1.0))); // below POOL_APPROACH_EPS
	// Within the touch tolerance (a rack's rounding), still now.
	assert_true(pool_predict_ball_ball(pool_v3(-2 * R - 5e-10, 0, 0), pool_v3(1, 0, 0), zero, R, 1.0) == 0.0);
	// Separating now but pulled back later by the relative acceleration: a later contact.
	double t = pool_predict_ball_ball(dp, pool_v3(-0.1, 0, 0), pool_v3(0.5, 0, 0), R, 10.0);
	near_rel(t, 0.2, 1e-9);
}

// Cushions: a rolling ball meets the north nose when W - y = sqrt(R^2 - (h - R)^2); pockets by
// their mouths on the rail lines.
static void test_cushion_and_pockets(void **state) {
	(void)state;
	pool_table_def t = pool_default_table_def();
	const double h = t.cushion_height, dc = sqrt(R * R - (h - R) * (h - R));
	pool_ball_state s = {0};
	s.pos = pool_v3(1.0, 0.6, R);
	s.vel = pool_v3(0.0, 2.0, 0.0);
	pool_rail rail;
	pool_pocket pocket;
	double tc = pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), 10.0, &rail, &pocket);
	near_rel(tc, (t.width - dc - 0.6) / 2.0, 1e-12);
	assert_int_equal(rail, POOL_RAIL_NORTH);
	assert_int_equal(pocket, POOL_POCKET_NONE);
	// Towards the south-west: the west rail at y inside the last corner_mouth/sqrt(2).
	s.pos = pool_v3(0.3, 0.1, R);
	s.vel = pool_v3(-1.0, -0.1, 0.0);
	tc = pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), 10.0, &rail, &pocket);
	assert_int_equal(rail, POOL_RAIL_WEST);
	assert_int_equal(pocket, POOL_POCKET_SW);
	// Touching the rail: moving in hits now, moving out never.
	s.pos = pool_v3(t.length - dc, 0.6, R);
	s.vel = pool_v3(0.5, 0.0, 0.0);
	assert_true(pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), 10.0, &rail, &pocket) == 0.0);
	assert_int_equal(rail, POOL_RAIL_EAST);
	s.vel = pool_v3(-0.5, 0.0, 0.0);
	assert_true(pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), 0.5, &rail, &pocket) > 0.5 * (t.length - 2 * dc));
	// Mouth intervals.
	const double L = t.length, W = t.width, c = t.corner_mouth / sqrt(2.0);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_SOUTH, L / 2 + 0.5 * t.side_mouth - 1e-6), POOL_POCKET_S);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_SOUTH, L / 2 + 0.5 * t.side_mouth + 1e-6), POOL_POCKET_NONE);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_NORTH, L / 2), POOL_POCKET_N);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_NORTH, c - 1e-6), POOL_POCKET_NW);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_NORTH, c + 1e-6), POOL_POCKET_NONE);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_SOUTH, L - c + 1e-6), POOL_POCKET_SE);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_EAST, W - c + 1e-6), POOL_POCKET_NE);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_EAST, c - 1e-6), POOL_POCKET_SE);
	assert_int_equal(pool_pocket_at(&t, POOL_RAIL_WEST, W / 2), POOL_POCKET_NONE);
}

// A ball frozen to the north rail, sliding along it (v_y = 0) with a slip that curves it into the
// rail (a_y > 0): it is already in contact and being pushed in, so the contact is now, not never
// (the nose would otherwise let it through). Pushed away, or moving along without a push, no contact.
static void test_cushion_touching_pushed_in(void **state) {
	(void)state;
	pool_table_def t = pool_default_table_def();
	const double h = t.cushion_height, dc = sqrt(R * R - (h - R) * (h - R));
	pool_ball_state s = {0};
	s.pos = pool_v3(0.5, t.width - dc, R);
	s.vel = pool_v3(1.0, 0.0, 0.0);
	pool_rail rail;
	pool_pocket pocket;
	assert_true(pool_predict_cushion(&t, R, &s, pool_v3(-1.0, 1.5, 0.0), 0.1, &rail, &pocket) == 0.0);
	assert_int_equal(rail, POOL_RAIL_NORTH);
	assert_int_equal(pocket, POOL_POCKET_NONE);
	// The same at the west rail, moving along -y.
	s.pos = pool_v3(dc, 0.6, R);
	s.vel = pool_v3(0.0, -1.0, 0.0);
	assert_true(pool_predict_cushion(&t, R, &s, pool_v3(-1.5, 1.0, 0.0), 0.1, &rail, &pocket) == 0.0);
	assert_int_equal(rail, POOL_RAIL_WEST);
	// Pushed away from the rail, or no push: no contact within the window.
	assert_true(isinf(pool_predict_cushion(&t, R, &s, pool_v3(1.5, 1.0, 0.0), 0.1, &rail, &pocket)));
	assert_true(isinf(pool_predict_cushion(&t, R, &s, pool_v3(0.0, 1.0, 0.0), 0.1, &rail, &pocket)));
}

// Touching (here overlapping by 5e-10 m, inside the touch tolerance), no normal relative velocity,
// and a relative acceleration pushing the balls together (|p|^2 = 4R^2 + a2 t^2 + ... with
// a2 = dv.dv + 2 da.dp < 0): contact now, or they would pass through each other. With the same
// acceleration pulling them apart, or a tangential speed fast enough to curve them apart, none.
static void test_touching_pushed_together(void **state) {
	(void)state;
	const pool_vec3 dp = pool_v3(0, -2 * R + 5e-10, 0), dv = pool_v3(0.1, 0, 0);
	// dp = p1 - p2 points along -y; a relative acceleration with +y drives body 1 into body 2.
	const pool_vec3 da = pool_v3(-0.3, 0.9, 0);
	assert_true(pool_v3_dot(dv, dv) + 2.0 * pool_v3_dot(da, dp) < 0.0);
	assert_true(pool_predict_ball_ball(dp, dv, da, R, 1.0) == 0.0);
	assert_true(pool_predict_ball_ball(pool_v3(0, -2 * R, 0), dv, da, R, 1.0) == 0.0);
	// Pulled apart: never within the window.
	assert_true(isinf(pool_predict_ball_ball(dp, dv, pool_v3(-0.3, -0.9, 0), R, 1.0)));
	// Tangential speed 1 m/s curves them apart faster than 1.8 m/s^2 pushes them in: a2 > 0.
	assert_true(isinf(pool_predict_ball_ball(dp, pool_v3(1.0, 0, 0), da, R, 1.0)));
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_linear_approach),
		cmocka_unit_test(test_decelerating),
		cmocka_unit_test(test_touching),
		cmocka_unit_test(test_touching_pushed_together),
		cmocka_unit_test(test_cushion_and_pockets),
		cmocka_unit_test(test_cushion_touching_pushed_in),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
