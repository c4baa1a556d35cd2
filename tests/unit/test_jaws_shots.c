// Invariants over random shots on the three table families (wpa-9ft and snooker with pockets
// "jaws", carom with none), planar and airborne: no ball inside a cushion (its distance to the
// nose curve, sampled densely, never below R in 3D, so never below dc on the cloth) nor on the
// cloth over a hole without being pocketed, no two balls inside each other, kinetic energy never increases
// across an event, every shot ends (at rest, within max_events), and a rerun gives the same
// events bit for bit.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "motion.h"
#include "pool/pool.h"
#include "link_step.h"
#include "table_shape.h"
#include "vec3.h"

#if defined(__SANITIZE_ADDRESS__)
#define SHOTS 40 // ASan+UBSan Debug build: the same checks, fewer shots
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHOTS 40
#endif
#endif
#ifndef SHOTS
#define SHOTS 300
#endif
#define SAMPLES 600
#define MAX_BALLS 16
/// m: rounding of positions at table scale, the touching band of contacts.
#define POSITION_TOLERANCE 1e-9

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double urand(void) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

static int active(const pool_ball_state *b) { return b->motion != POOL_MOTION_POCKETED && b->motion != POOL_MOTION_OFF_TABLE; }

// How far (m) a ball centred at p is inside the cushions (> 0: a violation): R less its 3D
// distance to the nose curve (jaws), or to the four nose lines (none), and how far over a hole.
static double inside(const pool_table_shape *sh, const pool_sim_def *def, pool_vec3 p) {
	const double R = def->params.ball_radius, h = def->table.cushion_height;
	if (def->table.pockets == POOL_POCKETS_NONE) {
		const double across[4] = {p.y, def->table.width - p.y, p.x, def->table.length - p.x};
		double worst = -INFINITY;
		for (int k = 0; k < 4; ++k)
			worst = fmax(worst, across[k] < 0.0 ? R - across[k] : R - sqrt(across[k] * across[k] + (p.z - h) * (p.z - h)));
		return worst;
	}
	double worst = R - pool_shape_distance(sh, p, NULL);
	// On the cloth over a hole (a flying ball may pass over one, or drop through its throat).
	for (int k = 0; k < 6 && p.z <= R + POSITION_TOLERANCE; ++k) {
		const pool_pocket_shape *ps = &sh->pockets[k];
		worst = fmax(worst, ps->hole_radius - hypot(p.x - ps->hx, p.y - ps->hy));
	}
	return worst;
}

/// Radians in a degree.
#define DEG (3.14159265358979323846 / 180.0)

typedef struct stats {
	double worst_inside, worst_overlap, worst_energy;
	long events, shots, pocketed, jaw_hits, facing_hits;
	int max_events;
} stats;

static void sample(const pool_sim *sim, const pool_table_shape *sh, const pool_sim_def *def, double t, stats *st) {
	pool_ball_state s[MAX_BALLS];
	const int n = pool_sim_ball_count(sim);
	assert_int_equal(pool_sim_state_at(sim, t, s), POOL_OK);
	for (int i = 0; i < n; ++i) {
		if (!active(&s[i]))
			continue;
		st->worst_inside = fmax(st->worst_inside, inside(sh, def, s[i].pos));
		for (int j = i + 1; j < n; ++j)
			if (active(&s[j]))
				st->worst_overlap = fmax(st->worst_overlap, 2.0 * def->params.ball_radius - pool_v3_len(pool_v3_sub(s[i].pos, s[j].pos)));
	}
}

// Stats with nothing seen yet.
static stats no_stats(void) {
	stats st;
	memset(&st, 0, sizeof st);
	st.worst_inside = st.worst_overlap = -INFINITY;
	return st;
}

// Samples the whole shot evenly (20 * SAMPLES intervals), between and beside its events.
static void sample_shot(const pool_sim *sim, const pool_table_shape *sh, const pool_sim_def *def, stats *st) {
	const double end = pool_sim_end_time(sim);
	for (int i = 0; i <= 20 * SAMPLES; ++i)
		sample(sim, sh, def, end * i / (20 * SAMPLES), st);
}

static void one_family(const char *preset, int airborne, stats *st) {
	pool_sim_def def = pool_default_sim_def();
	assert_int_equal(pool_table_preset(preset, &def.table), POOL_OK);
	assert_int_equal(pool_params_preset(preset, &def.params), POOL_OK);
	def.airborne = airborne != 0;
	pool_table_shape sh;
	assert_int_equal(pool_table_shape_build(&def.table, def.params.ball_radius, &sh, NULL), POOL_OK);
	pool_sim *sim = make_sim(&def), *again = make_sim(&def);
	const double R = def.params.ball_radius, dc = pool_table_contact_distance(&def.table, R);
	const double L = def.table.length, W = def.table.width;
	for (int k = 0; k < SHOTS; ++k) {
		pool_ball_state balls[MAX_BALLS];
		int n = 0;
		const int want = 1 + (int)(urand() * MAX_BALLS);
		for (int tries = 0; n < want && tries < 2000; ++tries) {
			pool_ball_state b;
			memset(&b, 0, sizeof b);
			b.id = n;
			// Near the cushions and pockets half the time: the parts get hit.
			const double margin = urand() < 0.5 ? 0.15 : 0.5 * W;
			double x = dc + urand() * (L - 2.0 * dc), y = dc + urand() * (W - 2.0 * dc);
			if (urand() < 0.5)
				x = urand() < 0.5 ? dc + urand() * margin : L - dc - urand() * margin;
			b.pos = pool_v3(x, y, R);
			int ok = 1;
			for (int j = 0; j < n; ++j)
				ok &= pool_v3_len(pool_v3_sub(b.pos, balls[j].pos)) >= 2.0 * R;
			if (ok)
				balls[n++] = b;
		}
		double r = 0.9 * R * sqrt(urand()), a = urand() * 6.283185307179586;
		pool_strike strike = {0.05 + urand() * 7.95, urand() * 6.283185307179586,
		                      airborne && urand() < 0.6 ? urand() * 1.3 : 0.0, r * cos(a), r * sin(a)};
		for (int pass = 0; pass < (k % 10 == 0 ? 2 : 1); ++pass) {
			pool_sim *s = pass ? again : sim;
			assert_int_equal(pool_sim_reset(s, NULL, NULL), POOL_OK);
			for (int i = 0; i < n; ++i)
				add_ball(s, &balls[i]);
			assert_int_equal(pool_sim_strike(s, 0, &strike, NULL), POOL_OK);
			assert_int_equal(pool_sim_run(s), POOL_OK);
		}
		if (pool_sim_stop_reason(sim) != POOL_STOP_REST)
			fail_msg("%s%s shot %d: stopped by %d", preset, airborne ? " airborne" : "", k, (int)pool_sim_stop_reason(sim));
		int ne;
		const pool_event *ev = pool_sim_events(sim, &ne);
		st->events += ne;
		st->shots++;
		st->max_events = ne > st->max_events ? ne : st->max_events;
		if (k % 10 == 0) { // determinism
			int n2;
			const pool_event *e2 = pool_sim_events(again, &n2);
			assert_int_equal(ne, n2);
			assert_memory_equal(ev, e2, sizeof(pool_event) * (size_t)ne);
		}
		// Energy across each event: the involved balls just before (their segments evolved to
		// the event) and just after.
		pool_ball_state seg[MAX_BALLS];
		double t0[MAX_BALLS];
		for (int i = 0; i < n; ++i) {
			seg[i] = balls[i];
			t0[i] = 0.0;
		}
		for (int e = 0; e < ne; ++e) {
			const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
			double before_e = 0.0, after_e = 0.0;
			for (int j = 0; j < ev[e].ball_count; ++j) {
				const int i = ball_index(balls, n, after[j].id);
				pool_ball_state before;
				if (ev[e].type == POOL_EVENT_STRIKE)
					before = seg[i];
				else
					pool_motion_evolve(&def.params, &seg[i], ev[e].time - t0[i], &before);
				before_e += pool_motion_energy(&def.params, &before);
				after_e += pool_motion_energy(&def.params, &after[j]);
				seg[i] = after[j];
				t0[i] = ev[e].time;
			}
			if (ev[e].type == POOL_EVENT_BALL_CUSHION) {
				st->jaw_hits += ev[e].part == POOL_PART_JAW;
				st->facing_hits += ev[e].part == POOL_PART_FACING;
			}
			st->pocketed += ev[e].type == POOL_EVENT_POCKET;
			if (ev[e].type != POOL_EVENT_STRIKE && ev[e].type != POOL_EVENT_LINK_BEGIN && ev[e].type != POOL_EVENT_LINK_STEP &&
			    ev[e].type != POOL_EVENT_LINK_END)
				st->worst_energy = fmax(st->worst_energy, after_e - before_e - 1e-12 * fmax(before_e, 1.0));
			sample(sim, &sh, &def, ev[e].time, st);
		}
		const double end = pool_sim_end_time(sim);
		for (int i = 0; i <= SAMPLES; ++i)
			sample(sim, &sh, &def, end * i / SAMPLES, st);
		if (st->worst_inside > POSITION_TOLERANCE || st->worst_overlap > POSITION_TOLERANCE || st->worst_energy > 0.0) {
			// The shot, to reproduce it: its balls, strike and events.
			for (int i = 0; i < n; ++i)
				printf("ball %d at (%.17g, %.17g)\n", (int)balls[i].id, balls[i].pos.x, balls[i].pos.y);
			printf("strike speed %.17g phi %.17g theta %.17g a %.17g b %.17g\n", strike.speed, strike.phi, strike.theta,
			       strike.a, strike.b);
			for (int e = 0; e < ne; ++e) {
				const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
				printf("  %.9f %s ball %d part %d pocket %d at (%.6f, %.6f, %.6f) v (%.4f, %.4f, %.4f)\n", ev[e].time,
				       pool_event_type_name(ev[e].type), (int)after[0].id, (int)ev[e].part, (int)ev[e].pocket, after[0].pos.x,
				       after[0].pos.y, after[0].pos.z, after[0].vel.x, after[0].vel.y, after[0].vel.z);
			}
			fail_msg("%s%s shot %d (seed state %llu): inside a cushion by %.3g m, overlap %.3g m, energy gain %.3g J", preset,
			         airborne ? " airborne" : "", k, (unsigned long long)rng, st->worst_inside, st->worst_overlap, st->worst_energy);
		}
	}
	pool_sim_destroy(sim);
	pool_sim_destroy(again);
}

static void test_families(void **state) {
	(void)state;
	const char *presets[] = {"wpa-9ft", "snooker", "carom"};
	for (int p = 0; p < 3; ++p)
		for (int airborne = 0; airborne <= 1; ++airborne) {
			stats st;
			memset(&st, 0, sizeof st);
			st.worst_inside = st.worst_overlap = st.worst_energy = -INFINITY;
			one_family(presets[p], airborne, &st);
			printf("%s%s: %ld shots, %ld events (max %d), %ld pocketed, %ld jaw and %ld facing contacts, "
			       "worst inside %.3g m, overlap %.3g m, energy %.3g J\n",
			       presets[p], airborne ? " airborne" : "", st.shots, st.events, st.max_events, st.pocketed, st.jaw_hits,
			       st.facing_hits, st.worst_inside, st.worst_overlap, st.worst_energy);
			// The shots reach the pockets' parts (and, on the cloth, the holes): the checks saw them.
			if (p < 2)
				assert_true(st.jaw_hits + st.facing_hits > 0 && (airborne || st.pocketed > 0));
		}
}

// A soak shot's jaws table as its scenario prints it: the WPA pockets (mouths, cut angles,
// jaws, shelves and holes) on a table of this size and nose height.
static void soak_jaws_table(pool_table_def *t, double length, double width, double nose) {
	t->length = length;
	t->width = width;
	t->cushion_height = nose;
	t->corner_mouth = 0.1143;
	t->side_mouth = 0.127;
	t->pockets = POOL_POCKETS_JAWS;
	t->corner_cut_angle = 142 * DEG;
	t->side_cut_angle = 104 * DEG;
	t->corner_jaw_radius = 0.02095;
	t->side_jaw_radius = 0.0079500000000000005;
	t->corner_shelf = 0.028575;
	t->side_shelf = 0.0047624999999999994;
	t->corner_hole_radius = 0.069849999999999995;
	t->side_hole_radius = 0.07619999999999999;
}

// A soak flight shot's definition: the defaults on its jaws table, airborne, with the soak's limits.
static pool_sim_def soak_flight_def(double length, double width, double nose) {
	pool_sim_def def = pool_default_sim_def();
	soak_jaws_table(&def.table, length, width, nose);
	def.airborne = true;
	def.max_time = 60;
	def.max_events = 20000;
	return def;
}

// A replayed soak shot's nose shape (for the checks) and its simulation.
static pool_sim *replay_setup(const pool_sim_def *def, pool_table_shape *sh) {
	assert_int_equal(pool_table_shape_build(&def->table, def->params.ball_radius, sh, NULL), POOL_OK);
	return make_sim(def);
}

// A ball linked (LINK) against a facing slides into the hole during a step: the hole's edge
// must be its event even though the part it touches is "contacted" at once (a part contact is
// the step's LCP's, no event; taken as the earliest prediction it hid the hole, and the ball
// slid 0.34 mm over the hole before the next step dropped it). The soak's shot (seed 1, index
// 16635, class nose): a 7 ft table with a high nose (1.85 R) and the thesis models.
static void test_linked_into_hole(void **state) {
	(void)state;
	pool_sim_def def = thesis_sim_def();
	soak_jaws_table(&def.table, 1.9811999999999999, 0.99059999999999993, 0.053004041623678999);
	def.airborne = false;
	pool_table_shape sh;
	pool_sim *sim = replay_setup(&def, &sh);
	const double R = def.params.ball_radius;
	const double at[4][2] = {{0.80517546545028851, 0.97577594689875402},
	                         {0.014824053586996301, 0.69859126863235865},
	                         {0.5883369213145947, 0.13539759234383328},
	                         {0.090700824259018153, 0.077470806258811697}};
	for (int i = 0; i < 4; ++i) {
		pool_ball_state b;
		memset(&b, 0, sizeof b);
		b.id = i;
		b.pos = pool_v3(at[i][0], at[i][1], R);
		if (i == 1) { // the soak's crawl of a ball at rest
			b.vel.x = 1.6534461295364629e-10;
			b.omega.y = 5.7863381611074813e-09;
		}
		add_ball(sim, &b);
	}
	const pool_strike strike = {9.998357414745092, 180 * DEG, 35.764550201990041 * DEG, -0.024215845921280756,
	                            0.015169819752230319};
	assert_int_equal(pool_sim_strike(sim, 0, &strike, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	stats st = no_stats();
	int ne, linked_pocket = 0;
	const pool_event *ev = pool_sim_events(sim, &ne);
	for (int e = 0; e < ne; ++e) {
		sample(sim, &sh, &def, ev[e].time, &st);
		linked_pocket += ev[e].type == POOL_EVENT_POCKET && ev[e].pocket == POOL_POCKET_NW;
	}
	sample_shot(sim, &sh, &def, &st);
	printf("linked into the hole: %d events, worst inside %.3g m, overlap %.3g m\n", ne, st.worst_inside, st.worst_overlap);
	assert_true(linked_pocket == 1); // the shot's ball 0 drops into the north-west corner
	assert_true(st.worst_inside <= POSITION_TOLERANCE);
	assert_true(st.worst_overlap <= POSITION_TOLERANCE);
	pool_sim_destroy(sim);
}

// A ball struck straight up from a corner mouth's edge (soak seed 2, mouth shot 40719: 12 m/s at
// 89 deg and full draw, on an 8 ft table with the nose 2e-10 m above the ball's centre) flies
// 4.2 m up and comes down 1.86 s later onto the south-east jaw at 18 m/s. The jaw's contact in
// flight is a root of a degree-8 polynomial in the time since the flight began, whose terms grow
// to 1e5 by then: its rounding put the contact 2.35e-7 m inside the jaw. At the contact and on
// samples every 0.2 ns around it the ball is no nearer the nose curve than R (within 1e-9 m).
static void test_long_flight_onto_a_jaw(void **state) {
	(void)state;
	pool_sim_def def = soak_flight_def(2.3367999999999998, 1.1683999999999999, 0.028575000195715631);
	pool_table_shape sh;
	pool_sim *sim = replay_setup(&def, &sh);
	pool_ball_state b;
	memset(&b, 0, sizeof b);
	b.pos = pool_v3(2.2559786949103775, 0.028574999999999001, def.params.ball_radius);
	add_ball(sim, &b);
	const pool_strike strike = {12.0, 90 * DEG, 89 * DEG, -5.2491423033183011e-18, -0.02857499978482481};
	assert_int_equal(pool_sim_strike(sim, 0, &strike, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	int ne, jaw = -1;
	const pool_event *ev = pool_sim_events(sim, &ne);
	for (int e = 0; e < ne && jaw < 0; ++e)
		if (ev[e].type == POOL_EVENT_BALL_CUSHION && ev[e].part == POOL_PART_JAW)
			jaw = e;
	assert_true(jaw >= 0);
	const double tc = ev[jaw].time;
	stats st = no_stats();
	sample(sim, &sh, &def, tc, &st);
	const double at_contact = st.worst_inside;
	for (int i = -50; i < 0; ++i) // (the state at tc is the contact's; before it, the flight)
		sample(sim, &sh, &def, tc + i * 2e-10, &st);
	printf("long flight onto a jaw: contact at t = %.12g s, %.3g m inside the nose curve there, worst %.3g m\n", tc,
	       at_contact, st.worst_inside);
	assert_true(tc > 1.8 && ev[jaw].pocket == POOL_POCKET_SE);
	assert_true(st.worst_inside <= POSITION_TOLERANCE);
	pool_sim_destroy(sim);
}

// A ball struck almost straight down with full side (soak seed 21, mouth shot 184749: 7 ft, the
// nose 8e-11 m above the ball's centre) hops along the north-east facing's nose line from above,
// 2R above the cloth, with its centre over the pocket's hole; LINK takes it at the facing's
// repeated contacts. Over a hole above the nose a ball is not in the pocket (in flight it flies
// on): it was pocketed at once, 2R above the cloth. Every pocket event is below the nose, and at
// the events and on samples no ball is inside the nose curve.
static void test_linked_above_a_hole(void **state) {
	(void)state;
	pool_sim_def def = soak_flight_def(1.9811999999999999, 0.99059999999999993, 0.028575000079588804);
	pool_table_shape sh;
	pool_sim *sim = replay_setup(&def, &sh);
	const double R = def.params.ball_radius;
	const pool_ball_state balls[2] = {
	    {.id = 0, .pos = {0.070980322776401386, 0.96202499999999991, R}, .vel = {-0.00056588838332504582, -0.00075526811793557344, 0},
	     .omega = {-51.419342007938425, -27.601371442546977, 13.706935021251141}},
	    {.id = 1, .pos = {1.9168974015108371, 0.96202399999999988, R}}};
	for (int i = 0; i < 2; ++i)
		add_ball(sim, &balls[i]);
	const pool_strike strike = {2.6164080278772657, 0.0, 85.218218050182514 * DEG, -0.028574999999971425, 3.4994282285600623e-18};
	assert_int_equal(pool_sim_strike(sim, 1, &strike, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	stats st = no_stats();
	int ne, linked = 0;
	double highest_pocket = -INFINITY;
	const pool_event *ev = pool_sim_events(sim, &ne);
	for (int e = 0; e < ne; ++e) {
		linked += ev[e].type == POOL_EVENT_LINK_BEGIN;
		if (ev[e].type == POOL_EVENT_POCKET) {
			// (the pocketed ball's state keeps where it left play)
			highest_pocket = fmax(highest_pocket, pool_sim_event_states(sim, &ev[e])->pos.z);
		}
		sample(sim, &sh, &def, ev[e].time, &st);
	}
	sample_shot(sim, &sh, &def, &st);
	printf("linked above a hole: %d events, %d link_begin, highest pocket event %.6g m above the nose, worst inside %.3g m\n",
	       ne, linked, highest_pocket - def.table.cushion_height, st.worst_inside);
	assert_true(linked > 0); // the shot still reaches LINK on the facing
	assert_true(highest_pocket <= def.table.cushion_height);
	assert_true(st.worst_inside <= POSITION_TOLERANCE);
	pool_sim_destroy(sim);
}

// A ball linked on the top of the cushion over a corner jaw (soak seed 49, mouth shot 27112: a
// 9 ft table, the nose 0.82 R high; ball 1, struck at 68 deg, hops along the north rail's nose
// from above and LINK takes it 3 mm inside the north-west jaw's circle, moving along it at
// 0.6 m/s). From there the arc bends towards the ball's centre: the step's tangent plane at the
// nearest point let it sink 0.6 um into the nose curve a step, 7.2 um after 16 steps (the soak's
// limit inside LINK is 1 um). The shot replayed: at every event and on samples no ball is inside
// the nose curve beyond LINK's touching band, and ball 1 still rides the jaw linked.
static void test_linked_over_a_jaw(void **state) {
	(void)state;
	pool_sim_def def = soak_flight_def(2.54, 1.27, 0.052232539917924987);
	pool_table_shape sh;
	pool_sim *sim = replay_setup(&def, &sh);
	const double R = def.params.ball_radius;
	const pool_ball_state balls[3] = {
	    {.id = 0, .motion = POOL_MOTION_AIRBORNE, .pos = {0.080822305589622376, 0.016026585102004286, 0.15650779209308591},
	     .vel = {-0.56287424282230125, -0.57712961059418255, 1.182363034858767},
	     .omega = {5.897227143611758, 38.308866732642159, -14.799420718579004}},
	    {.id = 2, .motion = POOL_MOTION_AIRBORNE, .pos = {0.042850677279967046, 0.83667887019038334, 0.082505259318200366},
	     .vel = {1.7891347759044862, -0.33085068673737972, 1.8894268908267984},
	     .omega = {-29.881812970675227, -10.22705189419294, -9.3251042768250958}},
	    {.id = 1, .pos = {0.02943863130846679, 0.89223280262147564, R}}};
	for (int i = 0; i < 3; ++i)
		add_ball(sim, &balls[i]);
	const pool_strike strike = {6.4492003586602502, 54.583830256398059 * DEG, 68 * DEG, -0.028574999999137381,
	                            3.4994282284579217e-18};
	assert_int_equal(pool_sim_strike(sim, 1, &strike, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	stats st = no_stats();
	int ne, jaw_steps = 0;
	const pool_event *ev = pool_sim_events(sim, &ne);
	for (int e = 0; e < ne; ++e) {
		sample(sim, &sh, &def, ev[e].time, &st);
		const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
		if (ev[e].type == POOL_EVENT_LINK_STEP && ev[e].ball_count == 1 && after->id == 1) {
			int part;
			const pool_vec3 p = after->pos;
			pool_shape_distance(&sh, p, &part);
			jaw_steps += sh.parts[part].part == POOL_PART_JAW && p.z > def.table.cushion_height;
		}
	}
	sample_shot(sim, &sh, &def, &st);
	printf("linked over a jaw: %d events, %d link steps of ball 1 on the jaw, worst inside %.3g m\n", ne, jaw_steps,
	       st.worst_inside);
	assert_true(jaw_steps >= 10); // the shot still rides the jaw linked
	assert_true(st.worst_inside <= POOL_LINK_TOUCH_GAP);
	pool_sim_destroy(sim);
}

int main(void) {
	const struct CMUnitTest tests[] = {cmocka_unit_test(test_families), cmocka_unit_test(test_linked_into_hole),
	                                   cmocka_unit_test(test_long_flight_onto_a_jaw), cmocka_unit_test(test_linked_above_a_hole),
	                                   cmocka_unit_test(test_linked_over_a_jaw)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
