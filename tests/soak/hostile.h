// Hostile random shots and their invariant checks, shared by tests/unit/test_random_shots.c and
// the soak program tests/soak/soak.c (header-only: both include it, nothing else links it).
//
// Generator. Every shot is a pure function of (seed, index, class): hs_make() seeds its own
// splitmix64 stream from the three, so a failing shot is regenerated exactly by
// `soak --seed S --shot I --class C`, and hs_print_scenario() writes it as a pool-sim
// libpool-scenario/1 file that replays bit for bit (numbers printed with 17 digits, angles drawn
// in degrees and converted with pool-sim's own factor).
//
// Classes (hs_class_names):
//   layout         racks (frozen or with a gap) and random layouts, the random-shot test's
//                  shots with harsher strikes (up to 12 m/s, elevation up to 89 deg)
//   rail_struck    the cue ball frozen to a rail (exactly at the contact distance, or within
//                  +-1e-9 m of it) struck along, into or away from the rail, massé included
//   rail_drift     balls frozen to rails that leave or approach them at +-1e-10..1e-6 m/s (or
//                  exactly 0, or 1e-16) with spin whose cloth friction drives them back
//   pair           touching pairs (distance 2R exactly or within +-1e-9 m, along the axes or any
//                  direction) separating or approaching at tiny speeds, spin driving them together
//   cluster        chains, triangles, hexagons and random blobs of touching balls, some at a rail,
//                  some of their balls drifting with tiny speeds and pushing spin
//   masse          random layouts struck at every elevation 0..89 deg with tip offsets up to the
//                  allowed maximum (a^2 + b^2 -> R^2) and aims at exact multiples of 90/45/30 deg
//   tiny_table     tables just over 2R (down to 2R (1 + 1e-12)), cushion heights from ~0 to ~2R,
//                  pocket mouths 0 or up to the allowed maximum, balls frozen to both rails
//   extreme_params any of the layouts above with mu_slide, mu_roll, mu_spin, mu_ball, mu_cushion
//                  = 0 (or large), e_ball, e_cushion = 0 or 1, and cushion height extremes
//   nose           full-size tables (7, 8, 9 ft) with noses from ~0 to ~2R high (the nose at and
//                  just above the ball's centre, and just below its top), ordinary cloth, the
//                  layouts above
//   mouth          the nose class's tables with one or two balls moved onto a pocket mouth's
//                  contact lines: a corner's two lines at once, along a corner's line inside its
//                  mouth or at its edge, a side mouth inside or at its edges, each exactly on the
//                  line or within +-1e-15..1e-9 m of it (or 1e-6, 1e-4 m inside), at rest or
//                  moving at 1e-6..3 m/s any way (soak seed 1, nose shot 5385 was such a ball)
// A third of every class's shots are airborne (options.airborne), and a third of those throw
// balls into the air as well. Half the shots of every class but tiny_table are on real pockets
// (pockets "jaws": the presets' facings, jaws and holes), the others on the thesis model's lines. Tables with a nose at or below the ball's centre, or above 1.9 R,
// are refused at validation (docs/physics.md: the nose would push the ball up and over the
// cushion, or wedge it against the cloth): such shots are counted as refused, not run.
// Strikes: speed 0.001..12 m/s (12 exactly too), phi at exact multiples of 90 deg (and 45, 30,
// aimed at a ball, or any), theta 0..89.999 deg, tip offset 0, random, or within 1e-12 R of R.
//
// Checks (hs_check, tolerances in the HS_TOL_* macros):
//   api         pool_sim_add_ball / strike / run succeed and every state stays finite
//   overlap     no two balls closer than 2R - POOL_TOUCH_TOLERANCE, sampled at every event time
//               and densely between events (at least HS_SAMPLES_MIN points per interval, more
//               when balls are fast: a relative displacement of at most R/4 between samples)
//   rail        no ball centre outside the cushion contact lines (dc = sqrt(R^2 - (h - R)^2)
//               from the nose lines) by more than POOL_TOUCH_TOLERANCE, same samples; in flight,
//               no ball closer than R to a nose (its line outside the pocket mouths, ending at
//               their edges), none past the
//               table's edge (it leaves: off_table), none below the cloth; on the cloth (its
//               motion) none past a mouth's contact line; a flight across a mouth's contact line
//               crosses it above the nose (below, the ball falls into the pocket there)
//   pocket      a pocket event happens inside the lines, on a rail line (HS_TOL_POCKET_LINE) and
//               in the mouth of the pocket it names (in flight: over the mouth, at or past the
//               contact line, inside the table's edge)
//   jaws        with pockets "jaws" the rail check is against the nose curve (table_shape.h): no
//               ball nearer it than R in 3D (so on the cloth nearer no part than d_c), below the
//               cloth, or on the cloth over a hole; a cushion event's gap and closing speed are
//               the nose curve's; a pocket event is at the named pocket's hole edge (a ball landing
//               from the air, or a linked one, anywhere over it), below the nose; off_table where
//               the ball crosses the table's edge or the nose curve above the nose, leaves a hole's
//               circle, or lands off the cloth
//   energy      energy (kinetic + potential above the cloth) never increases across an event
//               other than a LINK step (beyond HS_TOL_ENERGY_REL of it, HS_TOL_ENERGY_REL_CHANGE
//               for state changes, plus HS_TOL_ENERGY_ABS, and for slide_roll the energy of the
//               slip left by t's rounding; link_begin and link_end plus
//               HS_TOL_LINK_ABS)
//   link        every LINK step's balls hold at most HS_TOL_LINK_ABS more energy where the step
//               ends (its planned end, or where an event from outside cuts it) than entering it
//               (link_energy.h)
//   contact     an impulse acts on bodies in contact (gap <= POOL_TOUCH_TOLERANCE) that are not
//               separating faster than POOL_APPROACH_EPS (the library's own threshold, plus
//               HS_TOL_SPEED_*), and a ball-ball event never makes the pair approach faster
//   momentum    ball-ball events conserve momentum (HS_TOL_MOMENTUM_REL of the speeds plus
//               2 POOL_REST_EPS, the speed below which the library zeroes a ball at rest)
//   rest        a shot that stops at rest is at rest: every state at t + HS_REST_FAR equals the
//               state at the end (equal values; a ball spinning in place without friction is
//               at rest)
//   state_at    the checker's own closed-form tracking of the event history equals
//               pool_sim_state_at (equal values) (at up to HS_STATE_AT_CHECKS sample times)
//   determinism a second run of the same shot gives the same events and states, bit for bit
//   rest        (also) no ball in flight, and every ball on the cloth but a sleeping heap's, when a
//               shot stops at rest
// Shots cut by max_events or max_time are counted, not failed; their checks up to the cut apply.
// Every class must end with no failed shot (shots refused at validation are counted apart).
#ifndef POOL_TESTS_HOSTILE_H
#define POOL_TESTS_HOSTILE_H

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "link_energy.h"
#include "motion.h"
#include "predict.h" // POOL_APPROACH_EPS
#include "table_shape.h"
#ifndef POOL_APPROACH_EPS
#define POOL_APPROACH_EPS 1e-9
#endif
#include "pool/pool.h"

#define HS_MAX_BALLS 16
#define HS_PI 3.14159265358979323846
#define HS_DEG (HS_PI / 180.0) // pool-sim's degree factor (tools/common/scenario.c)

#define HS_TOL_LENGTH (POOL_TOUCH_TOLERANCE + 1e-12) // m: overlap, outside the lines, contact gap
                                                  // (the touch tolerance, plus rounding of a ball
                                                  // that starts at it)
#define HS_TOL_POCKET_LINE 1e-7            // m: a pocketed ball's distance from its rail line
#define HS_TOL_ENERGY_REL 1e-12            // of the energy before the event or at the segments' start
#define HS_TOL_ENERGY_REL_CHANGE 1e-10     // the same for slide_roll, roll_stop, spin_stop (the snap
                                           // onto rolling after a long slide: ~3e-12 seen)
#define HS_SNAP_ULPS 4.0                   // ulps of t by which a slide_roll may be placed off its root
                                           // (the energy of that slip: see the energy check)
#define HS_TOL_ENERGY_ABS 1e-18            // J (a 0.17 kg ball at 3.4e-9 m/s)
#define HS_TOL_ENERGY_ABS_AIR 1e-9         // J, with airborne motion: a ball put back onto the cloth
                                           // (settling, z = R) from the picometres under it that
                                           // rounding leaves, m g times that depth
#define HS_TOL_LINK_LENGTH 1e-6           // m, interpenetration inside a LINK cluster (issue 11)
#define HS_TOL_LINK_ABS LE_TOLERANCE       // J, Lemke's residual on impulses of a few mN s
#define HS_TOL_MOMENTUM_REL 1e-12          // of |v1| + |v2|
#define HS_TOL_SPEED_REL 1e-12             // of |v1| + |v2|: "not separating" is separating at
                                           // most POOL_APPROACH_EPS plus this
#define HS_TOL_SPEED_ABS POOL_REST_EPS      // m/s (the library's zero speed)
#define HS_REST_FAR 1e4                    // s after the end of a shot at rest
#define HS_SAMPLES_MIN 3                   // samples inside every interval between events
#define HS_SAMPLES_MAX 256                 // per interval
#define HS_SAMPLE_BUDGET 20000             // per shot; past it, HS_SAMPLES_MIN per interval
#define HS_STATE_AT_CHECKS 24              // sample times compared with pool_sim_state_at
#define HS_MAX_EVENTS 20000                // options.max_events of generated shots
#define HS_MAX_TIME 60.0                   // options.max_time of generated shots
#define HS_AIRBORNE_SHARE (1.0 / 3.0)      // shots with airborne motion, in every class
#define HS_TOL_POCKET_EDGE 1e-9            // m: a pocketed ball in flight inside the table's edge

typedef enum hs_class {
	HS_LAYOUT,
	HS_RAIL_STRUCK,
	HS_RAIL_DRIFT,
	HS_PAIR,
	HS_CLUSTER,
	HS_MASSE,
	HS_TINY_TABLE,
	HS_EXTREME_PARAMS,
	HS_NOSE,
	HS_MOUTH,
	HS_CLASS_COUNT
} hs_class;
static const char *const hs_class_names[HS_CLASS_COUNT] = {
	"layout", "rail_struck", "rail_drift", "pair", "cluster", "masse", "tiny_table", "extreme_params", "nose", "mouth"};

typedef enum hs_check_kind {
	HS_CK_API,
	HS_CK_OVERLAP,
	HS_CK_RAIL,
	HS_CK_POCKET,
	HS_CK_ENERGY,
	HS_CK_FLOOR,
	HS_CK_CONTACT,
	HS_CK_MOMENTUM,
	HS_CK_REST,
	HS_CK_STATE_AT,
	HS_CK_DETERMINISM,
	HS_CK_COUNT
} hs_check_kind;
static const char *const hs_check_names[HS_CK_COUNT] = {"api",     "overlap",  "rail", "pocket",   "energy",     "link",
                                                        "contact", "momentum", "rest", "state_at", "determinism"};

static inline int hs_class_from_name(const char *name) {
	for (int c = 0; c < HS_CLASS_COUNT; ++c)
		if (strcmp(name, hs_class_names[c]) == 0)
			return c;
	return -1;
}

// ---------------------------------------------------------------------------------------------
// Random numbers: splitmix64, one stream per shot.
typedef struct hs_rng {
	uint64_t s;
} hs_rng;

static inline uint64_t hs_next(hs_rng *r) {
	uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}
static inline double hs_u(hs_rng *r) { return (double)(hs_next(r) >> 11) * (1.0 / 9007199254740992.0); }
static inline double hs_range(hs_rng *r, double lo, double hi) { return lo + (hi - lo) * hs_u(r); }
static inline int hs_int(hs_rng *r, int n) { return (int)(hs_u(r) * n); }
static inline int hs_chance(hs_rng *r, double p) { return hs_u(r) < p; }
static inline double hs_logu(hs_rng *r, double lo, double hi) { return lo * pow(hi / lo, hs_u(r)); }
static inline double hs_sign(hs_rng *r) { return hs_chance(r, 0.5) ? 1.0 : -1.0; }

// A tiny signed speed: 0, rounding level (1e-16, 2^-52), or +-1e-10..1e-6 m/s.
static inline double hs_tiny_speed(hs_rng *r) {
	switch (hs_int(r, 8)) {
	case 0: return 0.0;
	case 1: return hs_sign(r) * 1e-16;
	case 2: return hs_sign(r) * ldexp(1.0, -52 + hs_int(r, 20));
	case 3: return hs_sign(r) * 1e-10;
	default: return hs_sign(r) * hs_logu(r, 1e-10, 1e-6);
	}
}

// Offset from an exact contact, m: 0 (exact), +-1e-9 (the touch tolerance), or within it;
// positive is a gap, negative an overlap / a ball outside its contact line.
static inline double hs_contact_offset(hs_rng *r) {
	switch (hs_int(r, 8)) {
	case 0:
	case 1:
	case 2: return 0.0;
	case 3: return -POOL_TOUCH_TOLERANCE;
	case 4: return POOL_TOUCH_TOLERANCE;
	case 5: return hs_sign(r) * hs_logu(r, 1e-16, 1e-9);
	default: return hs_range(r, -POOL_TOUCH_TOLERANCE, POOL_TOUCH_TOLERANCE);
	}
}

// ---------------------------------------------------------------------------------------------
// Shots.
typedef struct hs_shot {
	int cls;
	uint64_t seed;
	long index;
	pool_sim_def def;
	pool_ball_state balls[HS_MAX_BALLS];
	int n;
	int cue;                                    // index of the struck ball
	double speed, phi_deg, theta_deg, a, b;     // strike as written to the scenario file
	pool_strike strike;                         // the same in radians
	const char *origin;                         // how to reproduce a shot hs_make did not make (NULL: soak's)
	double corner_cut_deg, side_cut_deg;        // pockets "jaws": the cut angles as written to the scenario
} hs_shot;

static inline double hs_dc(const pool_sim_def *def) {
	return pool_table_contact_distance(&def->table, def->params.ball_radius); // the library's, bit for bit
}

// Would pool_sim_add_ball accept a ball at pos (same expressions as sim.c)?
static inline int hs_fits(const hs_shot *s, pool_vec3 pos) {
	const double R = s->def.params.ball_radius, L = s->def.table.length, W = s->def.table.width;
	const double dc = hs_dc(&s->def), tol = POOL_TOUCH_TOLERANCE;
	if (!(pos.x >= dc - tol && pos.x <= L - dc + tol && pos.y >= dc - tol && pos.y <= W - dc + tol))
		return 0;
	if (pool_table_hole_at(&s->def.table, pos.x, pos.y) != POOL_POCKET_NONE) // jaws: a hole reaching inside the lines
		return 0;
	if (pos.z > R) { // in the air: clear of the noses too (pool_sim_add_ball refuses a ball inside one)
		const double h = s->def.table.cushion_height;
		for (int rail = 0; rail < 4; ++rail) {
			const double in = rail == POOL_RAIL_SOUTH ? pos.y : rail == POOL_RAIL_NORTH ? W - pos.y : rail == POOL_RAIL_WEST ? pos.x : L - pos.x;
			if (sqrt(in * in + (pos.z - h) * (pos.z - h)) < R + 1e-6)
				return 0;
		}
	}
	for (int j = 0; j < s->n; ++j) {
		pool_vec3 d = {pos.x - s->balls[j].pos.x, pos.y - s->balls[j].pos.y, pos.z - s->balls[j].pos.z};
		if (sqrt(d.x * d.x + d.y * d.y + d.z * d.z) < 2.0 * R - tol)
			return 0;
	}
	return 1;
}

static inline int hs_add(hs_shot *s, pool_vec3 pos) {
	if (s->n >= HS_MAX_BALLS || !hs_fits(s, pos))
		return -1;
	pool_ball_state *b = &s->balls[s->n];
	memset(b, 0, sizeof *b);
	b->id = s->n;
	b->pos = pos;
	b->pos.z = s->def.params.ball_radius;
	return s->n++;
}

static inline pool_vec3 hs_xy(double x, double y, double R) {
	pool_vec3 v = {x, y, R};
	return v;
}

// A random position inside the contact lines (at least `margin` m inside them).
static inline pool_vec3 hs_random_pos(const hs_shot *s, hs_rng *r, double margin) {
	const double dc = hs_dc(&s->def), L = s->def.table.length, W = s->def.table.width;
	double lo_x = dc + margin, hi_x = L - dc - margin, lo_y = dc + margin, hi_y = W - dc - margin;
	if (hi_x < lo_x)
		lo_x = hi_x = 0.5 * L;
	if (hi_y < lo_y)
		lo_y = hi_y = 0.5 * W;
	return hs_xy(hs_range(r, lo_x, hi_x), hs_range(r, lo_y, hi_y), s->def.params.ball_radius);
}

static inline int hs_add_random(hs_shot *s, hs_rng *r, double margin) {
	for (int tries = 0; tries < 200; ++tries) {
		int i = hs_add(s, hs_random_pos(s, r, margin));
		if (i >= 0)
			return i;
	}
	return -1;
}

// Sets ball i's spin so that its slip has the given direction and magnitude (u = v + R k x w),
// keeping its z-spin; zero slip makes a rolling (or resting) ball.
static inline void hs_set_slip(hs_shot *s, int i, double ux, double uy) {
	const double R = s->def.params.ball_radius;
	pool_ball_state *b = &s->balls[i];
	b->omega.x = (uy - b->vel.y) / R;
	b->omega.y = -(ux - b->vel.x) / R;
}

// Spin whose cloth friction pushes ball i along (qx, qy) (unit): slip mostly against q, with a
// sideways part; magnitude 1e-6..5 m/s. With probability `away` it pushes the other way instead.
static inline void hs_push_spin(hs_shot *s, hs_rng *r, int i, double qx, double qy, double away) {
	double q = hs_chance(r, away) ? -1.0 : 1.0;
	double mag = hs_chance(r, 0.2) ? hs_logu(r, 1e-6, 1e-2) : hs_logu(r, 1e-2, 5.0);
	double side = hs_chance(r, 0.4) ? 0.0 : hs_range(r, -3.0, 3.0); // up to ~70 deg off the normal
	double ux = -q * qx + side * -qy, uy = -q * qy + side * qx;
	double len = sqrt(ux * ux + uy * uy);
	hs_set_slip(s, i, mag * ux / len, mag * uy / len);
	if (hs_chance(r, 0.3))
		s->balls[i].omega.z = hs_range(r, -60.0, 60.0);
}

// ---------------------------------------------------------------------------------------------
// Strikes.
static inline double hs_aim_deg(hs_rng *r, const hs_shot *s) {
	switch (hs_int(r, 10)) {
	case 0:
	case 1:
	case 2:
	case 3: return 90.0 * (hs_int(r, 6) - 1); // -90, 0, 90, 180, 270, 360
	case 4: return 45.0 * hs_int(r, 8);
	case 5: return 30.0 * hs_int(r, 12);
	case 6:
		if (s->n > 1) { // through the centre of another ball
			int j = hs_int(r, s->n);
			if (j != s->cue) {
				double dx = s->balls[j].pos.x - s->balls[s->cue].pos.x, dy = s->balls[j].pos.y - s->balls[s->cue].pos.y;
				return atan2(dy, dx) / HS_DEG;
			}
		}
		return hs_range(r, 0.0, 360.0);
	default: return hs_range(r, 0.0, 360.0);
	}
}

static inline void hs_finish_strike(hs_shot *s) {
	const double R = s->def.params.ball_radius;
	while (!(R * R - s->a * s->a - s->b * s->b > 0.0)) { // the library's test (strike.c)
		s->a *= 1.0 - 1e-12;
		s->b *= 1.0 - 1e-12;
	}
	s->strike.speed = s->speed;
	s->strike.phi = s->phi_deg * HS_DEG;
	s->strike.theta = s->theta_deg * HS_DEG;
	s->strike.a = s->a;
	s->strike.b = s->b;
}

// A hostile strike of ball s->cue; phi_deg < -1000 means "draw the aim".
static inline void hs_random_strike(hs_shot *s, hs_rng *r, double phi_deg) {
	const double R = s->def.params.ball_radius;
	switch (hs_int(r, 10)) {
	case 0:
	case 1: s->speed = hs_logu(r, 1e-3, 0.1); break;
	case 2:
	case 3: s->speed = hs_range(r, 8.0, 12.0); break;
	case 4: s->speed = 12.0; break;
	default: s->speed = hs_range(r, 0.05, 8.0); break;
	}
	s->phi_deg = phi_deg < -1000.0 ? hs_aim_deg(r, s) : phi_deg;
	switch (hs_int(r, 8)) {
	case 0:
	case 1: s->theta_deg = 0.0; break;
	case 2:
	case 3: s->theta_deg = (double)hs_int(r, 90); break;
	case 4: s->theta_deg = hs_chance(r, 0.5) ? 89.0 : hs_range(r, 85.0, 89.999); break;
	default: s->theta_deg = hs_range(r, 0.0, 89.999); break;
	}
	double rad;
	switch (hs_int(r, 8)) {
	case 0: rad = 0.0; break;
	case 1:
	case 2: rad = R * sqrt(hs_u(r)) * 0.95; break;
	case 3: rad = R * (1.0 - 1e-12); break;
	default: rad = R * (1.0 - hs_logu(r, 1e-12, 0.2)); break;
	}
	double ang = hs_chance(r, 0.4) ? 0.5 * HS_PI * hs_int(r, 4) : hs_range(r, 0.0, 2.0 * HS_PI);
	s->a = rad * cos(ang);
	s->b = rad * sin(ang);
	if (hs_chance(r, 0.4)) { // exact axes: pure side or pure top/back
		if (fabs(s->a) < fabs(s->b))
			s->a = 0.0;
		else
			s->b = 0.0;
	}
	hs_finish_strike(s);
}

// ---------------------------------------------------------------------------------------------
// Layout pieces.

// A ball frozen to `rail` (pool_rail order) at coordinate `along`; offset > 0 is a gap.
static inline pool_vec3 hs_rail_pos(const hs_shot *s, int rail, double along, double offset) {
	const double dc = hs_dc(&s->def), L = s->def.table.length, W = s->def.table.width, R = s->def.params.ball_radius;
	switch (rail) {
	case POOL_RAIL_SOUTH: return hs_xy(along, dc + offset, R);
	case POOL_RAIL_NORTH: return hs_xy(along, W - dc - offset, R);
	case POOL_RAIL_WEST: return hs_xy(dc + offset, along, R);
	default: return hs_xy(L - dc - offset, along, R);
	}
}

// Outward unit normal of a rail (from the table towards the rail).
static inline void hs_rail_out(int rail, double *ox, double *oy) {
	*ox = rail == POOL_RAIL_WEST ? -1.0 : rail == POOL_RAIL_EAST ? 1.0 : 0.0;
	*oy = rail == POOL_RAIL_SOUTH ? -1.0 : rail == POOL_RAIL_NORTH ? 1.0 : 0.0;
}

static inline double hs_rail_along(const hs_shot *s, hs_rng *r, int rail) {
	const double dc = hs_dc(&s->def), L = s->def.table.length, W = s->def.table.width;
	const double len = rail <= POOL_RAIL_NORTH ? L : W;
	const double corner = s->def.table.corner_mouth / sqrt(2.0);
	switch (hs_int(r, 8)) {
	case 0: return hs_range(r, dc, len - dc);           // anywhere, pocket mouths included
	case 1: return hs_chance(r, 0.5) ? dc : len - dc;   // in the corner
	case 2: return 0.5 * len;                           // a side pocket's centre (long rails)
	default: {                                          // between the pockets
		double lo = fmax(dc, corner + 2e-3), hi = fmin(len - dc, len - corner - 2e-3);
		return hi > lo ? hs_range(r, lo, hi) : 0.5 * len;
	}
	}
}

// Ball i (not the cue) drifts: tiny normal speed off its contact along (nx, ny) (unit, pointing
// away from the contact), an optional tangential speed, and spin pushing it back.
static inline void hs_drift(hs_shot *s, hs_rng *r, int i, double nx, double ny) {
	pool_ball_state *b = &s->balls[i];
	double vn = hs_tiny_speed(r);
	double vt = 0.0;
	switch (hs_int(r, 4)) {
	case 0: vt = hs_tiny_speed(r); break;
	case 1: vt = hs_range(r, -3.0, 3.0); break;
	default: break;
	}
	b->vel.x = vn * nx - vt * ny;
	b->vel.y = vn * ny + vt * nx;
	if (hs_chance(r, 0.85))
		hs_push_spin(s, r, i, -nx, -ny, 0.15);
	else if (hs_chance(r, 0.5))
		hs_set_slip(s, i, 0.0, 0.0); // rolling
}

static inline int hs_add_rail_ball(hs_shot *s, hs_rng *r, int *rail_out) {
	for (int tries = 0; tries < 50; ++tries) {
		int rail = hs_int(r, 4);
		int i = hs_add(s, hs_rail_pos(s, rail, hs_rail_along(s, r, rail), hs_contact_offset(r)));
		if (i >= 0) {
			if (rail_out)
				*rail_out = rail;
			return i;
		}
	}
	return -1;
}

static inline double hs_pair_angle(hs_rng *r) {
	switch (hs_int(r, 6)) {
	case 0:
	case 1: return 0.5 * HS_PI * hs_int(r, 4);   // along the axes: exact positions
	case 2: return HS_PI / 6.0 * hs_int(r, 12);  // rack directions: cos/sin rounding
	default: return hs_range(r, 0.0, 2.0 * HS_PI);
	}
}

// A ball touching ball j in direction ang (distance 2R + offset); -1 when it does not fit.
static inline int hs_add_touching(hs_shot *s, hs_rng *r, int j, double ang) {
	const double R = s->def.params.ball_radius;
	const double d = 2.0 * R + hs_contact_offset(r);
	double cx = cos(ang), cy = sin(ang);
	if (fmod(ang, 0.5 * HS_PI) == 0.0) { // exact axis directions
		int k = (int)(ang / (0.5 * HS_PI)) & 3;
		cx = k == 0 ? 1.0 : k == 2 ? -1.0 : 0.0;
		cy = k == 1 ? 1.0 : k == 3 ? -1.0 : 0.0;
	}
	pool_vec3 p = hs_xy(s->balls[j].pos.x + d * cx, s->balls[j].pos.y + d * cy, R);
	int i = hs_add(s, p);
	if (i < 0) { // rounding made it overlap by a hair more than the tolerance: exact 2R
		p = hs_xy(s->balls[j].pos.x + 2.0 * R * cx, s->balls[j].pos.y + 2.0 * R * cy, R);
		i = hs_add(s, p);
	}
	return i;
}

// Unit vector from ball j to ball i.
static inline void hs_dir(const hs_shot *s, int i, int j, double *nx, double *ny) {
	double dx = s->balls[i].pos.x - s->balls[j].pos.x, dy = s->balls[i].pos.y - s->balls[j].pos.y;
	double len = sqrt(dx * dx + dy * dy);
	*nx = dx / len;
	*ny = dy / len;
}

// The struck ball: index c, at rest (its z-spin may stay).
static inline void hs_make_cue(hs_shot *s, int c) {
	s->cue = c;
	s->balls[c].vel = hs_xy(0, 0, 0);
	s->balls[c].omega.x = s->balls[c].omega.y = 0.0;
}

// ---------------------------------------------------------------------------------------------
// Classes.

static inline void hs_gen_layout(hs_shot *s, hs_rng *r) {
	const double R = s->def.params.ball_radius;
	if (hs_chance(r, 0.6)) {
		double gap = hs_chance(r, 0.5) ? 0.0 : hs_range(r, 0.0, 2e-3);
		pool_ball_state rack[16];
		int n = pool_rack(hs_chance(r, 0.7) ? POOL_RACK_8BALL : POOL_RACK_9BALL, &s->def.table, &s->def.params, gap, rack, 16);
		for (int i = 1; i < n; ++i) // the object balls, then the cue ball on its spot or anywhere
			hs_add(s, rack[i].pos);
		int c = hs_chance(r, 0.5) ? hs_add_random(s, r, 0.0) : -1;
		if (c < 0)
			c = hs_add(s, rack[0].pos);
		hs_make_cue(s, c < 0 ? 0 : c);
		if (hs_chance(r, 0.3)) {
			pool_strike k = pool_break_strike(hs_range(r, 0.5, 12.0));
			double dx = rack[1].pos.x - s->balls[s->cue].pos.x, dy = rack[1].pos.y - s->balls[s->cue].pos.y;
			s->speed = k.speed;
			s->phi_deg = hs_chance(r, 0.5) ? k.phi / HS_DEG : atan2(dy, dx) / HS_DEG; // at the apex
			s->theta_deg = k.theta / HS_DEG;
			s->a = k.a;
			s->b = k.b;
			hs_finish_strike(s);
			return;
		}
	} else {
		int want = 2 + hs_int(r, 15);
		for (int k = 0; k < want; ++k)
			hs_add_random(s, r, hs_chance(r, 0.2) ? 0.0 : R);
		hs_make_cue(s, 0);
	}
	hs_random_strike(s, r, -2000.0);
}

static inline void hs_gen_rail_struck(hs_shot *s, hs_rng *r) {
	int rail;
	int c = hs_add_rail_ball(s, r, &rail);
	if (c < 0)
		c = hs_add_random(s, r, 0.0);
	hs_make_cue(s, c);
	if (hs_chance(r, 0.3))
		s->balls[c].omega.z = hs_range(r, -60.0, 60.0);
	int others = hs_int(r, 4);
	for (int k = 0; k < others; ++k) {
		int rr = -1, i = hs_chance(r, 0.5) ? hs_add_rail_ball(s, r, &rr) : hs_add_random(s, r, 0.0);
		if (i >= 0 && rr >= 0 && hs_chance(r, 0.5)) {
			double ox, oy;
			hs_rail_out(rr, &ox, &oy);
			hs_drift(s, r, i, -ox, -oy);
		}
	}
	// Aim along the rail (either way), into it, away from it, a few degrees off, or anywhere.
	double base = rail == POOL_RAIL_SOUTH ? 0.0 : rail == POOL_RAIL_NORTH ? 180.0 : rail == POOL_RAIL_WEST ? 90.0 : 270.0;
	double phi;
	switch (hs_int(r, 8)) {
	case 0:
	case 1: phi = base; break;                   // along
	case 2: phi = base + 180.0; break;           // along, the other way
	case 3: phi = base + 90.0; break;            // away from the rail
	case 4: phi = base - 90.0; break;            // into the rail
	case 5: phi = base + hs_sign(r) * hs_logu(r, 1e-6, 10.0) + (hs_chance(r, 0.5) ? 180.0 : 0.0); break;
	default: phi = -2000.0; break;
	}
	hs_random_strike(s, r, phi);
}

static inline void hs_gen_rail_drift(hs_shot *s, hs_rng *r) {
	int k = 1 + hs_int(r, 4);
	for (int t = 0; t < k; ++t) {
		int rail, i = hs_add_rail_ball(s, r, &rail);
		if (i < 0)
			continue;
		double ox, oy;
		hs_rail_out(rail, &ox, &oy);
		hs_drift(s, r, i, -ox, -oy);
		if (hs_chance(r, 0.2)) { // a second ball touching it, frozen too
			int j = hs_add_touching(s, r, i, hs_pair_angle(r));
			if (j >= 0) {
				double nx, ny;
				hs_dir(s, j, i, &nx, &ny);
				hs_drift(s, r, j, nx, ny);
			}
		}
	}
	int c = hs_add_random(s, r, 0.0);
	if (c < 0)
		c = 0;
	hs_make_cue(s, c);
	hs_random_strike(s, r, -2000.0);
	if (hs_chance(r, 0.3)) { // the drifting balls are the shot: a feeble strike elsewhere
		s->speed = hs_logu(r, 1e-3, 0.05);
		hs_finish_strike(s);
	}
}

static inline void hs_gen_pair(hs_shot *s, hs_rng *r) {
	const double R = s->def.params.ball_radius;
	int pairs = 1 + hs_int(r, 3), cue = -1;
	for (int p = 0; p < pairs; ++p) {
		int a = hs_chance(r, 0.2) ? hs_add_rail_ball(s, r, NULL) : hs_add_random(s, r, 3.0 * R);
		if (a < 0)
			continue;
		int b = hs_add_touching(s, r, a, hs_pair_angle(r));
		if (b < 0)
			continue;
		double nx, ny; // from b to a
		hs_dir(s, a, b, &nx, &ny);
		// Relative normal speed vn (> 0: separating) split between the two, or a common
		// tangential speed (a pair sliding together), and spin pushing them into each other.
		double vn = hs_tiny_speed(r), vt = hs_chance(r, 0.3) ? hs_range(r, -2.0, 2.0) : 0.0;
		double share = hs_int(r, 3) * 0.5; // a's share of vn: 0, 1/2 or 1
		s->balls[a].vel = hs_xy(share * vn * nx - vt * ny, share * vn * ny + vt * nx, 0.0);
		s->balls[b].vel = hs_xy(-(1.0 - share) * vn * nx - vt * ny, -(1.0 - share) * vn * ny + vt * nx, 0.0);
		int which = hs_int(r, 4); // spin on a, on b, on both, or none
		if (which == 0 || which == 2)
			hs_push_spin(s, r, a, -nx, -ny, 0.1);
		if (which == 1 || which == 2)
			hs_push_spin(s, r, b, nx, ny, 0.1);
		if (cue < 0 && vt == 0.0 && hs_chance(r, 0.4)) { // strike one of them
			int c = which == 0 ? b : a;
			if (which != 2) {
				cue = c;
				hs_make_cue(s, c);
			}
		}
	}
	if (cue < 0) {
		cue = hs_add_random(s, r, 0.0);
		if (cue < 0)
			cue = 0;
		hs_make_cue(s, cue);
	}
	hs_random_strike(s, r, -2000.0);
}

static inline void hs_gen_cluster(hs_shot *s, hs_rng *r) {
	const double R = s->def.params.ball_radius;
	int shape = hs_int(r, 4);
	int first = hs_chance(r, 0.3) ? hs_add_rail_ball(s, r, NULL) : hs_add_random(s, r, 4.0 * R);
	if (first < 0)
		first = hs_add_random(s, r, 0.0);
	int k = 3 + hs_int(r, 6);
	if (shape == 0) { // a chain, straight or bending
		double ang = hs_pair_angle(r);
		int last = first;
		for (int t = 1; t < k; ++t) {
			if (hs_chance(r, 0.2))
				ang += HS_PI / 3.0 * (hs_chance(r, 0.5) ? 1 : -1);
			int i = hs_add_touching(s, r, last, ang);
			if (i < 0)
				break;
			last = i;
		}
	} else if (shape == 1) { // a hexagon around the first ball
		double ang0 = hs_pair_angle(r);
		for (int t = 0; t < 6 && t < k; ++t)
			hs_add_touching(s, r, first, ang0 + t * HS_PI / 3.0);
	} else if (shape == 2) { // a frozen triangle (rows of touching balls)
		double ang0 = hs_pair_angle(r);
		int row_start = first, rows = 2 + hs_int(r, 3);
		for (int row = 1; row < rows && row_start >= 0; ++row) {
			int prev = hs_add_touching(s, r, row_start, ang0 + HS_PI / 6.0);
			if (prev < 0)
				break;
			int next_start = prev;
			for (int c = 0; c < row && prev >= 0; ++c)
				prev = hs_add_touching(s, r, prev, ang0 - HS_PI / 2.0);
			row_start = next_start;
		}
	} else { // a random blob
		for (int t = 1; t < k; ++t)
			hs_add_touching(s, r, hs_int(r, s->n), hs_chance(r, 0.5) ? HS_PI / 3.0 * hs_int(r, 6) : hs_range(r, 0.0, 2.0 * HS_PI));
	}
	// Some of its balls drift with tiny speeds and pushing spin, towards a random neighbour.
	for (int i = 0; i < s->n; ++i) {
		if (!hs_chance(r, 0.4))
			continue;
		int j = hs_int(r, s->n);
		if (j == i)
			continue;
		double nx, ny;
		hs_dir(s, i, j, &nx, &ny);
		hs_drift(s, r, i, nx, ny);
	}
	int c;
	if (hs_chance(r, 0.5) || s->n >= HS_MAX_BALLS) {
		c = hs_int(r, s->n);
	} else {
		c = hs_add_random(s, r, 0.0);
		if (c < 0)
			c = hs_int(r, s->n);
	}
	hs_make_cue(s, c);
	hs_random_strike(s, r, -2000.0);
}

static inline void hs_gen_masse(hs_shot *s, hs_rng *r) {
	int want = 1 + hs_int(r, 8);
	for (int k = 0; k < want; ++k) {
		if (s->n > 0 && hs_chance(r, 0.2))
			hs_add_touching(s, r, hs_int(r, s->n), hs_pair_angle(r));
		else if (hs_chance(r, 0.15))
			hs_add_rail_ball(s, r, NULL);
		else
			hs_add_random(s, r, 0.0);
	}
	if (s->n == 0)
		hs_add_random(s, r, 0.0);
	hs_make_cue(s, hs_int(r, s->n));
	hs_random_strike(s, r, -2000.0);
	if (hs_chance(r, 0.5)) { // massé proper: steep cue, offset near the edge
		s->theta_deg = hs_range(r, 45.0, 89.999);
		double rad = s->def.params.ball_radius * (1.0 - hs_logu(r, 1e-12, 0.3)), ang = hs_range(r, 0.0, 2.0 * HS_PI);
		s->a = rad * cos(ang);
		s->b = rad * sin(ang);
		hs_finish_strike(s);
	}
}

static inline double hs_cushion_height_extreme(hs_rng *r, double R) {
	switch (hs_int(r, 6)) {
	case 0: return R * hs_logu(r, 1e-9, 1e-2);             // almost on the cloth: dc ~ 0
	case 1: return R;                                      // nose at the centre: dc = R
	case 2: return 2.0 * R * (1.0 - hs_logu(r, 1e-12, 1e-2)); // almost at the top: dc ~ 0
	default: return hs_range(r, 1e-6 * R, 2.0 * R * (1.0 - 1e-9));
	}
}

static inline void hs_extreme_params(hs_shot *s, hs_rng *r) {
	pool_params *p = &s->def.params;
	const double fr[5] = {0.0, 0.0, 1e-6, 1.0, -1.0};
	double *mus[5] = {&p->mu_slide, &p->mu_roll, &p->mu_spin, &p->mu_ball, &p->mu_cushion};
	for (int k = 0; k < 5; ++k)
		if (hs_chance(r, 0.5)) {
			double v = fr[hs_int(r, 5)];
			*mus[k] = v < 0.0 ? hs_range(r, 0.0, 1.0) : v;
		}
	double *es[2] = {&p->e_ball, &p->e_cushion};
	for (int k = 0; k < 2; ++k)
		if (hs_chance(r, 0.5))
			*es[k] = hs_chance(r, 0.4) ? 0.0 : hs_chance(r, 0.6) ? 1.0 : hs_u(r);
	// The same extremes for mathavan2010's own nose parameters (no draw: the stream is unchanged).
	p->e_cushion_mathavan = p->e_cushion;
	p->mu_cushion_mathavan = p->mu_cushion;
	if (hs_chance(r, 0.1))
		p->g = hs_chance(r, 0.5) ? 1.62 : 24.8;
	if (hs_chance(r, 0.4))
		s->def.table.cushion_height = hs_cushion_height_extreme(r, p->ball_radius);
}

static inline void hs_gen_tiny_table(hs_shot *s, hs_rng *r) {
	const double R = s->def.params.ball_radius;
	pool_table_def *t = &s->def.table;
	t->length = 2.0 * R * (1.0 + (hs_chance(r, 0.5) ? hs_logu(r, 1e-12, 1e-2) : hs_logu(r, 1e-2, 4.0)));
	t->width = 2.0 * R * (1.0 + (hs_chance(r, 0.5) ? hs_logu(r, 1e-12, 1e-2) : hs_logu(r, 1e-2, 4.0)));
	if (hs_chance(r, 0.5)) {
		double w = t->width;
		t->width = t->length;
		t->length = w;
	}
	t->cushion_height = hs_chance(r, 0.3) ? 0.03629 : hs_cushion_height_extreme(r, R);
	double cmax = 0.5 * sqrt(2.0) * fmin(t->length, t->width);
	t->corner_mouth = hs_chance(r, 0.5) ? 0.0 : cmax * (hs_chance(r, 0.5) ? hs_u(r) : 1.0 - hs_logu(r, 1e-9, 1e-2));
	t->side_mouth = hs_chance(r, 0.5) ? 0.0 : t->length * (hs_chance(r, 0.5) ? hs_u(r) : 1.0 - hs_logu(r, 1e-9, 1e-2));
	while (pool_table_def_validate(t, NULL) != POOL_OK) {
		t->corner_mouth *= 0.5;
		t->side_mouth *= 0.5;
	}
	if (hs_chance(r, 0.5))
		hs_extreme_params(s, r);
	int want = 1 + hs_int(r, 4);
	for (int k = 0; k < want; ++k) {
		int i = -1;
		switch (hs_int(r, 4)) {
		case 0: { // in a corner: frozen to two rails
			const double dc = hs_dc(&s->def);
			i = hs_add(s, hs_xy(hs_chance(r, 0.5) ? dc : t->length - dc, hs_chance(r, 0.5) ? dc : t->width - dc, R));
			break;
		}
		case 1: i = hs_add_rail_ball(s, r, NULL); break;
		case 2:
			if (s->n > 0)
				i = hs_add_touching(s, r, hs_int(r, s->n), hs_pair_angle(r));
			break;
		default: i = hs_add_random(s, r, 0.0); break;
		}
		if (i > 0 && hs_chance(r, 0.5))
			hs_drift(s, r, i, hs_range(r, -1, 1) < 0 ? -1.0 : 1.0, 0.0);
	}
	if (s->n == 0) // the centre always fits
		hs_add(s, hs_xy(0.5 * t->length, 0.5 * t->width, R));
	hs_make_cue(s, 0);
	hs_random_strike(s, r, -2000.0);
}

// A nose height from ~0 to ~2R: on the cloth, low, at the ball's centre, just above it, just
// below the ball's top, or between (the first three are refused at validation).
static inline double hs_nose_height(hs_rng *r, double R) {
	switch (hs_int(r, 8)) {
	case 0: return R * hs_logu(r, 1e-9, 1e-2);
	case 1: return R * hs_range(r, 0.05, 0.5);
	case 2: return R;
	case 3: return R * (1.0 + hs_logu(r, 1e-12, 1e-3));
	case 4: return 2.0 * R * (1.0 - hs_logu(r, 1e-12, 1e-2));
	default: return R * hs_range(r, 1.05, 1.95);
	}
}

static inline void hs_gen_layout(hs_shot *s, hs_rng *r);
static inline void hs_gen_rail_struck(hs_shot *s, hs_rng *r);
static inline void hs_gen_rail_drift(hs_shot *s, hs_rng *r);
static inline void hs_gen_pair(hs_shot *s, hs_rng *r);
static inline void hs_gen_cluster(hs_shot *s, hs_rng *r);
static inline void hs_gen_masse(hs_shot *s, hs_rng *r);

// A full-size table (WPA 7, 8 or 9 ft) with a nose anywhere from ~0 to ~2R, ordinary cloth, and
// one of the layouts above.
static inline void hs_gen_nose(hs_shot *s, hs_rng *r) {
	static const char *const presets[3] = {"wpa-7ft", "wpa-8ft", "wpa-9ft"};
	pool_table_preset(presets[hs_int(r, 3)], &s->def.table);
	s->def.table.cushion_height = hs_nose_height(r, s->def.params.ball_radius);
	switch (hs_int(r, 6)) {
	case 0: hs_gen_layout(s, r); break;
	case 1: hs_gen_rail_struck(s, r); break;
	case 2: hs_gen_rail_drift(s, r); break;
	case 3: hs_gen_pair(s, r); break;
	case 4: hs_gen_cluster(s, r); break;
	default: hs_gen_masse(s, r); break;
	}
}

// The mouth class: the nose class's shot, then one or two balls (the cue ball among them, at
// rest) moved onto the contact lines of a pocket mouth, on them or within rounding of them,
// where they fit.
static inline void hs_gen_mouth(hs_shot *s, hs_rng *r) {
	hs_gen_nose(s, r);
	static const double off[] = {0.0, 0.0, 0.0, -1e-9, -5e-10, -1e-12, -1e-15, 1e-15, 1e-12, 5e-10, 1e-9, -1e-6, -1e-4};
	const int n_off = (int)(sizeof off / sizeof off[0]);
	const double R = s->def.params.ball_radius, L = s->def.table.length, W = s->def.table.width;
	const double dc = hs_dc(&s->def), c = s->def.table.corner_mouth / sqrt(2.0), sm = s->def.table.side_mouth;
	const int moves = 1 + hs_int(r, 2);
	for (int m = 0; m < moves && s->n > 0; ++m) {
		const int i = hs_int(r, s->n);
		const int east = hs_int(r, 2), north = hs_int(r, 2), kind = hs_int(r, 4);
		const double a = off[hs_int(r, n_off)], b = off[hs_int(r, n_off)]; // > 0: past the line
		// along: from the corner, inside the mouth (dc..c + R) or at its edge c (within rounding)
		const double along = hs_chance(r, 0.5) ? hs_range(r, dc, c + R) : c + off[hs_int(r, n_off)];
		double x = east ? L - dc + a : dc - a, y = north ? W - dc + b : dc - b;
		if (kind == 1) // along the east or west line
			y = north ? W - along : along;
		else if (kind == 2) // along the north or south line
			x = east ? L - along : along;
		else if (kind == 3) // a side mouth: inside, or at an edge within rounding
			x = 0.5 * L + (hs_chance(r, 0.5) ? hs_range(r, -0.5 * sm - R, 0.5 * sm + R)
			                                 : (east ? 1.0 : -1.0) * (0.5 * sm + off[hs_int(r, n_off)]));
		const pool_ball_state keep = s->balls[i];
		s->balls[i].pos = hs_xy(-1e9, -1e9, -1e9); // out of the way while it is tested
		const pool_vec3 p = hs_xy(x, y, R);
		if (!hs_fits(s, p)) {
			s->balls[i] = keep;
			continue;
		}
		memset(&s->balls[i].vel, 0, sizeof s->balls[i].vel);
		memset(&s->balls[i].omega, 0, sizeof s->balls[i].omega);
		s->balls[i].pos = p;
		if (i == s->cue || hs_chance(r, 0.25))
			continue; // at rest (the struck ball must be)
		const double speed = exp(hs_range(r, log(1e-6), log(3.0))), dir = hs_range(r, 0.0, 2.0 * HS_PI);
		s->balls[i].vel = hs_xy(speed * cos(dir), speed * sin(dir), 0.0);
		if (hs_chance(r, 0.5))
			s->balls[i].omega = hs_xy(hs_range(r, -80.0, 80.0), hs_range(r, -80.0, 80.0), hs_range(r, -20.0, 20.0));
	}
}

// Balls thrown into the air (airborne shots): up to two balls other than the cue ball lifted up
// to 0.25 m and thrown at up to 2 m/s (mostly upwards), with spin, where they fit.
static inline void hs_throw_balls(hs_shot *s, hs_rng *r) {
	const double R = s->def.params.ball_radius;
	const int throws = 1 + hs_int(r, 2);
	for (int k = 0; k < throws && s->n > 1; ++k) {
		const int i = hs_int(r, s->n);
		if (i == s->cue)
			continue;
		pool_ball_state keep = s->balls[i];
		pool_vec3 up = keep.pos;
		up.z = R + hs_range(r, 0.0, 0.25);
		s->balls[i].pos = hs_xy(-1e9, -1e9, -1e9); // out of the way while it is tested
		if (!hs_fits(s, up)) {
			s->balls[i] = keep;
			continue;
		}
		s->balls[i].pos = up;
		s->balls[i].vel = hs_xy(hs_range(r, -2.0, 2.0), hs_range(r, -2.0, 2.0), hs_range(r, -1.0, 2.0));
		s->balls[i].omega = hs_xy(hs_range(r, -50.0, 50.0), hs_range(r, -50.0, 50.0), hs_range(r, -20.0, 20.0));
	}
}

static inline void hs_gen_extreme_params(hs_shot *s, hs_rng *r) {
	hs_extreme_params(s, r);
	switch (hs_int(r, 6)) {
	case 0: hs_gen_layout(s, r); break;
	case 1: hs_gen_rail_struck(s, r); break;
	case 2: hs_gen_rail_drift(s, r); break;
	case 3: hs_gen_pair(s, r); break;
	case 4: hs_gen_cluster(s, r); break;
	default: hs_gen_masse(s, r); break;
	}
}

// The shot (seed, index, cls): a pure function of the three.
static inline void hs_make(hs_shot *s, uint64_t seed, long index, int cls) {
	memset(s, 0, sizeof *s);
	s->cls = cls;
	s->seed = seed;
	s->index = index;
	hs_rng r = {seed * 0xD1B54A32D192ED03ull ^ ((uint64_t)index * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)cls << 56)};
	hs_next(&r);
	s->def = pool_default_sim_def();
	// A quarter of the shots under the "thesis" laws (the 2012 work's), the rest the defaults: the
	// top two bits of a Weyl sequence in the index, so neither the class (index modulo the
	// classes) nor the generator's stream depends on it.
	if (((uint64_t)index * 0x9E3779B97F4A7C15ull) >> 62 == 3)
		s->def.models = pool_thesis_models();
	s->def.max_events = HS_MAX_EVENTS;
	s->def.max_time = HS_MAX_TIME;
	// Half the shots on real pockets ("jaws": facings, jaws, holes; the WPA geometry of the
	// presets), the others on the thesis model's lines, by another bit of the index's Weyl
	// sequence; tiny tables keep the lines (their rails are too short for the jaws). Chosen before
	// the generators, so they place no ball over a hole (hs_fits).
	const int jaws = cls != HS_TINY_TABLE && (((uint64_t)index * 0x9E3779B97F4A7C15ull) >> 61 & 1);
	s->def.table.pockets = jaws ? POOL_POCKETS_JAWS : POOL_POCKETS_MOUTH_LINES;
	switch (cls) {
	case HS_LAYOUT: hs_gen_layout(s, &r); break;
	case HS_RAIL_STRUCK: hs_gen_rail_struck(s, &r); break;
	case HS_RAIL_DRIFT: hs_gen_rail_drift(s, &r); break;
	case HS_PAIR: hs_gen_pair(s, &r); break;
	case HS_CLUSTER: hs_gen_cluster(s, &r); break;
	case HS_MASSE: hs_gen_masse(s, &r); break;
	case HS_TINY_TABLE: hs_gen_tiny_table(s, &r); break;
	case HS_EXTREME_PARAMS: hs_gen_extreme_params(s, &r); break;
	case HS_MOUTH: hs_gen_mouth(s, &r); break;
	default: hs_gen_nose(s, &r); break;
	}
	// Again after the generators (the nose class takes a preset's table). The cut angles as
	// pool-sim computes them from the degrees the scenario carries, so it replays bit for bit.
	s->def.table.pockets = jaws ? POOL_POCKETS_JAWS : POOL_POCKETS_MOUTH_LINES;
	if (jaws) {
		s->corner_cut_deg = 142.0;
		s->side_cut_deg = 104.0;
		s->def.table.corner_cut_angle = s->corner_cut_deg * HS_DEG;
		s->def.table.side_cut_angle = s->side_cut_deg * HS_DEG;
	}
	if (s->n == 0) { // a generator found no room at all: one ball in the middle
		hs_add(s, hs_xy(0.5 * s->def.table.length, 0.5 * s->def.table.width, s->def.params.ball_radius));
		hs_make_cue(s, 0);
		hs_random_strike(s, &r, -2000.0);
	}
	if (hs_chance(&r, HS_AIRBORNE_SHARE)) {
		s->def.airborne = true;
		if (hs_chance(&r, 1.0 / 3.0))
			hs_throw_balls(s, &r);
	}
}

// ---------------------------------------------------------------------------------------------
// The shot as a pool-sim scenario (docs/interfaces.md), replaying bit for bit.
static inline void hs_print_scenario(FILE *f, const hs_shot *s) {
	const pool_table_def *t = &s->def.table;
	const pool_params *p = &s->def.params;
	fprintf(f, "{\"format\": \"libpool-scenario/1\",\n");
	fprintf(f, " \"table\": {\"length\": %.17g, \"width\": %.17g, \"cushion_height\": %.17g, \"corner_mouth\": %.17g, "
	           "\"side_mouth\": %.17g, \"pockets\": \"%s\"",
	        t->length, t->width, t->cushion_height, t->corner_mouth, t->side_mouth, pool_pockets_model_name(t->pockets));
	if (t->pockets == POOL_POCKETS_JAWS)
		fprintf(f, ", \"corner_cut_angle\": %.17g, \"side_cut_angle\": %.17g, \"corner_jaw_radius\": %.17g, "
		           "\"side_jaw_radius\": %.17g, \"corner_shelf\": %.17g, \"side_shelf\": %.17g, \"corner_hole_radius\": %.17g, "
		           "\"side_hole_radius\": %.17g",
		        s->corner_cut_deg, s->side_cut_deg, t->corner_jaw_radius, t->side_jaw_radius, t->corner_shelf, t->side_shelf,
		        t->corner_hole_radius, t->side_hole_radius);
	fprintf(f, "},\n");
	fprintf(f, " \"params\": {\"g\": %.17g, \"mu_slide\": %.17g, \"mu_roll\": %.17g, \"mu_spin\": %.17g, \"mu_ball\": %.17g, "
	           "\"e_ball\": %.17g, \"mu_cushion\": %.17g, \"e_cushion\": %.17g, \"mu_table\": %.17g, \"e_table\": %.17g, "
	           "\"ball_radius\": %.17g, \"ball_mass\": %.17g, \"cue_mass\": %.17g, \"e_cushion_mathavan\": %.17g, "
	           "\"mu_cushion_mathavan\": %.17g},\n",
	        p->g, p->mu_slide, p->mu_roll, p->mu_spin, p->mu_ball, p->e_ball, p->mu_cushion, p->e_cushion, p->mu_table,
	        p->e_table, p->ball_radius, p->ball_mass, p->cue_mass, p->e_cushion_mathavan, p->mu_cushion_mathavan);
	fprintf(f, " \"balls\": [");
	for (int i = 0; i < s->n; ++i) {
		const pool_ball_state *b = &s->balls[i];
		if (b->pos.z != p->ball_radius)
			fprintf(f, "%s\n  {\"id\": %d, \"pos\": [%.17g, %.17g, %.17g]", i ? "," : "", (int)b->id, b->pos.x, b->pos.y,
			        b->pos.z);
		else
			fprintf(f, "%s\n  {\"id\": %d, \"pos\": [%.17g, %.17g]", i ? "," : "", (int)b->id, b->pos.x, b->pos.y);
		if (b->vel.x != 0.0 || b->vel.y != 0.0 || b->vel.z != 0.0)
			fprintf(f, ", \"vel\": [%.17g, %.17g, %.17g]", b->vel.x, b->vel.y, b->vel.z);
		if (b->omega.x != 0.0 || b->omega.y != 0.0 || b->omega.z != 0.0)
			fprintf(f, ", \"omega\": [%.17g, %.17g, %.17g]", b->omega.x, b->omega.y, b->omega.z);
		fprintf(f, "}");
	}
	fprintf(f, "],\n \"strike\": {\"ball\": %d, \"speed\": %.17g, \"phi\": %.17g, \"theta\": %.17g, \"a\": %.17g, \"b\": %.17g},\n",
	        (int)s->balls[s->cue].id, s->speed, s->phi_deg, s->theta_deg, s->a, s->b);
	fprintf(f, " \"models\": {\"cushion\": \"%s\", \"ball_ball_friction\": \"%s\", \"squirt\": \"%s\"},\n",
	        pool_cushion_model_name(s->def.models.cushion), pool_ball_friction_model_name(s->def.models.ball_ball_friction),
	        pool_squirt_model_name(s->def.models.squirt));
	fprintf(f, " \"options\": {\"airborne\": %s, \"max_time\": %.17g, \"max_events\": %d}}\n",
	        s->def.airborne ? "true" : "false", s->def.max_time, s->def.max_events);
}

// ---------------------------------------------------------------------------------------------
// Running and checking.
typedef struct hs_report {
	int refused;                  // the def was refused at validation (its nose's height)
	char refusal[256];            // its message
	unsigned mask;                // bit k: check k failed
	double mag[HS_CK_COUNT];      // the worst magnitude of each failed check (m, J, ratio...)
	char msg[HS_CK_COUNT][400];   // the first failure of each check
	pool_stop_reason stop;
	int events;
} hs_report;

typedef struct hs_stats {
	long shots, events, samples, floored, stop_rest, stop_max_events, stop_max_time, failed_shots, refused, airborne;
	double worst_overlap, worst_rail, worst_gain, worst_floor_gain, worst_floor_ratio, worst_momentum, worst_gap,
		worst_separating;
	long class_shots[HS_CLASS_COUNT], class_failed[HS_CLASS_COUNT], class_max_events[HS_CLASS_COUNT];
	long class_refused[HS_CLASS_COUNT], class_airborne[HS_CLASS_COUNT];
	long fail[HS_CLASS_COUNT][HS_CK_COUNT];
	long gross[HS_CLASS_COUNT][HS_CK_COUNT]; // failures beyond hs_gross[check]
	// pockets "jaws": shots (airborne among them), contacts with a jaw, a facing, a nose segment,
	// and balls pocketed on the cloth and from the air
	long jaws_shots, jaws_airborne, jaw_hits, facing_hits, nose_hits, hole_pockets, air_pockets;
} hs_stats;

// Magnitude above which a failure counts as gross in the summary: m for overlap, rail, pocket,
// contact and rest (distance moved in HS_REST_FAR), J for energy, bound ratio for floor.
static const double hs_gross[HS_CK_COUNT] = {0.0, 1e-6, 1e-6, 1e-6, 1e-9, 2.0, 1e-6, 1e-9, 1e-6, 0.0, 0.0};

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static inline void hs_fail_mag(hs_report *rep, int check, double mag, const char *fmt, ...) {
	if (!(rep->mag[check] >= mag))
		rep->mag[check] = isnan(mag) ? INFINITY : mag;
	if (rep->mask & (1u << check))
		return;
	rep->mask |= 1u << check;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(rep->msg[check], sizeof rep->msg[check], fmt, ap);
	va_end(ap);
}
#define hs_fail(rep, check, ...) hs_fail_mag(rep, check, INFINITY, __VA_ARGS__)

// Sets up and runs the shot; *initial receives the states the library derived on adding the
// balls (the first segment of each ball). Failures go to rep (check "api").
static inline int hs_run(pool_sim *sim, const hs_shot *s, pool_ball_state *initial, hs_report *rep) {
	pool_error err;
	pool_result res = pool_sim_reset(sim, &s->def, &err);
	static const char nose_refusal[] = "table.cushion_height: must be ";
	const double nose = s->def.table.cushion_height / s->def.params.ball_radius;
	if (res == POOL_ERR_INVALID_ARGUMENT && strncmp(err.message, nose_refusal, sizeof nose_refusal - 1) == 0 &&
	    !(nose > 1.0 && nose <= 1.9)) {
		rep->refused = 1; // docs/physics.md: not simulated, refused naming the field
		snprintf(rep->refusal, sizeof rep->refusal, "%s", err.message);
		return -1;
	}
	if (res != POOL_OK) {
		hs_fail(rep, HS_CK_API, "pool_sim_reset: %s", err.message);
		return -1;
	}
	for (int i = 0; i < s->n; ++i)
		if ((res = pool_sim_add_ball(sim, &s->balls[i], &err)) != POOL_OK) {
			hs_fail(rep, HS_CK_API, "pool_sim_add_ball: %s", err.message);
			return -1;
		}
	if (initial)
		memcpy(initial, pool_sim_balls(sim), sizeof(pool_ball_state) * (size_t)s->n);
	if ((res = pool_sim_strike(sim, s->balls[s->cue].id, &s->strike, &err)) != POOL_OK) {
		hs_fail(rep, HS_CK_API, "pool_sim_strike: %s", err.message);
		return -1;
	}
	if ((res = pool_sim_run(sim)) != POOL_OK) {
		int ne = 0;
		pool_sim_events(sim, &ne);
		hs_fail(rep, HS_CK_API, "pool_sim_run: %s after %d events", pool_result_str(res), ne);
		return -1;
	}
	return 0;
}

static inline int hs_on_table(const pool_ball_state *b) {
	return b->motion != POOL_MOTION_POCKETED && b->motion != POOL_MOTION_OFF_TABLE;
}

static inline int hs_state_finite(const pool_ball_state *b) {
	return isfinite(b->pos.x) && isfinite(b->pos.y) && isfinite(b->pos.z) && isfinite(b->vel.x) && isfinite(b->vel.y) &&
	       isfinite(b->vel.z) && isfinite(b->omega.x) && isfinite(b->omega.y) && isfinite(b->omega.z);
}

// Equal values (so -0 equals 0; NaN equals nothing).
static inline int hs_same_vec(pool_vec3 a, pool_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
static inline int hs_same_state(const pool_ball_state *a, const pool_ball_state *b) {
	return hs_same_vec(a->pos, b->pos) && hs_same_vec(a->vel, b->vel) && hs_same_vec(a->omega, b->omega) &&
	       a->motion == b->motion && a->id == b->id;
}

// Distance outside the contact lines (> 0: outside).
static inline double hs_outside(const pool_sim_def *def, double dc, pool_vec3 p) {
	return fmax(fmax(dc - p.x, p.x - (def->table.length - dc)), fmax(dc - p.y, p.y - (def->table.width - dc)));
}

// Outside the lines by more than the tolerance, in pool_sim_add_ball's own expressions (so a
// ball the library accepted at the tolerance is not failed for the rounding of dc - x).
static inline int hs_beyond_lines(const pool_sim_def *def, double dc, pool_vec3 p) {
	const double tol = HS_TOL_LENGTH, L = def->table.length, W = def->table.width;
	return !(p.x >= dc - tol && p.x <= L - dc + tol && p.y >= dc - tol && p.y <= W - dc + tol);
}

// Pocket whose mouth holds a contact with `rail` at coordinate `along` (docs/physics.md "Pocket").
static inline pool_pocket hs_pocket_at(const pool_table_def *t, int rail, double along);

// Distance along a rail's inward normal from its nose line, the table's edge, to p (> 0 on the table).
static inline double hs_inside_edge(const pool_sim_def *def, int rail, pool_vec3 p) {
	switch (rail) {
	case POOL_RAIL_SOUTH: return p.y;
	case POOL_RAIL_NORTH: return def->table.width - p.y;
	case POOL_RAIL_WEST: return p.x;
	default: return def->table.length - p.x;
	}
}

// The point of a rail's nose nearest to a ball centred at p: on the nose line at p's coordinate
// along the rail, or over a pocket mouth the nearest end of the nose (a mouth's edge).
static inline pool_vec3 hs_nose_point(const pool_sim_def *def, int rail, pool_vec3 p) {
	const pool_table_def *t = &def->table;
	const int along_x = rail <= POOL_RAIL_NORTH;
	const double len = along_x ? t->length : t->width, along = along_x ? p.x : p.y;
	double at = along;
	if (hs_pocket_at(t, rail, along) != POOL_POCKET_NONE) {
		// The nose: the rail less its mouths (corners [0, c], [len - c, len], the side pocket's
		// [len/2 -+ w/2] on the long rails), in at most two pieces; its ends bound them.
		const double corner = t->corner_mouth / sqrt(2.0);
		double lo[2] = {corner, len}, hi[2] = {len - corner, len}, ends[4];
		int pieces = 1, n = 0;
		if (along_x && t->side_mouth > 0.0) {
			lo[1] = 0.5 * (len + t->side_mouth);
			hi[1] = hi[0];
			hi[0] = 0.5 * (len - t->side_mouth);
			pieces = 2;
		}
		for (int k = 0; k < pieces; ++k)
			if (lo[k] < hi[k]) {
				if (lo[k] > 0.0)
					ends[n++] = lo[k];
				if (hi[k] < len)
					ends[n++] = hi[k];
			}
		if (n == 0) { // no nose on this rail: nothing to touch
			const pool_vec3 far = {1e300, 1e300, 1e300};
			return far;
		}
		double best = INFINITY;
		for (int k = 0; k < n; ++k)
			if (fabs(ends[k] - along) < best) {
				best = fabs(ends[k] - along);
				at = ends[k];
			}
	}
	const double line = rail == POOL_RAIL_NORTH ? t->width : rail == POOL_RAIL_EAST ? t->length : 0.0;
	pool_vec3 q = {along_x ? at : line, along_x ? line : at, t->cushion_height};
	return q;
}

// How far a ball (airborne motion: on the cloth or in the air) is where no ball in play may be
// (> 0: a violation, m): below the cloth, past the table's edge (a ball clearing a rail leaves
// the table: off_table), closer than R to a nose (its line outside the pocket mouths, ending at
// their edges), or, on the cloth over a mouth, past the contact line (it falls into the pocket
// there). "On the cloth" is the ball's motion, not its height: a ball in flight that crossed
// the line over a mouth above the nose flies on until it lands (docs/physics.md "Predicting
// events"), and with a nose within 1e-9 m of R it crosses lower than R + POOL_TOUCH_TOLERANCE
// (soak seed 1, nose shot 5385: launched at 1.2 cm/s from 1e-9 m inside the line, it crossed
// 1.2e-11 m above the cloth, 1e-11 m above the nose). hs_mouth_crossing checks that a flight
// crosses a mouth's line above the nose.
static inline double hs_outside_air(const pool_sim_def *def, double dc, const pool_ball_state *b) {
	const double R = def->params.ball_radius;
	const pool_vec3 p = b->pos;
	const int on_cloth = b->motion != POOL_MOTION_AIRBORNE && p.z <= R + POOL_TOUCH_TOLERANCE;
	double worst = R - p.z;
	for (int rail = 0; rail < 4; ++rail) {
		const double in = hs_inside_edge(def, rail, p);
		worst = fmax(worst, -in);
		const double along = rail <= POOL_RAIL_NORTH ? p.x : p.y;
		const pool_vec3 q = hs_nose_point(def, rail, p); // (the nose's end over a mouth)
		worst = fmax(worst, R - sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z)));
		if (hs_pocket_at(&def->table, rail, along) != POOL_POCKET_NONE && on_cloth)
			worst = fmax(worst, dc - in);
	}
	return worst;
}

// A flight (segment `seg`, airborne: straight across the cloth, gravity on z alone) that began
// inside a rail's contact line and at `dt` into it is past that line by more than the tolerance
// crossed it at some instant; over a pocket mouth it must have crossed at or above the nose, or
// it would have fallen into the pocket there. Returns how far below the nose it crossed (> 0: a
// ball let through a mouth's line, m), -INFINITY when it crossed no such line.
static inline double hs_mouth_crossing(const pool_sim_def *def, double dc, const pool_ball_state *seg, double dt) {
	double worst = -INFINITY;
	if (seg->motion != POOL_MOTION_AIRBORNE)
		return worst;
	pool_vec3 end = seg->pos;
	end.x += seg->vel.x * dt;
	end.y += seg->vel.y * dt;
	for (int rail = 0; rail < 4; ++rail) {
		const double in0 = hs_inside_edge(def, rail, seg->pos) - dc, in1 = hs_inside_edge(def, rail, end) - dc;
		if (!(in0 >= 0.0 && in1 < -HS_TOL_LENGTH))
			continue;
		const double tau = dt * in0 / (in0 - in1); // the crossing: in(t) is linear in t
		const double along = rail <= POOL_RAIL_NORTH ? seg->pos.x + seg->vel.x * tau : seg->pos.y + seg->vel.y * tau;
		if (hs_pocket_at(&def->table, rail, along) == POOL_POCKET_NONE)
			continue; // the nose is there: the distance to it is hs_outside_air's
		const double z = seg->pos.z + seg->vel.z * tau - 0.5 * def->params.g * tau * tau;
		worst = fmax(worst, def->table.cushion_height - z);
	}
	return worst;
}

// Pockets "jaws" (docs/physics.md "Table geometry"): how far a ball centred at p is where no
// ball in play may be (> 0: a violation, m): nearer the nose curve than R in 3D (on the cloth,
// nearer a part's line or arc than d_c; in flight, its 3D distance to the nose), below the cloth,
// or on the cloth over a hole (it drops there: pocket).
static inline double hs_inside_jaws(const pool_table_shape *shape, const pool_sim_def *def, pool_vec3 p) {
	const double R = def->params.ball_radius;
	double worst = fmax(R - pool_shape_distance(shape, p, NULL), R - p.z);
	for (int k = 0; k < 6 && p.z <= R + POOL_TOUCH_TOLERANCE; ++k)
		if (shape->has_pocket[k])
			worst = fmax(worst, shape->pockets[k].hole_radius - hypot(p.x - shape->pockets[k].hx, p.y - shape->pockets[k].hy));
	return worst;
}

// Positions at time t: overlaps and the lines (in flight: the noses and the table's edge; with
// pockets "jaws", shape: the nose curve and the holes).
static inline void hs_check_positions(const hs_shot *s, const pool_table_shape *shape, double dc,
                                      const pool_ball_state *b, double t, hs_stats *st, hs_report *rep) {
	const double R = s->def.params.ball_radius;
	st->samples++;
	for (int i = 0; i < s->n; ++i) {
		if (!hs_on_table(&b[i]))
			continue;
		if (!hs_state_finite(&b[i]))
			hs_fail(rep, HS_CK_API, "t=%.17g: ball %d has a non-finite state", t, (int)b[i].id);
		const int linked = b[i].motion == POOL_MOTION_LINKED;
		if (shape) {
			const double out = hs_inside_jaws(shape, &s->def, b[i].pos);
			if (out > st->worst_rail)
				st->worst_rail = out;
			if (!(out <= (linked ? HS_TOL_LINK_LENGTH : HS_TOL_LENGTH)))
				hs_fail_mag(rep, HS_CK_RAIL, out,
				            "t=%.17g: ball %d at (%.17g, %.17g, %.17g) is %.3g m into the nose curve, the cloth or over a hole",
				            t, (int)b[i].id, b[i].pos.x, b[i].pos.y, b[i].pos.z, out);
		} else if (s->def.airborne) {
			const double out = hs_outside_air(&s->def, dc, &b[i]);
			if (out > st->worst_rail)
				st->worst_rail = out;
			if (!(out <= (linked ? HS_TOL_LINK_LENGTH : HS_TOL_LENGTH)))
				hs_fail_mag(rep, HS_CK_RAIL, out,
				            "t=%.17g: ball %d at (%.17g, %.17g, %.17g) is %.3g m into a cushion, the cloth or past the table's edge",
				            t, (int)b[i].id, b[i].pos.x, b[i].pos.y, b[i].pos.z, out);
		} else {
			double out = hs_outside(&s->def, dc, b[i].pos);
			if (out > st->worst_rail)
				st->worst_rail = out;
			if (hs_beyond_lines(&s->def, dc, b[i].pos) && !(linked && out <= HS_TOL_LINK_LENGTH))
				hs_fail_mag(rep, HS_CK_RAIL, out, "t=%.17g: ball %d at (%.17g, %.17g) is %.3g m outside the cushion lines", t,
				            (int)b[i].id, b[i].pos.x, b[i].pos.y, out);
		}
		for (int j = i + 1; j < s->n; ++j) {
			if (!hs_on_table(&b[j]))
				continue;
			double dx = b[i].pos.x - b[j].pos.x, dy = b[i].pos.y - b[j].pos.y, dz = b[i].pos.z - b[j].pos.z;
			double d = sqrt(dx * dx + dy * dy + dz * dz), ov = 2.0 * R - d;
			if (ov > st->worst_overlap)
				st->worst_overlap = ov;
			// Two balls of a LINK cluster: the step's LCP holds them apart to first order, within
			// HS_TOL_LINK_LENGTH (issue 11's bound on interpenetration).
			const double tol = linked && b[j].motion == POOL_MOTION_LINKED ? HS_TOL_LINK_LENGTH : HS_TOL_LENGTH;
			if (!(d >= 2.0 * R - tol)) // pool_sim_add_ball's expression
				hs_fail_mag(rep, HS_CK_OVERLAP, ov, "t=%.17g: balls %d and %d overlap by %.3g m", t, (int)b[i].id, (int)b[j].id, ov);
		}
	}
}

static inline int hs_index_of(const hs_shot *s, int32_t id) {
	for (int i = 0; i < s->n; ++i)
		if (s->balls[i].id == id)
			return i;
	return -1;
}

// Pocket whose mouth holds a contact with `rail` at coordinate `along` (docs/physics.md "Pocket").
static inline pool_pocket hs_pocket_at(const pool_table_def *t, int rail, double along) {
	const double corner = t->corner_mouth / sqrt(2.0), L = t->length, W = t->width;
	if (rail <= POOL_RAIL_NORTH) {
		int north = rail == POOL_RAIL_NORTH;
		if (along < corner)
			return north ? POOL_POCKET_NW : POOL_POCKET_SW;
		if (along > L - corner)
			return north ? POOL_POCKET_NE : POOL_POCKET_SE;
		if (fabs(along - 0.5 * L) < 0.5 * t->side_mouth)
			return north ? POOL_POCKET_N : POOL_POCKET_S;
		return POOL_POCKET_NONE;
	}
	int east = rail == POOL_RAIL_EAST;
	if (along < corner)
		return east ? POOL_POCKET_SE : POOL_POCKET_SW;
	if (along > W - corner)
		return east ? POOL_POCKET_NE : POOL_POCKET_NW;
	return POOL_POCKET_NONE;
}

// Gap of a ball centre to a rail's contact line (> 0 inside).
static inline double hs_rail_gap(const pool_sim_def *def, double dc, int rail, pool_vec3 p) {
	switch (rail) {
	case POOL_RAIL_SOUTH: return p.y - dc;
	case POOL_RAIL_NORTH: return (def->table.width - dc) - p.y;
	case POOL_RAIL_WEST: return p.x - dc;
	default: return (def->table.length - dc) - p.x;
	}
}

// All invariants of a finished run of shot s (initial: from hs_run).
static inline void hs_check(const pool_sim *sim, const hs_shot *s, const pool_ball_state *initial, hs_stats *st,
                            hs_report *rep) {
	const pool_params *p = &s->def.params;
	const double R = p->ball_radius, dc = hs_dc(&s->def);
	const int n = s->n;
	pool_table_shape shape; // pockets "jaws": the nose curve and the holes the checks measure against
	const pool_table_shape *jaws =
	    s->def.table.pockets == POOL_POCKETS_JAWS && pool_table_shape_build(&s->def.table, R, &shape, NULL) == POOL_OK ? &shape : NULL;
	int ne;
	const pool_event *ev = pool_sim_events(sim, &ne);
	rep->events = ne;
	if (jaws) {
		st->jaws_shots++;
		st->jaws_airborne += s->def.airborne;
	}
	rep->stop = pool_sim_stop_reason(sim);
	st->events += ne;
	pool_ball_state seg[HS_MAX_BALLS], now[HS_MAX_BALLS], lib[HS_MAX_BALLS];
	double t0[HS_MAX_BALLS];
	for (int i = 0; i < n; ++i) {
		seg[i] = initial[i];
		t0[i] = 0.0;
	}
	long samples = 0;
	int state_at_checks = 0;
	const long state_at_every = ne / HS_STATE_AT_CHECKS + 1;
	double prev_t = 0.0;
	for (int e = 0; e < ne; ++e) {
		const pool_event *E = &ev[e];
		const double t = E->time;
		if (!(t >= prev_t) || !isfinite(t))
			hs_fail(rep, HS_CK_API, "event %d at t=%.17g after t=%.17g", e, t, prev_t);
		prev_t = t;
		const pool_ball_state *after = pool_sim_event_states(sim, E);
		pool_ball_state before[HS_MAX_BALLS];
		int idx[HS_MAX_BALLS];
		double eb = 0.0, ea = 0.0, escale = 0.0; // escale: energy at the segments' starts too
		int bad = 0;
		for (int k = 0; k < E->ball_count && k < HS_MAX_BALLS; ++k) {
			idx[k] = hs_index_of(s, after[k].id);
			if (idx[k] < 0) {
				hs_fail(rep, HS_CK_API, "event %d names unknown ball %d", e, (int)after[k].id);
				bad = 1;
				break;
			}
			pool_motion_evolve(p, &seg[idx[k]], t - t0[idx[k]], &before[k]);
			eb += le_energy(p, &before[k]);
			escale += fmax(le_energy(p, &before[k]), le_energy(p, &seg[idx[k]]));
			ea += le_energy(p, &after[k]);
		}
		if (bad)
			break;
		const int flagged = E->type == POOL_EVENT_LINK_BEGIN || E->type == POOL_EVENT_LINK_STEP || E->type == POOL_EVENT_LINK_END;
		if (E->type != POOL_EVENT_STRIKE) {
			const double gain = ea - eb;
			if (!isfinite(ea))
				hs_fail(rep, HS_CK_API, "event %d (%s, t=%.17g): non-finite energy", e, pool_event_type_name(E->type), t);
			if (flagged && E->type == POOL_EVENT_LINK_STEP) {
				st->floored++; // a step: held to the energy entering it where it ends (le_check)
			} else if (flagged) {
				st->floored++;
				if (gain > st->worst_floor_gain)
					st->worst_floor_gain = gain;
				if (gain / HS_TOL_LINK_ABS > st->worst_floor_ratio)
					st->worst_floor_ratio = gain / HS_TOL_LINK_ABS;
				if (!(gain <= HS_TOL_LINK_ABS + HS_TOL_ENERGY_REL * escale + HS_TOL_ENERGY_ABS))
					hs_fail_mag(rep, HS_CK_FLOOR, gain / HS_TOL_LINK_ABS, "event %d (%s, t=%.17g, link): gains %.3g J > %.3g J", e,
					        pool_event_type_name(E->type), t, gain, HS_TOL_LINK_ABS);
			} else {
				const double rel = E->type == POOL_EVENT_SLIDE_ROLL || E->type == POOL_EVENT_ROLL_STOP ||
				                           E->type == POOL_EVENT_SPIN_STOP
				                       ? HS_TOL_ENERGY_REL_CHANGE
				                       : HS_TOL_ENERGY_REL;
				double over = gain - rel * escale;
				if (over > st->worst_gain)
					st->worst_gain = over;
				// The snap onto rolling at time t: t itself is known to within half an ulp, and the
				// slip shrinks at 7/2 mu_slide g, so up to that slip is left to snap away (setting
				// w from v: 2/5 m |v| of energy per m/s of it), whatever the library does.
				double snap = 0.0;
				if (E->type == POOL_EVENT_SLIDE_ROLL && E->ball_count == 1) {
					const double v = sqrt(after[0].vel.x * after[0].vel.x + after[0].vel.y * after[0].vel.y);
					const double slip = 3.5 * p->mu_slide * p->g * HS_SNAP_ULPS * (nextafter(t, INFINITY) - t);
					snap = 0.4 * p->ball_mass * v * slip;
				}
				if (!(gain <= rel * escale + snap + (s->def.airborne ? HS_TOL_ENERGY_ABS_AIR : HS_TOL_ENERGY_ABS)))
					hs_fail_mag(rep, HS_CK_ENERGY, gain, "event %d (%s, t=%.17g): energy %.17g -> %.17g J (+%.3g J)", e,
					        pool_event_type_name(E->type), t, eb, ea, gain);
			}
		}
		if (E->type == POOL_EVENT_BALL_BALL && E->ball_count == 2) {
			const pool_ball_state *b1 = &before[0], *b2 = &before[1];
			double dx = b1->pos.x - b2->pos.x, dy = b1->pos.y - b2->pos.y, dz = b1->pos.z - b2->pos.z;
			double d = sqrt(dx * dx + dy * dy + dz * dz);
			double nx = dx / d, ny = dy / d, nz = dz / d;
			double speeds = sqrt(b1->vel.x * b1->vel.x + b1->vel.y * b1->vel.y + b1->vel.z * b1->vel.z) +
			                sqrt(b2->vel.x * b2->vel.x + b2->vel.y * b2->vel.y + b2->vel.z * b2->vel.z);
			double vn0 = (b1->vel.x - b2->vel.x) * nx + (b1->vel.y - b2->vel.y) * ny + (b1->vel.z - b2->vel.z) * nz;
			double vn1 = (after[0].vel.x - after[1].vel.x) * nx + (after[0].vel.y - after[1].vel.y) * ny +
			             (after[0].vel.z - after[1].vel.z) * nz;
			double tol_v = HS_TOL_SPEED_REL * speeds + HS_TOL_SPEED_ABS;
			double gap = d - 2.0 * R;
			if (gap > st->worst_gap)
				st->worst_gap = gap;
			if (vn0 > st->worst_separating)
				st->worst_separating = vn0;
			if (!(gap <= HS_TOL_LENGTH))
				hs_fail_mag(rep, HS_CK_CONTACT, gap, "event %d (ball_ball %d-%d, t=%.17g): impulse at a gap of %.3g m", e,
				        (int)after[0].id, (int)after[1].id, t, gap);
			if (!(vn0 <= POOL_APPROACH_EPS + tol_v))
				hs_fail_mag(rep, HS_CK_CONTACT, vn0, "event %d (ball_ball %d-%d, t=%.17g): impulse on a pair separating at %.3g m/s%s", e,
				        (int)after[0].id, (int)after[1].id, t, vn0, flagged ? " (link)" : "");
			else if (!(vn1 >= vn0 - tol_v))
				hs_fail(rep, HS_CK_CONTACT, "event %d (ball_ball %d-%d, t=%.17g): attractive impulse, normal speed %.3g -> %.3g m/s",
				        e, (int)after[0].id, (int)after[1].id, t, vn0, vn1);
			double dpx = after[0].vel.x + after[1].vel.x - b1->vel.x - b2->vel.x;
			double dpy = after[0].vel.y + after[1].vel.y - b1->vel.y - b2->vel.y;
			double dpz = after[0].vel.z + after[1].vel.z - b1->vel.z - b2->vel.z;
			// In flight a ball on the cloth pushed into it slower than POOL_APPROACH_EPS stays on it
			// (motion.c): the cloth takes that vertical push.
			if (s->def.airborne)
				dpz = fmax(fabs(dpz) - 2.0 * POOL_APPROACH_EPS, 0.0);
			double dp = sqrt(dpx * dpx + dpy * dpy + dpz * dpz);
			double rel = dp / (speeds + 1e-300);
			if (rel > st->worst_momentum && speeds > 1e-9)
				st->worst_momentum = rel;
			if (!(dp <= HS_TOL_MOMENTUM_REL * speeds + 2.0 * POOL_REST_EPS))
				hs_fail_mag(rep, HS_CK_MOMENTUM, dp, "event %d (ball_ball %d-%d, t=%.17g): momentum changes by %.3g m/s (speeds %.3g)", e,
				        (int)after[0].id, (int)after[1].id, t, dp, speeds);
		}
		if (E->type == POOL_EVENT_BALL_CUSHION && E->ball_count == 1) {
			const pool_ball_state *b = &before[0];
			double ox, oy;
			hs_rail_out(E->rail, &ox, &oy);
			double gap = hs_rail_gap(&s->def, dc, E->rail, b->pos);
			double vin = b->vel.x * ox + b->vel.y * oy; // > 0: towards the rail
			if (jaws) { // the nose curve: the distance to it in 3D, and its rate along the nearest part's normal
				int part = -1;
				gap = pool_shape_distance(jaws, b->pos, &part) - R;
				const pool_vec3 nrm = pool_shape_normal(jaws, part, b->pos);
				vin = -(nrm.x * b->vel.x + nrm.y * b->vel.y + nrm.z * b->vel.z);
			} else if (s->def.airborne) { // in flight too: the distance to the nose, and its rate
				const pool_vec3 q = hs_nose_point(&s->def, E->rail, b->pos);
				const double dx = b->pos.x - q.x, dy = b->pos.y - q.y, dz = b->pos.z - q.z;
				const double dist = sqrt(dx * dx + dy * dy + dz * dz);
				gap = dist - R;
				vin = -(dx * b->vel.x + dy * b->vel.y + dz * b->vel.z) / dist; // > 0: closing
			}
			double tol_v = HS_TOL_SPEED_REL * sqrt(b->vel.x * b->vel.x + b->vel.y * b->vel.y) + HS_TOL_SPEED_ABS;
			if (gap > st->worst_gap)
				st->worst_gap = gap;
			if (-vin > st->worst_separating)
				st->worst_separating = -vin;
			if (!(gap <= HS_TOL_LENGTH))
				hs_fail_mag(rep, HS_CK_CONTACT, gap, "event %d (ball_cushion %d %s, t=%.17g): impulse at a gap of %.3g m", e,
				        (int)after[0].id, pool_rail_name(E->rail), t, gap);
			if (!(vin >= -POOL_APPROACH_EPS - tol_v))
				hs_fail_mag(rep, HS_CK_CONTACT, -vin, "event %d (ball_cushion %d %s, t=%.17g): impulse on a ball leaving the rail at %.3g m/s%s",
				        e, (int)after[0].id, pool_rail_name(E->rail), t, -vin, flagged ? " (link)" : "");
		}
		if (jaws && E->type == POOL_EVENT_BALL_CUSHION) {
			st->jaw_hits += E->part == POOL_PART_JAW;
			st->facing_hits += E->part == POOL_PART_FACING;
			st->nose_hits += E->part == POOL_PART_NOSE;
		}
		if (E->type == POOL_EVENT_POCKET && E->ball_count == 1 && jaws) {
			if (before[0].motion == POOL_MOTION_AIRBORNE)
				st->air_pockets++;
			else
				st->hole_pockets++;
			// Over the hole of the pocket named: on the cloth its centre crosses the hole's edge
			// (a linked ball past it by what its step moved it); in flight it enters the hole's
			// circle below the nose or lands over it.
			const pool_ball_state *b = &before[0];
			const pool_pocket_shape *ps = &jaws->pockets[E->pocket < 6 ? E->pocket : 0];
			const double in = ps->hole_radius - hypot(b->pos.x - ps->hx, b->pos.y - ps->hy);
			// (A ball landing over the hole, airborne until then, drops wherever it lands.)
			const int rolling_in = b->pos.z <= R + HS_TOL_LENGTH && b->motion != POOL_MOTION_AIRBORNE &&
			                       b->motion != POOL_MOTION_LINKED;
			const int ok = E->pocket < 6 && jaws->has_pocket[E->pocket] && in >= -HS_TOL_POCKET_LINE &&
			               (!rolling_in || in <= HS_TOL_POCKET_LINE) &&
			               b->pos.z <= s->def.table.cushion_height + HS_TOL_LENGTH;
			if (!ok)
				hs_fail_mag(rep, HS_CK_POCKET, fmax(fabs(in), 1e-6),
				            "event %d (pocket %s, ball %d, t=%.17g) at (%.17g, %.17g, %.17g): %.3g m inside that pocket's hole "
				            "(at its edge on the cloth, over it in flight, below the nose)",
				            e, pool_pocket_name(E->pocket), (int)after[0].id, t, b->pos.x, b->pos.y, b->pos.z, in);
		} else if (E->type == POOL_EVENT_POCKET && E->ball_count == 1 && s->def.airborne) {
			// Crossing a contact line over its mouth below the nose, or landing past it: over the
			// mouth of the pocket named, at or past the line, inside the table's edge.
			const pool_ball_state *b = &before[0];
			int ok = 0;
			double edge = 0.0;
			for (int rail = 0; rail < 4; ++rail) {
				const double in = hs_inside_edge(&s->def, rail, b->pos);
				const double along = rail <= POOL_RAIL_NORTH ? b->pos.x : b->pos.y;
				edge = fmax(edge, -in);
				ok |= in <= dc + HS_TOL_POCKET_LINE && hs_pocket_at(&s->def.table, rail, along) == E->pocket;
			}
			if (!ok || !(edge <= HS_TOL_POCKET_EDGE))
				hs_fail_mag(rep, HS_CK_POCKET, fmax(edge, 1e-6 * !ok),
				            "event %d (pocket %s, ball %d, t=%.17g) at (%.17g, %.17g, %.17g): %.3g m past the edge%s", e,
				            pool_pocket_name(E->pocket), (int)after[0].id, t, b->pos.x, b->pos.y, b->pos.z, edge,
				            ok ? "" : ", not over that pocket's mouth at or past its contact line");
		} else if (E->type == POOL_EVENT_POCKET && E->ball_count == 1) {
			const pool_ball_state *b = &before[0];
			double out = hs_outside(&s->def, dc, b->pos);
			int ok = 0;
			for (int rail = 0; rail < 4 && !ok; ++rail) {
				double g = hs_rail_gap(&s->def, dc, rail, b->pos);
				double along = rail <= POOL_RAIL_NORTH ? b->pos.x : b->pos.y;
				ok = fabs(g) <= HS_TOL_POCKET_LINE && hs_pocket_at(&s->def.table, rail, along) == E->pocket;
			}
			if (hs_beyond_lines(&s->def, dc, b->pos) || !ok)
				hs_fail_mag(rep, HS_CK_POCKET, fmax(out, 1e-6 * !ok), "event %d (pocket %s, ball %d, t=%.17g) at (%.17g, %.17g): %.3g m outside the lines%s",
				        e, pool_pocket_name(E->pocket), (int)after[0].id, t, b->pos.x, b->pos.y, out,
				        ok ? "" : ", not on a rail line in that pocket's mouth");
		}
		if (E->type == POOL_EVENT_OFF_TABLE && E->ball_count == 1) {
			// A ball leaves the table where it crosses the table's edge, above the nose (with
			// pockets "jaws" where it crosses the nose curve above the nose, leaves a hole's circle
			// in flight, or lands off the cloth).
			const pool_ball_state *b = &before[0];
			double edge = INFINITY;
			for (int rail = 0; rail < 4; ++rail)
				edge = fmin(edge, fabs(hs_inside_edge(&s->def, rail, b->pos)));
			for (int k = 0; jaws && k < 6; ++k)
				if (jaws->has_pocket[k])
					edge = fmin(edge, fabs(jaws->pockets[k].hole_radius - hypot(b->pos.x - jaws->pockets[k].hx, b->pos.y - jaws->pockets[k].hy)));
			if (jaws) { // crossing the nose curve in plan (above the nose), leaving a hole's circle, landing
				const pool_vec3 level = {b->pos.x, b->pos.y, s->def.table.cushion_height};
				edge = fmin(edge, pool_shape_distance(jaws, level, NULL));
				if (b->pos.z <= R + HS_TOL_LENGTH)
					edge = 0.0;
			}
			if (!(edge <= HS_TOL_POCKET_LINE))
				hs_fail_mag(rep, HS_CK_POCKET, edge, "event %d (off_table, ball %d, t=%.17g) at (%.17g, %.17g, %.17g): %.3g m from the table's edge",
				            e, (int)after[0].id, t, b->pos.x, b->pos.y, b->pos.z, edge);
		}
		for (int k = 0; k < E->ball_count && k < HS_MAX_BALLS; ++k) {
			seg[idx[k]] = after[k];
			t0[idx[k]] = t;
		}
		// After the last event at this instant: positions now and densely up to the next event.
		if (e + 1 < ne && ev[e + 1].time == t)
			continue;
		const double t_next = e + 1 < ne ? ev[e + 1].time : pool_sim_end_time(sim);
		int K = 0;
		if (t_next > t) {
			double vmax = 0.0;
			for (int i = 0; i < n; ++i)
				if (hs_on_table(&seg[i]))
					vmax = fmax(vmax, sqrt(seg[i].vel.x * seg[i].vel.x + seg[i].vel.y * seg[i].vel.y + seg[i].vel.z * seg[i].vel.z));
			vmax += fmax(fmax(p->mu_slide, p->mu_roll), s->def.airborne ? 1.0 : 0.0) * p->g * (t_next - t);
			double want = ceil((t_next - t) * 2.0 * vmax / (0.25 * R));
			K = HS_SAMPLES_MIN + (want < HS_SAMPLES_MAX ? (int)want : HS_SAMPLES_MAX);
			if (samples > HS_SAMPLE_BUDGET)
				K = HS_SAMPLES_MIN;
		}
		for (int k = 0; k <= K; ++k) {
			double ts = k == 0 ? t : t + (t_next - t) * ((double)k / (K + 1));
			if (k > 0 && !(ts > t && ts < t_next)) // strictly between the events (a 1-ulp interval)
				continue;
			for (int i = 0; i < n; ++i)
				pool_motion_evolve(p, &seg[i], ts - t0[i], &now[i]);
			hs_check_positions(s, jaws, dc, now, ts, st, rep);
			for (int i = 0; i < n && !jaws && s->def.airborne; ++i) {
				const double below = hs_on_table(&now[i]) ? hs_mouth_crossing(&s->def, dc, &seg[i], ts - t0[i]) : -INFINITY;
				if (!(below <= HS_TOL_LENGTH))
					hs_fail_mag(rep, HS_CK_RAIL, below,
					            "t=%.17g: ball %d crossed a contact line over a mouth in flight %.3g m below the nose, and flew on",
					            ts, (int)now[i].id, below);
			}
			++samples;
			if ((k == 0 || k == K / 2 + 1) && (e % state_at_every == 0) && state_at_checks < 2 * HS_STATE_AT_CHECKS) {
				++state_at_checks;
				if (pool_sim_state_at(sim, ts, lib) != POOL_OK)
					hs_fail(rep, HS_CK_STATE_AT, "pool_sim_state_at(%.17g) fails", ts);
				else
					for (int i = 0; i < n; ++i)
						if (!hs_same_state(&lib[i], &now[i]))
							hs_fail(rep, HS_CK_STATE_AT, "t=%.17g ball %d: pool_sim_state_at %s pos (%.17g, %.17g) vel (%.17g, %.17g) w (%.17g, %.17g, %.17g) "
							        "differs from the event history %s pos (%.17g, %.17g) vel (%.17g, %.17g) w (%.17g, %.17g, %.17g)",
							        ts, (int)lib[i].id, pool_motion_name(lib[i].motion), lib[i].pos.x, lib[i].pos.y, lib[i].vel.x, lib[i].vel.y,
							        lib[i].omega.x, lib[i].omega.y, lib[i].omega.z, pool_motion_name(now[i].motion), now[i].pos.x, now[i].pos.y,
							        now[i].vel.x, now[i].vel.y, now[i].omega.x, now[i].omega.y, now[i].omega.z);
			}
		}
	}
	int steps_ok = 1;
	const le_result steps = le_check(sim, p, initial, n, &steps_ok);
	if (steps.worst > st->worst_floor_gain)
		st->worst_floor_gain = steps.worst;
	if (steps.worst / HS_TOL_LINK_ABS > st->worst_floor_ratio)
		st->worst_floor_ratio = steps.worst / HS_TOL_LINK_ABS;
	if (!steps_ok)
		hs_fail_mag(rep, HS_CK_FLOOR, steps.worst / HS_TOL_LINK_ABS,
		            "event %d (t=%.17g): the balls of the LINK step of event %d hold %.3g J more than entering it",
		            steps.worst_event, steps.worst_time, steps.worst_step, steps.worst);
	switch (rep->stop) {
	case POOL_STOP_REST: {
		st->stop_rest++;
		const double T = pool_sim_time(sim);
		pool_ball_state end[HS_MAX_BALLS], far[HS_MAX_BALLS];
		if (pool_sim_state_at(sim, T, end) != POOL_OK || pool_sim_state_at(sim, T + HS_REST_FAR, far) != POOL_OK) {
			hs_fail(rep, HS_CK_REST, "pool_sim_state_at fails after the end (t=%.17g)", T);
			break;
		}
		for (int i = 0; i < n; ++i) {
			// (A heap resting above the cloth sleeps, linked: at rest; a ball in flight is not.)
			if (hs_on_table(&end[i]) && (end[i].motion == POOL_MOTION_AIRBORNE ||
			                             (end[i].motion != POOL_MOTION_LINKED && !(fabs(end[i].pos.z - R) <= HS_TOL_LENGTH))))
				hs_fail_mag(rep, HS_CK_REST, fabs(end[i].pos.z - R), "at rest at t=%.17g, ball %d is %s %.3g m above the cloth", T,
				            (int)end[i].id, pool_motion_name(end[i].motion), end[i].pos.z - R);
			// A ball that keeps sliding or spinning in place (zero friction) is at rest: nothing moves.
			if (!hs_same_state(&end[i], &far[i]))
				hs_fail_mag(rep, HS_CK_REST, hypot(far[i].pos.x - end[i].pos.x, far[i].pos.y - end[i].pos.y), "at rest at t=%.17g, ball %d (%s, v=(%.3g, %.3g)) is at (%.17g, %.17g), %g s later at (%.17g, %.17g)",
				        T, (int)end[i].id, pool_motion_name(end[i].motion), end[i].vel.x, end[i].vel.y, end[i].pos.x,
				        end[i].pos.y, HS_REST_FAR, far[i].pos.x, far[i].pos.y);
		}
		hs_check_positions(s, jaws, dc, far, T + HS_REST_FAR, st, rep);
		break;
	}
	case POOL_STOP_MAX_EVENTS: st->stop_max_events++; break;
	case POOL_STOP_MAX_TIME: st->stop_max_time++; break;
	default: hs_fail(rep, HS_CK_API, "the run ended without a stop reason"); break;
	}
}

// Same events and after-states in both simulations, bit for bit.
static inline void hs_check_same(const pool_sim *a, const pool_sim *b, hs_report *rep) {
	int n1, n2;
	const pool_event *e1 = pool_sim_events(a, &n1), *e2 = pool_sim_events(b, &n2);
	if (n1 != n2) {
		hs_fail(rep, HS_CK_DETERMINISM, "a rerun gives %d events instead of %d", n2, n1);
		return;
	}
	for (int e = 0; e < n1; ++e) {
		if (memcmp(&e1[e], &e2[e], sizeof e1[e]) != 0 ||
		    memcmp(pool_sim_event_states(a, &e1[e]), pool_sim_event_states(b, &e2[e]),
		           sizeof(pool_ball_state) * (size_t)e1[e].ball_count) != 0) {
			hs_fail(rep, HS_CK_DETERMINISM, "a rerun differs at event %d (t=%.17g)", e, e1[e].time);
			return;
		}
	}
}

// Runs, checks and (rerun != NULL) reruns shot s; folds the result into st.
static inline void hs_shot_run_check(pool_sim *sim, pool_sim *rerun, const hs_shot *s, hs_stats *st, hs_report *rep) {
	memset(rep, 0, sizeof *rep);
	pool_ball_state initial[HS_MAX_BALLS];
	st->shots++;
	st->class_shots[s->cls]++;
	st->airborne += s->def.airborne;
	st->class_airborne[s->cls] += s->def.airborne;
	if (hs_run(sim, s, initial, rep) == 0) {
		hs_check(sim, s, initial, st, rep);
		if (rep->stop == POOL_STOP_MAX_EVENTS)
			st->class_max_events[s->cls]++;
		if (rerun) {
			hs_report dummy;
			memset(&dummy, 0, sizeof dummy);
			if (hs_run(rerun, s, NULL, &dummy) == 0)
				hs_check_same(sim, rerun, rep);
			else
				hs_fail(rep, HS_CK_DETERMINISM, "the rerun fails: %s", dummy.msg[HS_CK_API]);
		}
	}
	if (rep->refused) {
		st->refused++;
		st->class_refused[s->cls]++;
	}
	if (rep->mask) {
		st->failed_shots++;
		st->class_failed[s->cls]++;
		for (int c = 0; c < HS_CK_COUNT; ++c)
			if (rep->mask & (1u << c)) {
				st->fail[s->cls][c]++;
				if (rep->mag[c] > hs_gross[c])
					st->gross[s->cls][c]++;
			}
	}
}

static inline const char *hs_stop_name(pool_stop_reason r) {
	return r == POOL_STOP_REST ? "rest" : r == POOL_STOP_MAX_TIME ? "max_time" : r == POOL_STOP_MAX_EVENTS ? "max_events" : "none";
}

static inline void hs_print_report(FILE *f, const hs_shot *s, const hs_report *rep) {
	if (s->origin)
		fprintf(f, "FAIL shot index=%ld class=%s (%d balls, %d events, stop %s); reproduce: %s\n", s->index,
		        hs_class_names[s->cls], s->n, rep->events, hs_stop_name(rep->stop), s->origin);
	else
		fprintf(f, "FAIL shot seed=%llu index=%ld class=%s (%d balls, %d events, stop %s); reproduce: soak --seed %llu --shot %ld --class %s\n",
		        (unsigned long long)s->seed, s->index, hs_class_names[s->cls], s->n, rep->events, hs_stop_name(rep->stop),
		        (unsigned long long)s->seed, s->index, hs_class_names[s->cls]);
	for (int c = 0; c < HS_CK_COUNT; ++c)
		if (rep->mask & (1u << c))
			fprintf(f, "  %s: %s\n", hs_check_names[c], rep->msg[c]);
	fprintf(f, "  scenario:\n");
	hs_print_scenario(f, s);
}

static inline void hs_print_summary(FILE *f, const char *what, const hs_stats *st) {
	fprintf(f,
	        "%s: shots %ld, events %ld, samples %ld, failed shots %ld; worst overlap %.3g m, worst outside the cushion lines "
	        "%.3g m, worst energy gain %.3g J outside LINK, %.3g J in LINK events (%ld of them, worst %.3g of HS_TOL_LINK_ABS); worst "
	        "momentum error %.3g, worst contact gap %.3g m, worst separating speed at an impulse %.3g m/s; stops: rest %ld, "
	        "max_events %ld, max_time %ld; airborne %ld (%.1f%%), refused at validation %ld\n",
	        what, st->shots, st->events, st->samples, st->failed_shots, st->worst_overlap, st->worst_rail, st->worst_gain,
	        st->worst_floor_gain, st->floored, st->worst_floor_ratio, st->worst_momentum, st->worst_gap, st->worst_separating,
	        st->stop_rest, st->stop_max_events, st->stop_max_time, st->airborne,
	        st->shots ? 100.0 * st->airborne / st->shots : 0.0, st->refused);
	fprintf(f, "  pockets \"jaws\": %ld shots (%ld airborne), %ld jaw, %ld facing and %ld nose contacts, %ld balls pocketed "
	           "rolling or sliding in, %ld landing or dropping from the air\n",
	        st->jaws_shots, st->jaws_airborne, st->jaw_hits, st->facing_hits, st->nose_hits, st->hole_pockets, st->air_pockets);
	for (int c = 0; c < HS_CLASS_COUNT; ++c) {
		if (!st->class_shots[c])
			continue;
		fprintf(f, "  %-15s shots %7ld  airborne %6ld  refused %6ld  failed %6ld (%.2f%%)  max_events %5ld ", hs_class_names[c],
		        st->class_shots[c], st->class_airborne[c], st->class_refused[c], st->class_failed[c],
		        100.0 * st->class_failed[c] / st->class_shots[c], st->class_max_events[c]);
		for (int k = 0; k < HS_CK_COUNT; ++k)
			if (st->fail[c][k])
				fprintf(f, " %s %ld (gross %ld)", hs_check_names[k], st->fail[c][k], st->gross[c][k]);
		fprintf(f, "\n");
	}
}

#endif
