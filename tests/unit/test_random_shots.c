// Invariants over many random shots run to rest: termination, no interpenetration, balls stay on
// the table, kinetic energy never increases across an event, momentum conserved in ball-ball
// events, determinism (a rerun gives the same event list bit for bit).
// test_hostile_shots runs the hostile classes of tests/soak/hostile.h (frozen balls, tiny
// separation speeds, massé, extreme tables and parameters) under its stricter checks.
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

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/// m/s, a velocity the library cleans to zero as rest (motion.h's POOL_REST_EPS): a collision
/// of a linked ball drifting at the LCP's rounding (1e-12 m/s) with a resting ball gives that
/// ball a speed below it, which is then zero, and the pair's momentum changes by up to this.
#define REST_CLEANUP 1e-12

/// J: what a LINK step may add in planar mode, where its LCP only dissipates: Lemke's residual
/// (POOL_LEMKE_RESIDUAL_MAX relative) on impulses of a few mN s.
#define LINK_ENERGY_TOLERANCE 1e-9

#include "../soak/hostile.h"
#include "motion.h"
#include "pool/pool.h"
#include "vec3.h"

#if defined(__SANITIZE_ADDRESS__)
#define DEFAULT_SHOTS 1000 // ASan+UBSan Debug build: same checks, fewer shots
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DEFAULT_SHOTS 1000
#endif
#endif
#ifndef DEFAULT_SHOTS
#define DEFAULT_SHOTS 10000
#endif
#define DEFAULT_HOSTILE_SHOTS (DEFAULT_SHOTS / 5)

// Hostile classes run by default: all of them (they found issue 9's contact leaks).
// POOL_TEST_HOSTILE overrides the list ("all", or class names separated by commas; hostile.h);
// POOL_TEST_HOSTILE_SHOTS the number of shots and POOL_TEST_HOSTILE_SEED the seed.
#define DEFAULT_HOSTILE_CLASSES "all"

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double urand(void) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct shot {
	pool_ball_state balls[16];
	int n;
	pool_strike strike;
} shot;

// Random racks (frozen or with a small gap, 8- or 9-ball) and random layouts of 2-16 balls,
// struck with random speed (0.05-8 m/s), direction, elevation and tip offset.
static void make_shot(const pool_sim_def *def, int index, shot *s) {
	const double R = def->params.ball_radius;
	const double dc = pool_table_contact_distance(&def->table, R);
	if (index % 3 != 2) {
		double gap = urand() < 0.5 ? 0.0 : urand() * 2e-3;
		s->n = pool_rack(urand() < 0.7 ? POOL_RACK_8BALL : POOL_RACK_9BALL, &def->table, &def->params, gap, s->balls, 16);
		if (urand() < 0.5) { // the cue ball anywhere behind the head string
			s->balls[0].pos.x = dc + urand() * (0.25 * def->table.length - dc);
			s->balls[0].pos.y = dc + urand() * (def->table.width - 2.0 * dc);
		}
	} else {
		int want = 2 + (int)(urand() * 15);
		s->n = 0;
		for (int tries = 0; s->n < want && tries < 2000; ++tries) {
			pool_ball_state b;
			memset(&b, 0, sizeof b);
			b.id = s->n;
			b.pos = pool_v3(dc + urand() * (def->table.length - 2 * dc), dc + urand() * (def->table.width - 2 * dc), R);
			int ok = 1;
			for (int j = 0; j < s->n; ++j)
				ok &= pool_v3_len(pool_v3_sub(b.pos, s->balls[j].pos)) >= 2.0 * R;
			if (ok)
				s->balls[s->n++] = b;
		}
	}
	s->strike.speed = 0.05 + urand() * 7.95;
	s->strike.phi = urand() * 2.0 * M_PI;
	s->strike.theta = urand() < 0.5 ? 0.0 : urand() * 1.4;
	double r = 0.95 * R * sqrt(urand()), a = urand() * 2.0 * M_PI;
	s->strike.a = r * cos(a);
	s->strike.b = r * sin(a);
	if (index % 3 == 0 && urand() < 0.3)
		s->strike = pool_break_strike(0.5 + urand() * 7.5);
}

static void run_shot(pool_sim *sim, const pool_sim_def *def, const shot *s) {
	assert_int_equal(pool_sim_reset(sim, def, NULL), POOL_OK);
	for (int i = 0; i < s->n; ++i)
		assert_int_equal(pool_sim_add_ball(sim, &s->balls[i], NULL), POOL_OK);
	assert_int_equal(pool_sim_strike(sim, 0, &s->strike, NULL), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
}

static int active(const pool_ball_state *b) { return b->motion != POOL_MOTION_POCKETED && b->motion != POOL_MOTION_OFF_TABLE; }

typedef struct stats {
	double worst_overlap, worst_rail, worst_energy, worst_momentum;
	long events, linked;
	int max_events;
} stats;

// No two balls closer than 2R (to 1e-9 m), every ball inside the cushion contact lines.
static void check_positions(const pool_sim_def *def, const pool_ball_state *b, int n, stats *st) {
	const double R = def->params.ball_radius;
	const double dc = pool_table_contact_distance(&def->table, R);
	for (int i = 0; i < n; ++i) {
		if (!active(&b[i]))
			continue;
		double out = fmax(fmax(dc - b[i].pos.x, b[i].pos.x - (def->table.length - dc)),
		                  fmax(dc - b[i].pos.y, b[i].pos.y - (def->table.width - dc)));
		st->worst_rail = fmax(st->worst_rail, out);
		for (int j = i + 1; j < n; ++j)
			if (active(&b[j]))
				st->worst_overlap = fmax(st->worst_overlap, 2.0 * R - pool_v3_len(pool_v3_sub(b[i].pos, b[j].pos)));
	}
}

static void check_shot(pool_sim *sim, const pool_sim_def *def, const shot *s, int dense, stats *st) {
	const pool_params *p = &def->params;
	assert_int_equal(pool_sim_stop_reason(sim), POOL_STOP_REST);
	int ne;
	const pool_event *ev = pool_sim_events(sim, &ne);
	st->events += ne;
	if (ne > st->max_events)
		st->max_events = ne;
	// Walk the events keeping each ball's segment start, to get the states just before each event.
	pool_ball_state seg[16];
	double t0[16];
	for (int i = 0; i < s->n; ++i) {
		seg[i] = s->balls[i];
		t0[i] = 0.0;
	}
	int steps_ok = 1;
	const le_result steps = le_check(sim, p, s->balls, s->n, &steps_ok);
	if (!steps_ok)
		fail_msg("a LINK step ends %.3g J above the energy entering it (event %d)", steps.worst, steps.worst_event);
	pool_ball_state all[16];
	for (int e = 0; e < ne; ++e) {
		const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
		if (e > 0)
			assert_true(ev[e].time >= ev[e - 1].time);
		double e_before = 0.0, e_after = 0.0;
		pool_vec3 p_before = {0, 0, 0}, p_after = {0, 0, 0};
		double speeds = 0.0; // the momentum's scale: two balls meeting head on sum to ~0
		for (int k = 0; k < ev[e].ball_count; ++k) {
			const int i = ball_index(s->balls, s->n, after[k].id);
			pool_ball_state before;
			if (ev[e].type == POOL_EVENT_STRIKE)
				before = seg[i];
			else
				pool_motion_evolve(p, &seg[i], ev[e].time - t0[i], &before);
			e_before += pool_motion_energy(p, &before);
			e_after += pool_motion_energy(p, &after[k]);
			p_before = pool_v3_add(p_before, before.vel);
			speeds += pool_v3_len(before.vel);
			p_after = pool_v3_add(p_after, after[k].vel);
			seg[i] = after[k];
			t0[i] = ev[e].time;
		}
		if (ev[e].type != POOL_EVENT_STRIKE) {
			double gain = e_after - e_before - 1e-12 * e_before;
			if (le_is_link(ev[e].type)) {
				st->linked++;
				// A planar LINK step's LCP only dissipates, up to Lemke's residual on its
				// impulses: held to it where the step ends (below); link_begin and link_end here.
				if (ev[e].type != POOL_EVENT_LINK_STEP && !(gain <= LINK_ENERGY_TOLERANCE))
					fail_msg("a LINK event adds %.3g J", gain);
			} else {
				st->worst_energy = fmax(st->worst_energy, gain);
			}
		}
		if (ev[e].type == POOL_EVENT_BALL_BALL) {
			// Less what the clean-up of rest speeds may take (REST_CLEANUP per ball).
			double dp = pool_v3_len(pool_v3_sub(p_after, p_before)) - REST_CLEANUP * ev[e].ball_count;
			st->worst_momentum = fmax(st->worst_momentum, fmax(dp, 0.0) / (speeds + 1e-300));
		}
		// Positions of every ball at each event time.
		if (e + 1 == ne || ev[e + 1].time != ev[e].time) {
			assert_int_equal(pool_sim_state_at(sim, ev[e].time, all), POOL_OK);
			check_positions(def, all, s->n, st);
			if (e + 1 < ne) { // and halfway to the next event
				assert_int_equal(pool_sim_state_at(sim, 0.5 * (ev[e].time + ev[e + 1].time), all), POOL_OK);
				check_positions(def, all, s->n, st);
			}
		}
	}
	if (dense) {
		double T = pool_sim_time(sim);
		for (int k = 0; k <= dense; ++k) {
			assert_int_equal(pool_sim_state_at(sim, T * k / dense, all), POOL_OK);
			check_positions(def, all, s->n, st);
		}
	}
	// Everything at rest at the end.
	const pool_ball_state *fin = pool_sim_balls(sim);
	for (int i = 0; i < s->n; ++i)
		assert_true(fin[i].motion == POOL_MOTION_STATIONARY || fin[i].motion == POOL_MOTION_POCKETED);
}

static void test_random_shots(void **state) {
	(void)state;
	int shots = DEFAULT_SHOTS;
	const char *env = getenv("POOL_TEST_SHOTS");
	if (env && atoi(env) > 0)
		shots = atoi(env);
	// The default models, and every fourth shot the "thesis" set (the 2012 work's laws); the thesis
	// model's pockets: check_positions and hostile.h's checks are its contact lines and mouths
	// (pockets "jaws": test_jaws_shots.c).
	pool_sim_def def = pool_default_sim_def(), thesis = thesis_sim_def();
	def.table.pockets = thesis.table.pockets = POOL_POCKETS_MOUTH_LINES;
	pool_sim *sim, *again;
	assert_int_equal(pool_sim_create(&def, &sim, NULL), POOL_OK);
	assert_int_equal(pool_sim_create(&def, &again, NULL), POOL_OK);
	stats st;
	memset(&st, 0, sizeof st);
	static hs_stats hst;
	memset(&hst, 0, sizeof hst);
	int reruns = 0;
	for (int k = 0; k < shots; ++k) {
		shot s;
		const pool_sim_def *shot_def = k % 4 == 3 ? &thesis : &def;
		make_shot(shot_def, k, &s);
		run_shot(sim, shot_def, &s);
		check_shot(sim, shot_def, &s, k < 200 ? 2000 : 0, &st);
		if (k % 5 == 0) { // and hostile.h's stricter checks (dense overlap sampling, rest, contacts...)
			hs_shot h;
			memset(&h, 0, sizeof h);
			h.cls = HS_LAYOUT;
			h.index = k;
			// (test_random_shots' own layouts, not the soak's: its hint would name another shot)
			h.origin = "pool-sim on the scenario below (a test_random_shots layout shot)";
			h.def = *shot_def;
			h.n = s.n;
			pool_ball_state initial[16];
			for (int i = 0; i < s.n; ++i) {
				h.balls[i] = s.balls[i];
				initial[i] = s.balls[i];
				initial[i].motion = POOL_MOTION_STATIONARY; // at rest: the library derives the same
			}
			h.strike = s.strike;
			h.speed = s.strike.speed;
			h.phi_deg = s.strike.phi / HS_DEG;
			h.theta_deg = s.strike.theta / HS_DEG;
			h.a = s.strike.a;
			h.b = s.strike.b;
			hs_report rep;
			memset(&rep, 0, sizeof rep);
			hst.shots++;
			hst.class_shots[HS_LAYOUT]++;
			hs_check(sim, &h, initial, &hst, &rep);
			if (rep.mask) {
				hst.failed_shots++;
				if (hst.failed_shots <= 3)
					hs_print_report(stdout, &h, &rep);
			}
		}
		if (k % 50 == 0) { // determinism: a fresh run gives the same events and states, bit for bit
			run_shot(again, shot_def, &s);
			int n1, n2;
			const pool_event *e1 = pool_sim_events(sim, &n1), *e2 = pool_sim_events(again, &n2);
			assert_int_equal(n1, n2);
			assert_memory_equal(e1, e2, sizeof(pool_event) * (size_t)n1);
			for (int e = 0; e < n1; ++e)
				assert_memory_equal(pool_sim_event_states(sim, &e1[e]), pool_sim_event_states(again, &e2[e]),
				                    sizeof(pool_ball_state) * (size_t)e1[e].ball_count);
			++reruns;
		}
	}
	printf("random shots: %d (%d rerun), events %ld (max %d per shot), link events %ld, worst overlap %.3g m, "
	       "worst rail %.3g m, worst energy gain %.3g J, worst momentum error %.3g\n",
	       shots, reruns, st.events, st.max_events, st.linked, st.worst_overlap, st.worst_rail, st.worst_energy,
	       st.worst_momentum);
	hs_print_summary(stdout, "random shots under hostile.h's checks", &hst);
	assert_int_equal(hst.failed_shots, 0);
	assert_true(st.worst_overlap <= 1e-9);
	assert_true(st.worst_rail <= 1e-9);
	assert_true(st.worst_energy <= 1e-15);
	assert_true(st.worst_momentum <= 1e-12);
	assert_true(st.max_events < def.max_events);
	pool_sim_destroy(sim);
	pool_sim_destroy(again);
}

static void test_hostile_shots(void **state) {
	(void)state;
	int shots = DEFAULT_HOSTILE_SHOTS, classes[HS_CLASS_COUNT], n_classes = 0;
	const char *env = getenv("POOL_TEST_HOSTILE_SHOTS");
	if (env && atoi(env) > 0)
		shots = atoi(env);
	uint64_t seed = 1;
	env = getenv("POOL_TEST_HOSTILE_SEED");
	if (env && *env)
		seed = strtoull(env, NULL, 0);
	env = getenv("POOL_TEST_HOSTILE");
	char list[512];
	snprintf(list, sizeof list, "%s", env && *env ? env : DEFAULT_HOSTILE_CLASSES);
	if (strcmp(list, "all") == 0)
		for (int c = 0; c < HS_CLASS_COUNT; ++c)
			classes[n_classes++] = c;
	else
		for (char *tok = strtok(list, ","); tok && n_classes < HS_CLASS_COUNT; tok = strtok(NULL, ",")) {
			int c = hs_class_from_name(tok);
			if (c < 0)
				fail_msg("POOL_TEST_HOSTILE: unknown class '%s'", tok);
			classes[n_classes++] = c;
		}
	pool_sim_def def = pool_default_sim_def();
	// The thesis model's pockets: check_positions and hostile.h's checks are its contact lines
	// and mouths (pockets "jaws": test_jaws_shots.c).
	def.table.pockets = POOL_POCKETS_MOUTH_LINES;
	pool_sim *sim, *again;
	assert_int_equal(pool_sim_create(&def, &sim, NULL), POOL_OK);
	assert_int_equal(pool_sim_create(&def, &again, NULL), POOL_OK);
	static hs_stats st;
	memset(&st, 0, sizeof st);
	int reports = 0;
	for (int k = 0; k < shots; ++k) {
		hs_shot s;
		hs_report rep;
		hs_make(&s, seed, k, classes[k % n_classes]);
		hs_shot_run_check(sim, k % 20 == 0 ? again : NULL, &s, &st, &rep);
		if (rep.mask && reports++ < 3)
			hs_print_report(stdout, &s, &rep);
	}
	hs_print_summary(stdout, "hostile shots", &st);
	assert_int_equal(st.failed_shots, 0); // every class, none tolerated
	pool_sim_destroy(sim);
	pool_sim_destroy(again);
}

// A ball on the line of a corner mouth thrown up by a collision flies over the mouth: soak seed 1,
// nose shot 5385 (a 7 ft table, the nose 2e-12 m above the ball's centre). Ball 1 lies 1e-9 m
// inside the east contact line and on the north one, both over the north-east mouth; ball 2's
// hit at t = 7.9e-10 s sends it out across the east line at 1.02 m/s and up at 1.2 cm/s, so it
// crosses that line 1.2e-11 m above the cloth, 1e-11 m above the nose: in flight, above the
// nose, it flies on over the mouth and drops into the pocket where it lands, 2 v_z / g later.
// The soak's check took a ball within POOL_TOUCH_TOLERANCE of the cloth for one on it and failed
// the shot (2.8e-9 m past the line); whether a ball flies is its motion, and hs_mouth_crossing
// checks the height at which a flight crossed a mouth's line.
static void test_flight_over_a_mouth(void **state) {
	(void)state;
	hs_shot s;
	memset(&s, 0, sizeof s);
	s.cls = HS_NOSE;
	s.seed = 1;
	s.index = 5385;
	s.origin = "test_random_shots.c: test_flight_over_a_mouth";
	s.def = pool_default_sim_def();
	pool_table_def *t = &s.def.table;
	t->length = 1.9811999999999999;
	t->width = 0.99059999999999993;
	t->cushion_height = 0.028575000001969376;
	t->corner_mouth = 0.1143;
	t->side_mouth = 0.127;
	t->pockets = POOL_POCKETS_MOUTH_LINES;
	const pool_params *p = &s.def.params; // the defaults: the nose class draws only the table
	s.def.airborne = true;
	s.def.max_time = 60;
	s.def.max_events = 20000;
	const double R = p->ball_radius, h = t->cushion_height;
	const pool_ball_state balls[4] = {
	    {.id = 0, .pos = {1.9526249999999998, 0.1474287308511753, R}, .vel = {1.7637375306639954e-07, 5.8207660913467407e-11, 0},
	     .omega = {17.601200516553597, 6.4405117128685383, 0}},
	    {.id = 1, .pos = {1.9526249989999998, 0.96202499999999991, R}, .vel = {-1.8189894035458565e-12, -2.3274810654129219, 0},
	     .omega = {79.912517721753346, 2.068984752486295, 0}},
	    {.id = 2, .pos = {1.9046514431383008, 0.93096601495083164, R}, .vel = {7.071205030357851e-10, 4.5780315295083514e-10, 0}},
	    {.id = 3, .pos = {1.675050462056096, 0.38616610900406306, R}}};
	memcpy(s.balls, balls, sizeof balls);
	s.n = 4;
	s.cue = 3;
	s.speed = 0.0020396482034417533;
	s.phi_deg = 159.6285430304813;
	s.theta_deg = 71.840765146727847;
	s.b = -0.02250180945290977;
	const pool_strike strike = {s.speed, s.phi_deg * M_PI / 180.0, s.theta_deg * M_PI / 180.0, 0.0, s.b};
	s.strike = strike;

	pool_sim *sim;
	assert_int_equal(pool_sim_create(&s.def, &sim, NULL), POOL_OK);
	static hs_stats st;
	memset(&st, 0, sizeof st);
	hs_report rep;
	hs_shot_run_check(sim, NULL, &s, &st, &rep);
	if (rep.mask)
		hs_print_report(stdout, &s, &rep);
	assert_int_equal(rep.mask, 0);

	// The flight, from ball 1's launch: its crossing of the east line, its landing and pocket.
	int ne;
	const pool_event *ev = pool_sim_events(sim, &ne);
	pool_ball_state launch;
	double t_launch = -1.0, t_pocket = -1.0;
	pool_pocket pocket = POOL_POCKET_NONE;
	for (int e = 0; e < ne; ++e) {
		const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
		const int k = find_ball(after, ev[e].ball_count, 1);
		if (k < 0)
			continue;
		if (after[k].motion == POOL_MOTION_AIRBORNE && t_launch < 0.0) {
			launch = after[k];
			t_launch = ev[e].time;
		}
		if (ev[e].type == POOL_EVENT_POCKET) {
			t_pocket = ev[e].time;
			pocket = ev[e].pocket;
		}
	}
	assert_true(t_launch >= 0.0 && launch.vel.z > 0.0 && launch.vel.x > 0.0);
	const double L = t->length, dc = hs_dc(&s.def);
	const double tau_cross = (L - dc - launch.pos.x) / launch.vel.x;
	const double z_cross = launch.pos.z + launch.vel.z * tau_cross - 0.5 * p->g * tau_cross * tau_cross;
	const double flight = 2.0 * launch.vel.z / p->g; // back on the cloth (z = R): where it lands
	printf("flight over a mouth: launched at t = %.6g s, v_z %.6g m/s; crosses the line %.3g m above the nose; "
	       "pocket %s at t = %.9g s (landing %.9g s)\n",
	       t_launch, launch.vel.z, z_cross - h, pool_pocket_name(pocket), t_pocket, t_launch + flight);
	assert_true(z_cross > h); // above the nose: not a pocket at the line
	assert_int_equal(pocket, POOL_POCKET_NE);
	assert_true(fabs(t_pocket - (t_launch + flight)) <= 1e-12 * flight + 1e-15);
	// The check itself: under a real nose (1.27 R) the same flight crosses the line 0.27 R below
	// it, where the ball falls into the pocket; the check must see it fly on.
	pool_sim_def high = s.def;
	high.table.cushion_height = 1.27 * R;
	const double dc_high = hs_dc(&high);
	pool_ball_state inside = launch;
	inside.pos.x = L - dc_high - 1e-3; // (inside that nose's contact line, 0.96 R from the edge)
	const double tau_high = 1e-3 / launch.vel.x;
	assert_true(hs_mouth_crossing(&high, dc_high, &inside, 2.0 * tau_high) > 0.25 * R);
	assert_true(hs_mouth_crossing(&high, dc_high, &inside, 0.5 * tau_high) == -INFINITY); // not across yet
	assert_true(hs_mouth_crossing(&s.def, dc, &launch, 2.0 * tau_cross) < 0.0); // this shot's: above it
	pool_sim_destroy(sim);
}

int main(void) {
	const struct CMUnitTest tests[] = {cmocka_unit_test(test_random_shots), cmocka_unit_test(test_hostile_shots),
	                                   cmocka_unit_test(test_flight_over_a_mouth)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
