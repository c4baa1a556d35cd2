// The broadphase (broadphase.h): the grid leaves out only pairs the all-pairs loop rejects, so a
// shot gives the same events bit for bit with either search. Oracles: the all-pairs search itself
// (every event, its states and the final states compared byte for byte) on random shots of 2 to
// 200 balls (racks, layouts, crowds on larger tables, airborne shots, low restitution that forms
// LINK clusters), the soak's hostile classes and the scale scenes; the geometry against sampled
// distances (a ball that comes within 2R of another over a window is never left out); the choice
// by ball count; and a grid that runs out of memory hands back to all pairs with the same events.
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

#include "../soak/hostile.h"
#include "broadphase.h"
#include "pool/pool.h"
#include "scale_scene.h"
#include "schedule.h"
#include "world.h"

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SANITIZED 1
#endif
#endif
#ifdef SANITIZED
#define RANDOM_SHOTS 1000 // ASan+UBSan Debug build: the same checks on fewer shots
#define HOSTILE_SHOTS 240
#else
#define RANDOM_SHOTS 10000
#define HOSTILE_SHOTS 2400
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAX_BALLS 256

static uint64_t rng = 0xB40ADFA5E5EEDull;
static double urand(void) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct shot {
	pool_sim_def def;
	pool_ball_state balls[MAX_BALLS];
	int n;
	int struck; // index of the struck ball, -1: none
	pool_strike strike;
} shot;

// Sets the shot up with the given search, ready to run.
static void start(pool_sim *sim, const shot *s, pool_broadphase_mode mode) {
	assert_int_equal(pool_sim_reset(sim, &s->def, NULL), POOL_OK);
	pool_schedule_set_broadphase(sim, mode);
	for (int i = 0; i < s->n; ++i)
		add_ball(sim, &s->balls[i]);
	if (s->struck >= 0)
		assert_int_equal(pool_sim_strike(sim, s->balls[s->struck].id, &s->strike, NULL), POOL_OK);
}

// Runs the shot with the given search; the run's result.
static pool_result run(pool_sim *sim, const shot *s, pool_broadphase_mode mode) {
	start(sim, s, mode);
	return pool_sim_run(sim);
}

// Every event, its states and the final states, byte for byte.
static void assert_same(const pool_sim *a, const pool_sim *b, const char *what, long index) {
	int na, nb;
	const pool_event *ea = pool_sim_events(a, &na), *eb = pool_sim_events(b, &nb);
	if (na != nb)
		fail_msg("%s %ld: %d events with all pairs, %d with the grid", what, index, na, nb);
	for (int e = 0; e < na; ++e)
		if (memcmp(&ea[e], &eb[e], sizeof ea[e]) != 0 ||
		    memcmp(pool_sim_event_states(a, &ea[e]), pool_sim_event_states(b, &eb[e]),
		           sizeof(pool_ball_state) * (size_t)ea[e].ball_count) != 0)
			fail_msg("%s %ld: event %d (t = %.17g) differs", what, index, e, ea[e].time);
	assert_int_equal(pool_sim_ball_count(a), pool_sim_ball_count(b));
	assert_memory_equal(pool_sim_balls(a), pool_sim_balls(b), sizeof(pool_ball_state) * (size_t)pool_sim_ball_count(a));
	assert_int_equal(pool_sim_stop_reason(a), pool_sim_stop_reason(b));
}

// A ball at a random free place (margin from the contact lines), or -1 after many tries.
static int add_random_ball(shot *s, double margin) {
	const double R = s->def.params.ball_radius, dc = pool_table_contact_distance(&s->def.table, R);
	for (int tries = 0; tries < 500; ++tries) {
		const pool_vec3 p = {dc + margin + urand() * (s->def.table.length - 2.0 * (dc + margin)),
		                     dc + margin + urand() * (s->def.table.width - 2.0 * (dc + margin)), R};
		int ok = 1;
		for (int j = 0; j < s->n && ok; ++j)
			ok = hypot(p.x - s->balls[j].pos.x, p.y - s->balls[j].pos.y) >= 2.0 * R;
		if (!ok)
			continue;
		pool_ball_state *b = &s->balls[s->n];
		memset(b, 0, sizeof *b);
		b->id = s->n;
		b->pos = p;
		return s->n++;
	}
	return -1;
}

// Random shots: racks (frozen or with a gap), layouts of 2-16 balls, crowds of 20-200 balls on
// tables of up to 16 standard areas with a random share of them moving (rolling, sliding,
// spinning), airborne shots with elevated cues, and low ball restitution (LINK clusters).
static void make_shot(long index, shot *s) {
	memset(s, 0, sizeof *s);
	s->def = pool_default_sim_def();
	s->def.max_time = 30.0;
	const double R = s->def.params.ball_radius;
	const int kind = (int)(index % 4);
	if (kind == 3) { // a crowd on a larger table
		const double scale = 1.0 + urand() * 3.0;
		s->def.table.length *= scale;
		s->def.table.width *= scale;
	}
	if (urand() < 0.15)
		s->def.airborne = true;
	if (urand() < 0.1)
		s->def.params.e_ball = 0.05 + 0.5 * urand();
	if (kind == 0) {
		s->n = pool_rack(urand() < 0.7 ? POOL_RACK_8BALL : POOL_RACK_9BALL, &s->def.table, &s->def.params,
		                 urand() < 0.5 ? 0.0 : urand() * 2e-3, s->balls, MAX_BALLS);
	} else {
		const int want = kind == 3 ? 20 + (int)(urand() * 181) : 2 + (int)(urand() * 15);
		while (s->n < want && add_random_ball(s, 0.0) >= 0) {
		}
		if (kind == 3) // a share of the crowd already moving
			for (int i = 1; i < s->n; ++i) {
				if (urand() > 0.4)
					continue;
				pool_ball_state *b = &s->balls[i];
				const double v = 3.0 * urand(), a = 2.0 * M_PI * urand();
				b->vel = (pool_vec3){v * cos(a), v * sin(a), 0.0};
				const double kind_of_spin = urand();
				if (kind_of_spin < 0.5) // rolling
					b->omega = (pool_vec3){-b->vel.y / R, b->vel.x / R, 0.0};
				else if (kind_of_spin < 0.8) // sliding with side spin
					b->omega = (pool_vec3){20.0 * (urand() - 0.5), 20.0 * (urand() - 0.5), 40.0 * (urand() - 0.5)};
				else { // spinning in place
					b->vel = (pool_vec3){0.0, 0.0, 0.0};
					b->omega = (pool_vec3){0.0, 0.0, 30.0 * (urand() - 0.5)};
				}
			}
	}
	s->struck = 0;
	s->strike.speed = 0.05 + urand() * 7.95;
	s->strike.phi = urand() * 2.0 * M_PI;
	s->strike.theta = s->def.airborne && urand() < 0.7 ? urand() * 1.2 : 0.0;
	const double r = 0.9 * R * sqrt(urand()), a = urand() * 2.0 * M_PI;
	s->strike.a = r * cos(a);
	s->strike.b = r * sin(a);
}

static void test_random_shots_same_events(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	pool_sim *all = make_sim(&def), *grid = make_sim(&def);
	static shot s;
	long events = 0, grid_shots = 0, failed = 0;
	for (long k = 0; k < RANDOM_SHOTS; ++k) {
		make_shot(k, &s);
		const pool_result ra = run(all, &s, POOL_BROADPHASE_ALL_PAIRS), rg = run(grid, &s, POOL_BROADPHASE_GRID);
		assert_int_equal(ra, rg);
		failed += ra != POOL_OK;
		grid_shots += grid->broad.on; // the grid still on at the end: it served the whole shot
		assert_same(all, grid, "random shot", k);
		int n;
		pool_sim_events(all, &n);
		events += n;
	}
	printf("random shots: %d, events %ld, all on the grid to the end %ld, failed runs (both alike) %ld\n",
	       RANDOM_SHOTS, events, grid_shots, failed);
	assert_true(grid_shots > RANDOM_SHOTS * 9 / 10);
	pool_sim_destroy(all);
	pool_sim_destroy(grid);
}

static void test_hostile_same_events(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	pool_sim *all = make_sim(&def), *grid = make_sim(&def);
	static hs_shot h;
	static shot s;
	long events = 0, refused = 0;
	for (long k = 0; k < HOSTILE_SHOTS; ++k) {
		hs_make(&h, 23, k, (int)(k % HS_CLASS_COUNT));
		s.def = h.def;
		s.n = h.n;
		memcpy(s.balls, h.balls, sizeof(pool_ball_state) * (size_t)h.n);
		s.struck = h.cue;
		s.strike = h.strike;
		// Tables the library refuses at validation (the nose class's noses outside (R, 1.9 R],
		// docs/physics.md) run on neither search.
		if (pool_sim_reset(all, &s.def, NULL) != POOL_OK) {
			refused++;
			continue;
		}
		const pool_result ra = run(all, &s, POOL_BROADPHASE_ALL_PAIRS), rg = run(grid, &s, POOL_BROADPHASE_GRID);
		assert_int_equal(ra, rg);
		assert_same(all, grid, hs_class_names[h.cls], k);
		int n;
		pool_sim_events(all, &n);
		events += n;
	}
	printf("hostile shots: %d (%ld refused at validation), events %ld, the same with both searches\n", HOSTILE_SHOTS, refused, events);
	pool_sim_destroy(all);
	pool_sim_destroy(grid);
}

static void scale_shot(const char *family, int n, shot *s) {
	memset(s, 0, sizeof *s);
	s->def = pool_default_sim_def();
	s->def.max_time = 2.0;
	s->n = n;
	bool has_strike;
	char err[128];
	assert_int_equal(pool_scale_scene(family, n, &s->def.params, &s->def.table, s->balls, &has_strike, &s->strike, err,
	                                  sizeof err),
	                 0);
	s->struck = has_strike ? 0 : -1;
}

static void test_scale_scenes_same_events(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	pool_sim *all = make_sim(&def), *grid = make_sim(&def);
	static shot s;
	const char *families[] = {"gas", "break"};
	for (int f = 0; f < 2; ++f)
		for (int n = 64; n <= MAX_BALLS; n *= 2) {
			scale_shot(families[f], n, &s);
			assert_int_equal(run(all, &s, POOL_BROADPHASE_ALL_PAIRS), POOL_OK);
			assert_int_equal(run(grid, &s, POOL_BROADPHASE_GRID), POOL_OK);
			assert_true(grid->broad.on);
			assert_same(all, grid, families[f], n);
		}
	pool_sim_destroy(all);
	pool_sim_destroy(grid);
}

// The default search is all pairs below POOL_BROADPHASE_MIN_BALLS balls and the grid from there;
// the partner lists (who is waiting on whom) are kept at every ball count.
static void test_auto_by_ball_count(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim = make_sim(&def);
	static shot s;
	// (A scale scene has 2 balls at least: the verification build's threshold is 2.)
	for (int n = POOL_BROADPHASE_MIN_BALLS > 2 ? POOL_BROADPHASE_MIN_BALLS - 1 : 2; n <= POOL_BROADPHASE_MIN_BALLS; ++n) {
		scale_shot("gas", n, &s);
		assert_int_equal(run(sim, &s, POOL_BROADPHASE_AUTO), POOL_OK);
		assert_int_equal(sim->broad.on, n >= POOL_BROADPHASE_MIN_BALLS);
		assert_int_equal(sim->broad.watching, 1);
	}
	pool_sim_destroy(sim);
}

// An allocator that refuses every request once armed and `allowed` more have been served.
typedef struct rationed {
	int armed;
	long allowed;
} rationed;
static void *rationed_alloc(size_t size, void *ctx) {
	rationed *r = ctx;
	if (r->armed && r->allowed-- <= 0)
		return NULL;
	return malloc(size);
}
static void rationed_free(void *p, void *ctx) {
	(void)ctx;
	free(p);
}

// Runs the shot with the grid under an allocator that refuses every request after `allowed`
// more, for each allowed in [0, max_allowed]: out of memory for the grid is no error, the schedule
// goes back to all pairs and the shot's events must be those of all pairs. Counts the runs whose
// grid was off after the first event (*at_start) and those whose grid turned off later (*mid_shot).
static void rationed_runs(shot *s, long max_allowed, int *at_start, int *mid_shot) {
	pool_sim_def def = pool_default_sim_def();
	pool_sim *all = make_sim(&def);
	assert_int_equal(run(all, s, POOL_BROADPHASE_ALL_PAIRS), POOL_OK);
	*at_start = *mid_shot = 0;
	for (long allowed = 0; allowed <= max_allowed; ++allowed) {
		rationed r = {0, 0};
		s->def.allocator = (pool_allocator){rationed_alloc, rationed_free, &r};
		pool_sim *sim = make_sim(&s->def);
		// The history and LINK's arrays grow in a first run with all pairs; the grid's then
		// allocates in the second, with `allowed` blocks left.
		assert_int_equal(run(sim, s, POOL_BROADPHASE_ALL_PAIRS), POOL_OK);
		start(sim, s, POOL_BROADPHASE_GRID);
		r.armed = 1;
		r.allowed = allowed;
		assert_int_equal(pool_sim_step(sim), 1); // the first prediction and the first event
		const int on_after_first = sim->broad.on;
		assert_int_equal(pool_sim_run(sim), POOL_OK);
		*at_start += !on_after_first;
		*mid_shot += on_after_first && !sim->broad.on;
		assert_same(all, sim, "rationed", allowed);
		r.armed = 0;
		pool_sim_destroy(sim);
	}
	s->def.allocator = (pool_allocator){0};
	pool_sim_destroy(all);
}

// Out of memory at the start of a shot: the grid's cells, then its entries refused.
static void test_out_of_memory_falls_back(void **state) {
	(void)state;
	static shot s;
	scale_shot("gas", 256, &s);
	int at_start, mid_shot;
	rationed_runs(&s, 12, &at_start, &mid_shot);
	assert_true(at_start >= 2);
}

// The grid turning off mid-shot (its entries cannot grow after the first prediction filed every
// ball) hands the rest of the shot to all pairs with every reach box filed again: a crowd with
// every other ball rolling on a table of 4 standard areas and the cue ball struck hard, so that
// the balls set moving file long paths.
static void test_out_of_memory_mid_shot(void **state) {
	(void)state;
	static shot s;
	memset(&s, 0, sizeof s);
	s.def = pool_default_sim_def();
	s.def.max_time = 10.0;
	s.def.table.length *= 2.0;
	s.def.table.width *= 2.0;
	while (s.n < 40 && add_random_ball(&s, 0.0) >= 0) {
	}
	const double R = s.def.params.ball_radius;
	for (int i = 1; i < s.n; i += 2) {
		const double v = 1.0 + 3.0 * urand(), a = 2.0 * M_PI * urand();
		s.balls[i].vel = (pool_vec3){v * cos(a), v * sin(a), 0.0};
		s.balls[i].omega = (pool_vec3){-s.balls[i].vel.y / R, s.balls[i].vel.x / R, 0.0};
	}
	s.struck = 0;
	s.strike = (pool_strike){.speed = 8.0, .phi = 0.3, .a = 0.0, .b = 0.01};
	int at_start, mid_shot;
	rationed_runs(&s, 8, &at_start, &mid_shot);
	printf("out of memory mid-shot: the grid turned off after the first event in %d of 9 runs\n", mid_shot);
	assert_true(mid_shot >= 1);
}

// The geometry alone: ball j's segment filed over its window, ball i's path queried over another;
// whenever dense sampling finds the two within 2R at a common instant, j is among i's candidates.
static void test_query_finds_every_near_ball(void **state) {
	(void)state;
	const pool_allocator a = {rationed_alloc, rationed_free, &(rationed){0, 0}};
	pool_params p = pool_default_params();
	pool_table_def table = pool_default_table_def();
	table.length *= 2.0;
	table.width *= 2.0;
	const double R = p.ball_radius;
	pool_broadphase bp;
	memset(&bp, 0, sizeof bp);
	pool_broadphase_set_mode(&bp, POOL_BROADPHASE_GRID);
	int near = 0, left_out = 0, near_filed = 0;
	for (int k = 0; k < 40000; ++k) {
		assert_true(pool_broadphase_begin(&bp, &a, &table, R, 2));
		pool_segment seg[2];
		double from[2], to[2];
		for (int b = 0; b < 2; ++b) {
			pool_ball_state s;
			memset(&s, 0, sizeof s);
			// Both in a 0.6 m square in the middle: many pairs meet, many do not.
			s.pos = (pool_vec3){0.5 * table.length + 0.6 * (urand() - 0.5), 0.5 * table.width + 0.6 * (urand() - 0.5), R};
			if (urand() < 0.8) {
				// Half of the second balls head roughly for the first: near misses and hits.
				double ang = 2.0 * M_PI * urand();
				if (b == 1 && urand() < 0.5)
					ang = atan2(seg[0].start.pos.y - s.pos.y, seg[0].start.pos.x - s.pos.x) + 0.3 * (urand() - 0.5);
				const double v = 4.0 * urand();
				s.vel = (pool_vec3){v * cos(ang), v * sin(ang), 0.0};
				s.omega = (pool_vec3){60.0 * (urand() - 0.5), 60.0 * (urand() - 0.5), 0.0};
			}
			s.motion = pool_v3_len(s.vel) > 0.0 ? POOL_MOTION_SLIDING : POOL_MOTION_STATIONARY;
			from[b] = 0.2 * urand();
			pool_segment_begin(&seg[b], &p, &s, from[b]);
			to[b] = from[b] + fmin(3.0 * urand(), seg[b].move_end);
		}
		pool_broadphase_place(&bp, &a, 1, &seg[1], 1, from[1], to[1]);
		// The schedule asks from an instant of i's segment up to its own next event at the latest.
		// Half the queries come from ball i's own entries (its segment filed over its window, as
		// the schedule files every ball), half cut its path (a ball filed over another window).
		const int filed = k % 2;
		if (filed)
			pool_broadphase_place(&bp, &a, 0, &seg[0], 1, from[0], to[0]);
		const double now = from[0] + urand() * (to[0] - from[0]), horizon = to[0];
		const int count = pool_broadphase_query(&bp, 0, &seg[0], now, horizon);
		assert_true(count == 0 || (count == 1 && bp.found[0] == 1));
		const int marked = count == 1;
		// Only moving pairs, at common instants of the two windows.
		if (!seg[0].model->translating && !seg[1].model->translating)
			continue;
		const double lo = fmax(now, from[1]), hi = fmin(horizon, to[1]);
		double closest = INFINITY;
		for (int m = 0; m <= 2000 && lo <= hi; ++m) {
			const double t = lo + (hi - lo) * m / 2000.0;
			pool_vec3 pi, pj, vi, vj;
			pool_segment_path(&seg[0], t - seg[0].t0, &pi, &vi);
			pool_segment_path(&seg[1], t - seg[1].t0, &pj, &vj);
			closest = fmin(closest, hypot(pi.x - pj.x, pi.y - pj.y));
		}
		if (closest <= 2.0 * R) {
			++near;
			near_filed += filed;
			if (!marked)
				fail_msg("case %d: the balls come %.6g m apart, the query left ball 1 out", k, closest);
		} else if (!marked) {
			++left_out;
		}
	}
	printf("geometry: %d near pairs all found (%d from filed entries); %d of 40000 pairs left out\n", near, near_filed,
	       left_out);
	assert_true(near > 1000 && near_filed > 500 && left_out > 10000);
	pool_broadphase_free(&bp, &a);
}

int main(void) {
	const struct CMUnitTest tests[] = {
	    cmocka_unit_test(test_query_finds_every_near_ball),
	    cmocka_unit_test(test_auto_by_ball_count),
	    cmocka_unit_test(test_out_of_memory_falls_back),
	    cmocka_unit_test(test_out_of_memory_mid_shot),
	    cmocka_unit_test(test_scale_scenes_same_events),
	    cmocka_unit_test(test_random_shots_same_events),
	    cmocka_unit_test(test_hostile_same_events),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
