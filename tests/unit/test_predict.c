// Event prediction: ball-ball contact times (quartic), touching pairs, cushion and pocket contacts.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "pool/pool.h"
#include "geometry.h"
#include "motion.h"
#include "predict.h"
#include "vec3.h"

static const double R = 0.028575;
static const double PI = 3.14159265358979323846;

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
	// Approaching slower than POOL_APPROACH_EPS with nothing to stop the drift: the overlap would
	// grow without bound, so this is a contact now too (before, it was ignored: interpenetration),
	// once the window holds the drift past the tolerance (1e-12 m/s: 1000 s). Over a window of
	// 1 s it goes 1e-12 m deep: no contact in it (the next prediction, at its end, looks again).
	assert_true(pool_predict_ball_ball(dp, pool_v3(1e-12, 0, 0), zero, R, 2000.0) == 0.0);
	assert_true(isinf(pool_predict_ball_ball(dp, pool_v3(1e-12, 0, 0), zero, R, 1.0)));
	// ... but pushed apart at 1 m/s^2 the same drift overlaps by v^2 / 2a = 5e-25 m at most and
	// ends by itself: no contact.
	assert_true(isinf(pool_predict_ball_ball(dp, pool_v3(1e-12, 0, 0), pool_v3(-0.5, 0, 0), R, 1.0)));
	// Within the touch tolerance (a rack's rounding), still now.
	assert_true(pool_predict_ball_ball(pool_v3(-2 * R - 5e-10, 0, 0), pool_v3(1, 0, 0), zero, R, 1.0) == 0.0);
	// Separating now but pulled back later by the relative acceleration: a later contact.
	double t = pool_predict_ball_ball(dp, pool_v3(-0.1, 0, 0), pool_v3(0.5, 0, 0), R, 10.0);
	near_rel(t, 0.2, 1e-9);
}

// Issue 9, class 2: a touching pair separating slowly while friction drives it back together.
// The gap is x(t) = -v t + a t^2 / 2 (v the separation speed, a the pull): it returns at
// t = 2 v / a whatever the size of v, and when v is within rounding (|v| <= POOL_APPROACH_EPS)
// the pair is in contact now. Before the fix, v = 1e-10 gave no contact at all and the balls
// went 4 cm into each other.
static void test_touching_slow_separation_pulled_back(void **state) {
	(void)state;
	const double a = 2.0; // m/s^2 relative pull (da = a/2 along the normal)
	const pool_vec3 da = pool_v3(0.5 * a, 0, 0);
	const double offsets[] = {0.0, 5e-10, -5e-10, -1e-15, 1e-15}; // gap at the start, m
	for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; ++k) {
		const pool_vec3 dp = pool_v3(-2 * R - offsets[k], 0, 0); // body 1 left of body 2
		const double slow[] = {1e-10, 2.2e-16, 0.0, -1e-10, 1e-9};
		for (size_t i = 0; i < sizeof slow / sizeof slow[0]; ++i)
			assert_true(pool_predict_ball_ball(dp, pool_v3(-slow[i], 0, 0), da, R, 1.0) == 0.0);
		// Leaving faster than rounding: they meet again at 2 v / a (the start gap is taken as zero).
		const double fast[] = {2e-9, 1e-6, 1e-3, 0.1};
		for (size_t i = 0; i < sizeof fast / sizeof fast[0]; ++i)
			near_rel(pool_predict_ball_ball(dp, pool_v3(-fast[i], 0, 0), da, R, 10.0), 2 * fast[i] / a, 1e-6);
	}
	// Interpenetrating beyond the tolerance (a bug elsewhere, or a user's rounding) is still a
	// contact: approaching, however slowly, collides now.
	assert_true(pool_predict_ball_ball(pool_v3(-2 * R + 1e-6, 0, 0), pool_v3(1e-6, 0, 0), pool_v3(0, 0, 0), R, 1.0) == 0.0);
}

// Curvature decides for a touching pair with tangential relative speed u: the distance's
// acceleration is a_pull - u^2 / (2R). Pulled harder than that: contact now; softer: they part.
static void test_touching_curvature(void **state) {
	(void)state;
	const double u = 1.0, centripetal = u * u / (2 * R); // 17.5 m/s^2
	const pool_vec3 dp = pool_v3(0, -2 * R, 0), dv = pool_v3(u, 0, 0);
	assert_true(pool_predict_ball_ball(dp, dv, pool_v3(0, 0.5 * 1.1 * centripetal, 0), R, 1.0) == 0.0);
	assert_true(isinf(pool_predict_ball_ball(dp, dv, pool_v3(0, 0.5 * 0.9 * centripetal, 0), R, 1e-3)));
}

// Two touching balls moving apart uniformly (no relative acceleration) along their line of
// centres, slower than POOL_APPROACH_EPS: their distance's curvature is exactly zero, they part
// and never meet. Written as v.v - (v.d)^2 / d.d, the curvature is a difference of two equal
// numbers whose rounding takes either sign, and a "positive" one (+1.5e-36 m/s^2) made the pair
// pressed together, a contact now: soak seed 23, cluster shot 168914, balls 0 and 1 (a linked
// ball stopped by its cluster's step, the other linked and parting at 2.1e-11 m/s after their
// collision), where the contact cut the step after no time and the cluster stepped again, 200
// times at t = 0. Those two balls' own numbers first, then such pairs in every direction.
static void test_touching_parting_along_the_normal(void **state) {
	(void)state;
	const pool_vec3 zero = pool_v3(0, 0, 0);
	const pool_vec3 p0 = pool_v3(1.2188004870454536, 0.32570631429223962, R);
	const pool_vec3 p1 = pool_v3(1.1867651942189348, 0.27837912851320684, R);
	const pool_vec3 v1 = pool_v3(-1.1904582014346001e-11, -1.758717698214981e-11, 0);
	const pool_vec3 dp = pool_v3_sub(p0, p1), dv = pool_v3_scale(v1, -1.0);
	assert_true(pool_v3_len(dp) - 2 * R <= POOL_TOUCH_TOLERANCE);                  // touching
	assert_true(pool_v3_dot(dp, dv) > 0.0 && pool_v3_dot(dp, dv) < POOL_APPROACH_EPS * pool_v3_len(dp)); // parting slowly
	assert_true(isinf(pool_predict_ball_ball(dp, dv, zero, R, 1e-3)));
	assert_true(isinf(pool_predict_ball_ball(pool_v3_scale(dp, -1.0), v1, zero, R, 1e-3))); // from the other ball
	int now = 0;
	for (int k = 0; k < 3600; ++k) {
		const double a = 2.0 * PI * k / 3600.0, gap = 1e-9 * (k % 7) / 7.0, speed = 1e-12 * (1 + k % 900);
		const pool_vec3 n = pool_v3(cos(a), sin(a), 0);
		const pool_vec3 d = pool_v3_scale(n, 2 * R + gap);
		const pool_vec3 v = pool_v3_scale(n, speed);
		now += pool_predict_ball_ball(d, v, zero, R, 1e-3) < INFINITY;
	}
	assert_int_equal(now, 0);
}

// Two balls rolling side by side, touching, released by LINK (soak seed 29, nose shot 34885, balls
// 0 and 3 at t = 0.092 s): closing at 2.5e-11 m/s, within rounding, their tangential relative
// speed (7e-5 m/s) curving them apart by 5.8e-9 m/s^2 at this instant, so the drift test lets
// them go. But their rolling friction, along velocities 3 mrad apart, turns them together, and
// the higher terms of the gap take over before it ever opens: the closed form has them 1.04e-9 m
// deep 0.19 s later. The oracle is that closed form, sampled: the contact comes where the overlap
// first reaches POOL_TOUCH_TOLERANCE (to the sampling's step), and never deeper than that before.
static void test_touching_creep_turned_in_by_friction(void **state) {
	(void)state;
	const pool_params params = pool_default_sim_def().params;
	const pool_ball_state b0 = {.id = 0, .motion = POOL_MOTION_ROLLING, .pos = {2.132713667384912, 0.2527643382053801, R},
	                            .vel = {0.01086110987520449, 0.018905383236107836, 0},
	                            .omega = {-0.6616057125497053, 0.38009133421538005, 0}};
	const pool_ball_state b3 = {.id = 3, .motion = POOL_MOTION_ROLLING, .pos = {2.104175566486374, 0.20324970100478054, R},
	                            .vel = {0.010923824194648778, 0.018869237436235288, 0},
	                            .omega = {-0.6603407676722755, 0.38228606105507473, 0}};
	const pool_vec3 a0 = pool_motion_accel(&params, &b0), a3 = pool_motion_accel(&params, &b3);
	const pool_vec3 dp = pool_v3_sub(b0.pos, b3.pos), dv = pool_v3_sub(b0.vel, b3.vel);
	const pool_vec3 da = pool_v3_scale(pool_v3_sub(a0, a3), 0.5);
	const double T = 0.3; // both roll on past it (v / (mu_roll g) > 0.2 s)
	const double t = pool_predict_ball_ball(dp, dv, da, R, T);
	// The closed form, sampled every 0.1 ms: where the overlap first passes the tolerance.
	double first_deep = INFINITY, deepest_before = -INFINITY;
	for (int k = 0; k <= 3000; ++k) {
		const double tau = 1e-4 * k;
		const double gap = pool_v3_len(pool_v3_madd(pool_v3_madd(dp, tau, dv), tau * tau, da)) - 2 * R;
		if (-gap > POOL_TOUCH_TOLERANCE && first_deep == INFINITY)
			first_deep = tau;
		if (tau < t)
			deepest_before = fmax(deepest_before, -gap);
	}
	print_message("creep turned in: contact at %.6g s, the overlap passes the tolerance at %.4g s; deepest before %.3g m\n",
	              t, first_deep, deepest_before);
	assert_true(first_deep > 0.15 && first_deep < T); // the case: deep only much later
	assert_true(t <= first_deep && t > first_deep - 1e-4);
	assert_true(deepest_before <= POOL_TOUCH_TOLERANCE * (1.0 + 1e-6));
	const double gap_at = pool_v3_len(pool_v3_madd(pool_v3_madd(dp, t, dv), t * t, da)) - 2 * R;
	assert_true(fabs(gap_at + POOL_TOUCH_TOLERANCE) <= 1e-6 * POOL_TOUCH_TOLERANCE);
}

// A drift of rounding, 1e-30 m/s (a linked ball's LCP velocity), into a touching ball over a
// window of no time (the cluster's step at this instant) or of a step: v^2 / 2|a| with |a| the
// curvature of that drift, 6.5e-60 m/s^2, put it 8.6 cm deep, a contact now; in the window it
// goes nowhere. Soak seed 45, cluster shot 1988: balls 1 and 4, the contact at the step's start
// cut it after no time and the cluster stepped again, 19 times at t = 0.
static void test_touching_rounding_drift(void **state) {
	(void)state;
	const pool_vec3 zero = pool_v3(0, 0, 0);
	const pool_vec3 n = pool_v3(0.6, -0.8, 0);
	const pool_vec3 dp = pool_v3_scale(n, 2 * R + 2.21e-10);
	const pool_vec3 dv = pool_v3(-0.9e-30, 0.7e-30, 0); // closing at 1.1e-30 m/s, a little across
	assert_true(-pool_v3_dot(dp, dv) / pool_v3_len(dp) > 0.0);
	assert_true(isinf(pool_predict_ball_ball(dp, dv, zero, R, 0.0)));
	assert_true(isinf(pool_predict_ball_ball(dp, dv, zero, R, 16e-3)));
	assert_true(isinf(pool_predict_ball_ball(dp, dv, zero, R, 60.0)));
}

// Issue 9, class 1: the cushion version. A ball touching the south rail's contact line
// (y = dc), leaving it at speed v while its slip pulls it back at a: back at the line at
// t = 2 v / a, or now when v is within rounding; and a ball drifting to a rail with no friction
// (mu_slide = 0, class 4) reaches it at d / v however slow v is.
static void test_cushion_slow_separation_pulled_back(void **state) {
	(void)state;
	pool_table_def t = pool_default_table_def();
	const double h = t.cushion_height, dc = sqrt(R * R - (h - R) * (h - R));
	pool_rail rail;
	pool_pocket pocket;
	pool_ball_state s = {0};
	const double a = 1.5;
	const double offsets[] = {0.0, 5e-10, -5e-10, -2.2e-16};
	for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; ++k) {
		s.pos = pool_v3(1.0, dc + offsets[k], R);
		const double slow[] = {1e-10, 2.2e-16, 0.0, -1e-10};
		for (size_t i = 0; i < sizeof slow / sizeof slow[0]; ++i) {
			s.vel = pool_v3(-3.0, slow[i], 0.0);
			assert_true(pool_predict_cushion(&t, R, &s, pool_v3(0.5, -a, 0), 0.1, &rail, &pocket) == 0.0);
			assert_int_equal(rail, POOL_RAIL_SOUTH);
		}
		const double fast[] = {2e-9, 1e-6, 1e-3};
		for (size_t i = 0; i < sizeof fast / sizeof fast[0]; ++i) {
			s.vel = pool_v3(-3.0, fast[i], 0.0);
			near_rel(pool_predict_cushion(&t, R, &s, pool_v3(0.5, -a, 0), 0.1, &rail, &pocket), 2 * fast[i] / a, 1e-6);
			assert_int_equal(rail, POOL_RAIL_SOUTH);
		}
	}
	// No friction, 1e-9 m/s towards the north rail from 0.6 m: the contact is d / v later.
	s.pos = pool_v3(1.0, 0.6, R);
	s.vel = pool_v3(0.0, 1e-9, 0.0);
	near_rel(pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), INFINITY, &rail, &pocket), (t.width - dc - 0.6) / 1e-9, 1e-12);
	assert_int_equal(rail, POOL_RAIL_NORTH);
	s.vel = pool_v3(0.0, 1e-13, 0.0);
	near_rel(pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), INFINITY, &rail, &pocket), (t.width - dc - 0.6) / 1e-13, 1e-12);
	// Subnormal speeds: 5e-324 m/s towards a rail 3.4e-4 m away takes 7e319 s, never within a
	// window (the quadratic formula's discriminant underflows there: found by the soak).
	s.pos = pool_v3(1.0, dc + 3.4e-4, R);
	s.vel = pool_v3(0.0, -5e-324, 0.0);
	assert_true(isinf(pool_predict_cushion(&t, R, &s, pool_v3(0, 7.4e-322, 0), 1.0, &rail, &pocket)));
	s.vel = pool_v3(-0.5, -5e-324, 0.0);
	near_rel(pool_predict_cushion(&t, R, &s, pool_v3(0, 7.4e-322, 0), 10.0, &rail, &pocket), (1.0 - dc) / 0.5, 1e-12);
	assert_int_equal(rail, POOL_RAIL_WEST);
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
	// Leaving at 0.5 m/s: the west rail's line is (L - 2 dc) / 0.5 later, outside a 0.5 s window.
	s.vel = pool_v3(-0.5, 0.0, 0.0);
	assert_true(isinf(pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), 0.5, &rail, &pocket)));
	near_rel(pool_predict_cushion(&t, R, &s, pool_v3(0, 0, 0), 10.0, &rail, &pocket), (t.length - 2 * dc) / 0.5, 1e-12);
	assert_int_equal(rail, POOL_RAIL_WEST);
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

// Contacts at the edge of the window, where the cheap rejections (predict.c, contact.c) decide:
// a head-on pair and a ball rolling to a rail whose contact times are closed forms, with windows
// a part in 1e9 longer (the contact is found, at its time) and shorter (none).
static void test_window_edges(void **state) {
	(void)state;
	const pool_vec3 zero = pool_v3(0, 0, 0);
	const double d = 0.3, v = 0.8, a = 0.25; // the rear ball decelerates relative to the front one
	const double hit = (v - sqrt(v * v - 2.0 * a * (d - 2.0 * R))) / a;
	const pool_vec3 dirs[] = {pool_v3(1, 0, 0), pool_v3(sqrt(0.5), sqrt(0.5), 0), pool_v3(0.6, -0.8, 0)};
	for (size_t k = 0; k < sizeof dirs / sizeof dirs[0]; ++k) {
		const pool_vec3 n = dirs[k];
		const pool_vec3 dp = pool_v3_scale(n, -d), dv = pool_v3_scale(n, v), da = pool_v3_scale(n, -0.5 * a);
		near_rel(pool_predict_ball_ball(dp, dv, da, R, hit * (1.0 + 1e-9)), hit, 1e-12);
		assert_true(isinf(pool_predict_ball_ball(dp, dv, da, R, hit * (1.0 - 1e-9))));
		near_rel(pool_predict_ball_ball(dp, dv, zero, R, (d - 2.0 * R) / v * (1.0 + 1e-9)), (d - 2.0 * R) / v, 1e-12);
	}
	pool_table_def t = pool_default_table_def();
	const double h = t.cushion_height, dc = sqrt(R * R - (h - R) * (h - R)), gap = 0.2;
	pool_ball_state s = {0};
	s.pos = pool_v3(1.0, dc + gap, R);
	s.vel = pool_v3(0.1, -v, 0.0);
	const pool_vec3 acc = pool_v3(0.0, a, 0.0); // slowing on its way to the south rail
	const double to_rail = (v - sqrt(v * v - 2.0 * a * gap)) / a;
	pool_rail rail;
	pool_pocket pocket;
	near_rel(pool_predict_cushion(&t, R, &s, acc, to_rail * (1.0 + 1e-9), &rail, &pocket), to_rail, 1e-12);
	assert_int_equal(rail, POOL_RAIL_SOUTH);
	assert_true(isinf(pool_predict_cushion(&t, R, &s, acc, to_rail * (1.0 - 1e-9), &rail, &pocket)));
}

// Random pairs on the cloth against sampling their distance: whenever the sampled path comes
// within 2R (less a margin for the sampling), a contact is predicted inside the window, no later
// than the first such sample; whenever it stays outside (plus the margin), none is. Windows from
// a link step's millisecond to seconds, so every rejection's bound is exercised near its edge.
static void test_random_pairs_against_sampling(void **state) {
	(void)state;
	uint64_t x = 0x2545F4914F6CDD1Dull;
	int contacts = 0, misses = 0;
	for (int k = 0; k < 10000; ++k) {
		double u[7];
		for (int e = 0; e < 7; ++e) {
			x ^= x << 13, x ^= x >> 7, x ^= x << 17;
			u[e] = (double)(x >> 11) / 9007199254740992.0;
		}
		const double ang = 2.0 * PI * u[0], dist = 2.0 * R + 0.1 * u[1] * u[1];
		const pool_vec3 dp = pool_v3(dist * cos(ang), dist * sin(ang), 0.0);
		const double speed = 3.0 * u[2], heading = ang + PI + (u[3] - 0.5) * 1.2;
		const pool_vec3 dv = pool_v3(speed * cos(heading), speed * sin(heading), 0.0);
		const pool_vec3 da = pool_v3(2.0 * (u[4] - 0.5), 2.0 * (u[5] - 0.5), 0.0);
		const double T = 1e-3 * pow(1e3, u[6]);
		const double tau = pool_predict_ball_ball(dp, dv, da, R, T);
		// the closest sample and the first one inside
		const int samples = 4000;
		double closest = INFINITY, first_inside = INFINITY;
		for (int i = 0; i <= samples; ++i) {
			const double t = T * i / samples;
			const pool_vec3 p = pool_v3_add(pool_v3_add(dp, pool_v3_scale(dv, t)), pool_v3_scale(da, t * t));
			const double gap = pool_v3_len(p) - 2.0 * R;
			closest = fmin(closest, gap);
			if (gap < 0.0 && !isfinite(first_inside))
				first_inside = t;
		}
		// between samples the path moves at most (|dv| + 2 |da| T) T / samples
		const double margin = (speed + 2.0 * pool_v3_len(da) * T) * T / samples + 1e-12;
		if (closest < -margin) {
			if (!(tau <= first_inside))
				fail_msg("pair %d: the path enters 2R at %.9g s (window %.9g s), predicted %.9g", k, first_inside, T, tau);
			++contacts;
		} else if (closest > margin) {
			if (isfinite(tau))
				fail_msg("pair %d: the path stays %.3g m apart over %.9g s, predicted a contact at %.9g", k, closest, T,
				         tau);
			++misses;
		}
	}
	printf("random pairs: %d contacts, %d misses checked\n", contacts, misses);
	assert_true(contacts > 1000 && misses > 1000);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_linear_approach),
		cmocka_unit_test(test_decelerating),
		cmocka_unit_test(test_touching),
		cmocka_unit_test(test_touching_pushed_together),
		cmocka_unit_test(test_touching_slow_separation_pulled_back),
		cmocka_unit_test(test_touching_curvature),
		cmocka_unit_test(test_touching_parting_along_the_normal),
		cmocka_unit_test(test_touching_creep_turned_in_by_friction),
		cmocka_unit_test(test_touching_rounding_drift),
		cmocka_unit_test(test_cushion_slow_separation_pulled_back),
		cmocka_unit_test(test_cushion_and_pockets),
		cmocka_unit_test(test_cushion_touching_pushed_in),
		cmocka_unit_test(test_window_edges),
		cmocka_unit_test(test_random_pairs_against_sampling),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
