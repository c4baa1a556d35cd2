// Pockets "jaws" (docs/physics.md "Table geometry"): contact times against closed forms computed
// here from the WPA numbers (not from table_shape.c), the reflection off a facing by the cushion
// law, a ball rolling into a hole, the degree-8 jaw contact in flight against brute-force
// sampling of the distance, and the two airborne reproducers.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "handlers.h"
#include "poly_roots.h"
#include "pool/pool.h"
#include "predict.h"
#include "table_shape.h"
#include "vec3.h"

#define DEG (3.14159265358979323846 / 180.0)

static void near_abs(double got, double want, double tol, const char *what) {
	if (!(fabs(got - want) <= tol))
		fail_msg("%s: got %.17g, want %.17g (tolerance %g)", what, got, want, tol);
}

static pool_table_shape wpa_shape(void) {
	pool_table_shape sh;
	const pool_sim_def def = pool_default_sim_def();
	assert_int_equal(pool_table_shape_build(&def.table, def.params.ball_radius, &sh, NULL), POOL_OK);
	return sh;
}

// The south cushion's end at the side pocket s, east of the mouth, from the WPA numbers alone:
// virtual corner V = (L/2 + w/2, 0), nose along +x, the cushion below (y < 0); the facing leaves
// V at the cut angle through the cushion, direction (cos c, -sin c); the jaw of radius r is the
// circle tangent to both, its centre on the bisector at r / sin(c/2) from V.
typedef struct side_end {
	double vx, fx, fy, nx, ny, jx, jy, tangent;
} side_end;

static side_end south_side_east(const pool_table_def *t) {
	side_end e;
	const double c = t->side_cut_angle, r = t->side_jaw_radius;
	e.vx = 0.5 * t->length + 0.5 * t->side_mouth;
	e.fx = cos(c);
	e.fy = -sin(c);
	e.nx = -sin(c); // the facing's normal out of the cushion (towards the pocket's axis)
	e.ny = -cos(c);
	e.tangent = r / tan(0.5 * c);
	const double bx = 1.0 + e.fx, by = e.fy, bl = sqrt(bx * bx + by * by);
	e.jx = e.vx + bx / bl * r / sin(0.5 * c);
	e.jy = by / bl * r / sin(0.5 * c);
	return e;
}

// Rolling in a straight line u from p0 at speed v, decelerating at a: the time it has gone s.
static double time_to_go(double v, double a, double s) { return (v - sqrt(v * v - 2.0 * a * s)) / a; }

// A ball rolling straight at the side jaw's centre touches it when its centre is r + dc away.
static void test_jaw_contact_time_straight(void **state) {
	(void)state;
	const pool_sim_def def = pool_default_sim_def();
	const pool_table_shape sh = wpa_shape();
	const side_end e = south_side_east(&def.table);
	const double R = def.params.ball_radius, g = def.params.g, mu = def.params.mu_roll;
	const double dc = sqrt(R * R - (def.table.cushion_height - R) * (def.table.cushion_height - R));
	// From 0.3 m away, heading at the jaw's centre, inside the arc's span (the direction from the
	// centre to the ball lies between the nose's normal (0, 1) and the facing's).
	const double ang = 0.5 * (90.0 * DEG + atan2(e.ny, e.nx)), d0 = 0.3, v = 1.2, a = mu * g;
	const double ux = -cos(ang), uy = -sin(ang);
	pool_ball_state s = {0, POOL_MOTION_ROLLING, {e.jx - d0 * ux, e.jy - d0 * uy, R}, {v * ux, v * uy, 0}, {0, 0, 0}};
	pool_event_type kind;
	pool_site site;
	const double t = pool_predict_cushion_jaws(&sh, &s, pool_v3(-a * ux, -a * uy, 0.0), 10.0, &kind, &site);
	assert_int_equal(kind, POOL_EVENT_BALL_CUSHION);
	assert_int_equal(sh.parts[site.part].part, POOL_PART_JAW);
	assert_int_equal(site.pocket, POOL_POCKET_S);
	near_abs(t, time_to_go(v, a, d0 - (def.table.side_jaw_radius + dc)), 1e-12, "jaw contact time");
	// Offset by b from the centre line: contact when the centre is r + dc from the jaw's centre,
	// s^2 - 2 s d0 + d0^2 + b^2 = (r + dc)^2 along the line.
	const double b = 0.01, rc = def.table.side_jaw_radius + dc;
	const double px = -uy, py = ux; // perpendicular
	s.pos = pool_v3(e.jx - d0 * ux + b * px, e.jy - d0 * uy + b * py, R);
	const double t2 = pool_predict_cushion_jaws(&sh, &s, pool_v3(-a * ux, -a * uy, 0.0), 10.0, &kind, &site);
	near_abs(t2, time_to_go(v, a, d0 - sqrt(rc * rc - b * b)), 1e-12, "jaw contact time, offset");
}

// A ball rolling straight at the side pocket's east facing (perpendicular to it) meets it when
// its centre is dc from the facing's line; sliding on a parabola, when the quadratic distance
// reaches dc.
static void test_facing_contact_time(void **state) {
	(void)state;
	const pool_sim_def def = pool_default_sim_def();
	const pool_table_shape sh = wpa_shape();
	const side_end e = south_side_east(&def.table);
	const double R = def.params.ball_radius, h = def.table.cushion_height;
	const double dc = sqrt(R * R - (h - R) * (h - R));
	// A point of the facing a third of the way from the jaw to the hole, well inside its span.
	const double s_mid = e.tangent + 0.01;
	const double fx0 = e.vx + s_mid * e.fx, fy0 = s_mid * e.fy;
	// Start 35 mm out along the facing's normal (over the mouth, clear of the hole); roll back along it.
	const double d0 = 0.035, v = 0.8, a = def.params.mu_roll * def.params.g;
	pool_ball_state s = {0, POOL_MOTION_ROLLING, {fx0 + d0 * e.nx, fy0 + d0 * e.ny, R}, {-v * e.nx, -v * e.ny, 0}, {0, 0, 0}};
	pool_event_type kind;
	pool_site site;
	double t = pool_predict_cushion_jaws(&sh, &s, pool_v3(a * e.nx, a * e.ny, 0.0), 10.0, &kind, &site);
	assert_int_equal(kind, POOL_EVENT_BALL_CUSHION);
	assert_int_equal(sh.parts[site.part].part, POOL_PART_FACING);
	assert_int_equal(site.rail, POOL_RAIL_SOUTH);
	near_abs(t, time_to_go(v, a, d0 - dc), 1e-12, "facing contact time");
	// Sliding: the same start with a sideways acceleration along the facing (a parabola); the
	// distance to the line is still d0 - v t + (a_n / 2) t^2 with a_n the normal part.
	const double an = 1.0, at = 1.5; // m/s^2 along the normal (away) and along the facing
	const pool_vec3 acc = pool_v3(an * e.nx + at * e.fx, an * e.ny + at * e.fy, 0.0);
	t = pool_predict_cushion_jaws(&sh, &s, acc, 10.0, &kind, &site);
	const double want = (v - sqrt(v * v - 2.0 * an * (d0 - dc))) / an;
	near_abs(t, want, 1e-12, "facing contact time, sliding");
	assert_int_equal(sh.parts[site.part].part, POOL_PART_FACING);
}

// Rolling straight down the side pocket's axis: pocketed when the centre crosses the hole's
// edge, shelf + (hole centre to edge) from the mouth line.
static void test_rolling_into_hole(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	const double R = def.params.ball_radius, L = def.table.length;
	pool_sim *sim = make_sim(&def);
	const double y0 = 0.4, v = 1.0;
	pool_ball_state b = {0, POOL_MOTION_ROLLING, {0.5 * L, y0, R}, {0, -v, 0}, {v / R, 0, 0}};
	add_ball(sim, &b);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	int n;
	const pool_event *ev = pool_sim_events(sim, &n);
	assert_int_equal(n, 1);
	assert_int_equal(ev[0].type, POOL_EVENT_POCKET);
	assert_int_equal(ev[0].pocket, POOL_POCKET_S);
	// The hole's near edge is side_shelf behind the mouth line y = 0.
	const double a = def.params.mu_roll * def.params.g;
	near_abs(ev[0].time, time_to_go(v, a, y0 + def.table.side_shelf), 1e-12, "pocket time");
	pool_sim_destroy(sim);
}

// Petit's law off a facing, frictionless: in plan the velocity's part along the facing's normal
// n is reversed and scaled, v' = v - (1 + e) (v . n) cos^2(theta) n, theta the contact angle
// asin((h - R) / R) (the impulse is tilted; planar mode drops its vertical part).
static void test_facing_reflection(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	def.models.cushion = POOL_CUSHION_PETIT; // the law this closed form is of, whatever the default
	def.params.mu_cushion = 0.0;
	const pool_table_shape sh = wpa_shape();
	const side_end e = south_side_east(&def.table);
	const double R = def.params.ball_radius, h = def.table.cushion_height;
	const double dc = sqrt(R * R - (h - R) * (h - R)), theta = asin((h - R) / R);
	int k = -1;
	for (int i = 0; i < sh.n_parts; ++i)
		if (sh.parts[i].part == POOL_PART_FACING && sh.parts[i].pocket == POOL_POCKET_S && sh.parts[i].ax > 0.5 * def.table.length)
			k = i;
	assert_true(k >= 0);
	const double s_mid = e.tangent + 0.01;
	pool_ball_state s = {0, POOL_MOTION_SLIDING, {e.vx + s_mid * e.fx + dc * e.nx, s_mid * e.fy + dc * e.ny, R}, {0, 0, 0}, {0, 0, 0}};
	const double in = 30.0 * DEG; // incidence from the normal
	const double v = 1.0;
	const double tx = e.fx, ty = e.fy;
	s.vel = pool_v3(v * (-cos(in) * e.nx + sin(in) * tx), v * (-cos(in) * e.ny + sin(in) * ty), 0.0);
	pool_event_context ctx = {&def, POOL_RAIL_SOUTH, POOL_POCKET_S, &sh, k};
	pool_handle_ball_cushion(&ctx, POOL_EVENT_BALL_CUSHION, &s, 1);
	const double vn = -v * cos(in), c2 = cos(theta) * cos(theta);
	const double want_n = vn - (1.0 + def.params.e_cushion) * vn * c2, want_t = v * sin(in);
	near_abs(s.vel.x * e.nx + s.vel.y * e.ny, want_n, 1e-12, "normal speed after the facing");
	near_abs(s.vel.x * tx + s.vel.y * ty, want_t, 1e-12, "speed along the facing");
}

// The degree-8 contact of a flying ball with a jaw (a torus) against brute force: the distance
// from the centre to the jaw's arc, sampled every 1e-6 s, first reaching R; and the Bernstein
// search itself on polynomials with known roots.
static double arc_distance(const pool_nose_part *np, double h, pool_vec3 p) {
	double wx = p.x - np->ax, wy = p.y - np->ay;
	const double w = sqrt(wx * wx + wy * wy);
	const int inside = np->e0x * wy - np->e0y * wx >= 0.0 && wx * np->e1y - wy * np->e1x >= 0.0;
	double qx, qy;
	if (inside && w > 0.0) {
		qx = np->ax + np->length * wx / w;
		qy = np->ay + np->length * wy / w;
	} else {
		const double d0 = hypot(wx - np->length * np->e0x, wy - np->length * np->e0y);
		const double d1 = hypot(wx - np->length * np->e1x, wy - np->length * np->e1y);
		qx = np->ax + np->length * (d0 <= d1 ? np->e0x : np->e1x);
		qy = np->ay + np->length * (d0 <= d1 ? np->e0y : np->e1y);
	}
	return sqrt((p.x - qx) * (p.x - qx) + (p.y - qy) * (p.y - qy) + (p.z - h) * (p.z - h));
}

static void test_flight_jaw_brute_force(void **state) {
	(void)state;
	const pool_sim_def def = pool_default_sim_def();
	const pool_table_shape sh = wpa_shape();
	const double R = def.params.ball_radius, h = def.table.cushion_height, g = def.params.g;
	uint64_t seed = 12345;
	int contacts = 0, checked = 0;
	for (int trial = 0; trial < 3000; ++trial) {
		// A jaw at random, a ball flying towards a point near it from 10-20 cm away.
		seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
		const int k = 6 + (int)((seed >> 33) % 24);
		const pool_nose_part *np = &sh.parts[k];
		if (np->kind != POOL_NOSE_ARC)
			continue;
		double u[6];
		for (int i = 0; i < 6; ++i) {
			seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
			u[i] = (double)(seed >> 11) / 9007199254740992.0;
		}
		const double mid = atan2(np->e0y + np->e1y, np->e0x + np->e1x);
		const double aim = mid + (u[0] - 0.5) * 2.0;
		const double tx = np->ax + (np->length + R * (u[1] - 0.2)) * cos(aim), ty = np->ay + (np->length + R * (u[1] - 0.2)) * sin(aim);
		const double from = mid + (u[2] - 0.5) * 1.5, dist = 0.1 + 0.1 * u[3];
		pool_ball_state s = {0, POOL_MOTION_AIRBORNE, {tx + dist * cos(from), ty + dist * sin(from), R + 0.06 * u[4]}, {0, 0, 0}, {0, 0, 0}};
		const double speed = 1.0 + 3.0 * u[5], T = dist / speed * 2.0;
		s.vel = pool_v3((tx - s.pos.x) / dist * speed, (ty - s.pos.y) / dist * speed, 0.5 * g * T * (u[4] - 0.3));
		const pool_vec3 acc = pool_v3(0, 0, -g);
		if (arc_distance(np, h, s.pos) <= R)
			continue;
		// Brute force: the first sample within R, then bisection on the distance.
		double first = INFINITY;
		const int steps = (int)(T / 1e-6);
		for (int i = 1; i <= steps; ++i) {
			const double t = T * i / steps;
			const pool_vec3 p = pool_v3(s.pos.x + s.vel.x * t, s.pos.y + s.vel.y * t, s.pos.z + s.vel.z * t - 0.5 * g * t * t);
			if (arc_distance(np, h, p) < R) {
				double lo = T * (i - 1) / steps, hi = t;
				for (int j = 0; j < 60; ++j) {
					const double m = 0.5 * (lo + hi);
					const pool_vec3 q = pool_v3(s.pos.x + s.vel.x * m, s.pos.y + s.vel.y * m, s.pos.z + s.vel.z * m - 0.5 * g * m * m);
					if (arc_distance(np, h, q) < R)
						hi = m;
					else
						lo = m;
				}
				first = lo;
				break;
			}
		}
		// The library, on the jaw alone: its flight prediction over the same window, with the
		// other parts far (the first event it reports may be another part: compare only when it
		// is this jaw or none).
		pool_event_type kind;
		pool_site site;
		const double t = pool_predict_flight_jaws(&sh, &s, acc, T, &kind, &site);
		++checked;
		if (kind == POOL_EVENT_BALL_CUSHION && site.part != k)
			continue;
		if (isfinite(first) && first < t - 2e-6) {
			// A contact the library must not miss (nothing else came first).
				fail_msg("trial %d: brute force finds the jaw at t = %.9g, the library %s at %.9g", trial, first,
				         pool_event_type_name(kind), t);
		}
		if (kind == POOL_EVENT_BALL_CUSHION && site.part == k) {
			++contacts;
			near_abs(t, first, 2e-6, "jaw contact in flight");
		}
	}
	assert_true(contacts > 100 && checked > 1000);
}

// The Bernstein search finds the first falling root of products of known factors, close pairs
// included, and steps over rising roots and double roots (grazes).
static void test_poly_first_root(void **state) {
	(void)state;
	// (t - 0.3)(t - 0.30001)(t - 0.7)(t - 1.1)(t - 1.2)(t - 1.3)(t - 1.7)(t - 2): positive at 0.
	const double roots[8] = {0.3, 0.30001, 0.7, 1.1, 1.2, 1.3, 1.7, 2.0};
	double p[9] = {1.0}, tmp[9];
	int deg = 0;
	for (int k = 0; k < 8; ++k) {
		const double f[2] = {-roots[k], 1.0};
		pool_poly_mul(p, deg, f, 1, tmp);
		++deg;
		memcpy(p, tmp, sizeof(double) * (size_t)(deg + 1));
	}
	near_abs(pool_poly_first_falling_root(p, 8, 0.0, 3.0), 0.3, 1e-9, "first root (a pair 1e-5 apart: conditioning)");
	near_abs(pool_poly_first_falling_root(p, 8, 0.300005, 3.0), 0.7, 1e-12, "after a rising root");
	assert_true(isinf(pool_poly_first_falling_root(p, 8, 0.0, 0.29)));
	// A double root (a graze) is no crossing: (t - 0.5)^2 (t + 1) has none in [0, 1].
	const double graze[4] = {0.25, 0.75 - 1.0, 0.0, 1.0}; // (t^2 - t + 0.25)(t + 1) = t^3 - 0.75 t + 0.25
	assert_true(isinf(pool_poly_first_falling_root(graze, 3, 0.0, 1.0)));
}

// Issue 20, reproducer 1: a ball frozen to the west rail inside the NW corner's mouth, struck at
// 3 m/s along the rail, 10 degrees above it, airborne. It used to fly through the west nose once
// past the mouth. Now no sample of the shot is inside the nose curve (3D distance below R).
static double worst_inside(pool_sim *sim, const pool_sim_def *def) {
	pool_table_shape sh;
	assert_int_equal(pool_table_shape_build(&def->table, def->params.ball_radius, &sh, NULL), POOL_OK);
	const double end = pool_sim_end_time(sim);
	double worst = -INFINITY;
	for (int i = 0; i <= 20000; ++i) {
		pool_ball_state s[4];
		assert_int_equal(pool_sim_state_at(sim, end * i / 20000.0, s), POOL_OK);
		for (int b = 0; b < pool_sim_ball_count(sim); ++b)
			if (s[b].motion != POOL_MOTION_POCKETED && s[b].motion != POOL_MOTION_OFF_TABLE)
				worst = fmax(worst, def->params.ball_radius - pool_shape_distance(&sh, s[b].pos, NULL));
	}
	return worst;
}

static void test_reproducer_corner_jump(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	def.airborne = true;
	const double R = def.params.ball_radius, W = def.table.width;
	const double dc = pool_table_contact_distance(&def.table, R);
	pool_sim *sim = make_sim(&def);
	pool_ball_state b = {0, POOL_MOTION_STATIONARY, {dc, W - 0.06, R}, {0, 0, 0}, {0, 0, 0}};
	add_ball(sim, &b);
	pool_strike s = {3.0, -90.0 * DEG, 10.0 * DEG, 0.0, 0.0};
	assert_int_equal(pool_sim_strike(sim, 0, &s, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	const double worst = worst_inside(sim, &def);
	if (worst > POOL_TOUCH_TOLERANCE)
		fail_msg("the ball is %.3g m inside the cushion", worst);
	// It touches the west cushion (its jaw or nose) before 0.0764 s.
	int n, touched = 0;
	const pool_event *ev = pool_sim_events(sim, &n);
	for (int i = 0; i < n; ++i)
		touched |= ev[i].type == POOL_EVENT_BALL_CUSHION && ev[i].rail == POOL_RAIL_WEST && ev[i].time < 0.0764;
	assert_true(touched);
	pool_sim_destroy(sim);
}

// Issue 20, reproducer 2: a ball in flight crossing the north rail 12 mm outside the side mouth
// used to leave the table through the nose. It must touch the cushion (the jaw or the nose), and
// never be inside it; so must one crossing 20 mm outside, and one right over the mouth may fly
// into the pocket.
static void test_reproducer_side_flight(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	def.airborne = true;
	const double R = def.params.ball_radius, L = def.table.length, W = def.table.width;
	const double offsets[] = {0.012, 0.020, 0.005, -0.03};
	for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; ++k) {
		pool_sim *sim = make_sim(&def);
		// Rising towards the rail so it crosses the nose line near the nose's height.
		const double x = 0.5 * L + 0.5 * def.table.side_mouth + offsets[k];
		pool_ball_state b = {0, POOL_MOTION_AIRBORNE, {x, W - 0.2, R + 0.005}, {0, 2.6, 0.45}, {0, 0, 0}};
		add_ball(sim, &b);
		assert_int_equal(pool_sim_run(sim), POOL_OK);
		const double worst = worst_inside(sim, &def);
		if (worst > POOL_TOUCH_TOLERANCE)
			fail_msg("offset %g: the ball is %.3g m inside the cushion", offsets[k], worst);
		int n, touched = 0;
		const pool_event *ev = pool_sim_events(sim, &n);
		for (int i = 0; i < n; ++i)
			touched |= ev[i].type == POOL_EVENT_BALL_CUSHION;
		if (offsets[k] > 0.0)
			assert_true(touched);
		pool_sim_destroy(sim);
	}
}

#define TWO_PI 6.283185307179586476925

// A ball touching a jaw on the cloth and leaving it uniformly (no acceleration: a linked ball's
// segment) along the jaw's radius, slower than POOL_APPROACH_EPS: its distance from the jaw's
// axis has no curvature, it parts and never meets the jaw. The contact rule's curvature is the
// square of the velocity's part across the radius, never negative (pool_v3_across2; as
// v.v - (v.w)^2 / w.w it rounded to either sign, the pair contact of soak seed 23, cluster shot
// 168914). Every jaw of the table, 200 points across each one's span, speeds 1e-12 to 9e-10 m/s.
static void test_leaving_a_jaw_along_its_radius(void **state) {
	(void)state;
	const pool_table_shape sh = wpa_shape();
	const double R = pool_default_sim_def().params.ball_radius;
	int jaws = 0, tried = 0, contacts = 0;
	for (int k = 0; k < sh.n_parts; ++k) {
		const pool_nose_part *np = &sh.parts[k];
		if (np->kind != POOL_NOSE_ARC)
			continue;
		++jaws;
		const double a0 = atan2(np->e0y, np->e0x), a1 = atan2(np->e1y, np->e1x);
		const double span = fmod(a1 - a0 + 2.0 * TWO_PI, TWO_PI);
		for (int i = 1; i < 200; ++i) {
			const double a = a0 + span * i / 200.0, speed = 1e-12 * (1 + (i * 37) % 900);
			const double c = cos(a), sn = sin(a), d = np->length + sh.dc;
			pool_ball_state s;
			memset(&s, 0, sizeof s);
			s.motion = POOL_MOTION_LINKED;
			s.pos = pool_v3(np->ax + d * c, np->ay + d * sn, R);
			s.vel = pool_v3(speed * c, speed * sn, 0.0);
			if (!pool_shape_in_span(&sh, k, s.pos))
				continue;
			++tried;
			pool_event_type kind;
			pool_site site;
			const double t = pool_predict_cushion_jaws(&sh, &s, pool_v3(0, 0, 0), 1e-3, &kind, &site);
			contacts += t < INFINITY && kind == POOL_EVENT_BALL_CUSHION && site.part == k;
		}
	}
	print_message("leaving a jaw along its radius: %d jaws, %d positions, %d contacts\n", jaws, tried, contacts);
	assert_true(jaws == 12 && tried > 1000);
	assert_int_equal(contacts, 0);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_jaw_contact_time_straight), cmocka_unit_test(test_facing_contact_time),
		cmocka_unit_test(test_rolling_into_hole),        cmocka_unit_test(test_facing_reflection),
		cmocka_unit_test(test_flight_jaw_brute_force),   cmocka_unit_test(test_poly_first_root),
		cmocka_unit_test(test_reproducer_corner_jump),   cmocka_unit_test(test_reproducer_side_flight),
		cmocka_unit_test(test_leaving_a_jaw_along_its_radius),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
