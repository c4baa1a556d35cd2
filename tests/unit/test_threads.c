// libpool holds no global state, so AI players can simulate candidate shots on every core with
// one pool_sim per thread: shots run concurrently give, bit for bit, the results they give one
// after the other (events, the states after them, final states, stop reasons), while the threads
// share one read-only pool_sim_def.
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "pool/pool.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#if defined(__SANITIZE_ADDRESS__)
#define SHOTS 200 // ASan+UBSan Debug build
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHOTS 200
#endif
#endif
#ifndef SHOTS
#define SHOTS 1200
#endif
#define THREADS 4

typedef struct candidate {
	pool_ball_state balls[16];
	int n;
	pool_strike strike;
} candidate;

static candidate shots[SHOTS];
static uint64_t sequential[SHOTS], concurrent[SHOTS];
static const pool_sim_def *shared_def;

// FNV-1a over bytes: a fingerprint of everything a shot produced.
static uint64_t fnv(uint64_t h, const void *data, size_t size) {
	const unsigned char *p = data;
	for (size_t i = 0; i < size; ++i)
		h = (h ^ p[i]) * 0x100000001B3ull;
	return h;
}

static uint64_t hash_state(uint64_t h, const pool_ball_state *s) {
	const int32_t motion = (int32_t)s->motion;
	h = fnv(h, &s->id, sizeof s->id);
	h = fnv(h, &motion, sizeof motion);
	const double v[9] = {s->pos.x, s->pos.y, s->pos.z, s->vel.x, s->vel.y, s->vel.z, s->omega.x, s->omega.y, s->omega.z};
	return fnv(h, v, sizeof v);
}

// Simulates shot i on sim and returns its fingerprint (0 when the library failed).
static uint64_t simulate(pool_sim *sim, int i) {
	const candidate *c = &shots[i];
	if (pool_sim_reset(sim, NULL, NULL) != POOL_OK)
		return 0;
	for (int k = 0; k < c->n; ++k)
		if (pool_sim_add_ball(sim, &c->balls[k], NULL) != POOL_OK)
			return 0;
	if (pool_sim_strike(sim, c->balls[0].id, &c->strike, NULL) != POOL_OK || pool_sim_run(sim) != POOL_OK)
		return 0;
	uint64_t h = 0xCBF29CE484222325ull;
	int count = 0;
	const pool_event *ev = pool_sim_events(sim, &count);
	for (int e = 0; e < count; ++e) {
		const int32_t fields[4] = {(int32_t)ev[e].type, (int32_t)ev[e].rail, (int32_t)ev[e].pocket, ev[e].ball_count};
		h = fnv(h, &ev[e].time, sizeof ev[e].time);
		h = fnv(h, fields, sizeof fields);
		const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
		for (int k = 0; k < ev[e].ball_count; ++k)
			h = hash_state(h, &after[k]);
	}
	const pool_ball_state *final = pool_sim_balls(sim);
	for (int k = 0; k < pool_sim_ball_count(sim); ++k)
		h = hash_state(h, &final[k]);
	const int32_t stop = (int32_t)pool_sim_stop_reason(sim);
	return fnv(h, &stop, sizeof stop) | 1u; // never 0, which means failure
}

static uint64_t rng = 0xD1B54A32D192ED03ull;
static double urand(void) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

// Candidate shots an AI player might try: breaks and cue-ball strikes into a rack with a gap,
// random speed (0.3-8 m/s), aim, elevation and tip offset.
static void make_shots(const pool_sim_def *def) {
	const double R = def->params.ball_radius;
	for (int i = 0; i < SHOTS; ++i) {
		candidate *c = &shots[i];
		c->n = pool_rack(i % 2 ? POOL_RACK_9BALL : POOL_RACK_8BALL, &def->table, &def->params, i % 3 ? 1e-4 : 0.0,
		                 c->balls, 16);
		const double r = 0.6 * R * sqrt(urand()), a = 2.0 * M_PI * urand();
		c->strike = (pool_strike){0.3 + 7.7 * urand(), (urand() - 0.5) * 0.6, urand() < 0.7 ? 0.0 : 0.4 * urand(),
		                          r * cos(a), r * sin(a)};
	}
}

typedef struct worker {
	int first; // this worker takes shots first, first + THREADS, ...
	int failed;
} worker;

static void *run_worker(void *arg) {
	worker *w = arg;
	pool_sim *sim;
	if (pool_sim_create(shared_def, &sim, NULL) != POOL_OK) {
		w->failed = 1;
		return NULL;
	}
	for (int i = w->first; i < SHOTS; i += THREADS)
		concurrent[i] = simulate(sim, i);
	pool_sim_destroy(sim);
	return NULL;
}

static void test_concurrent_shots_match_sequential(void **state) {
	(void)state;
	static pool_sim_def def;
	def = pool_default_sim_def();
	shared_def = &def;
	make_shots(&def);

	pool_sim *sim;
	assert_int_equal(pool_sim_create(&def, &sim, NULL), POOL_OK);
	int distinct = 0;
	for (int i = 0; i < SHOTS; ++i) {
		sequential[i] = simulate(sim, i);
		assert_true(sequential[i] != 0);
		distinct += i == 0 || sequential[i] != sequential[i - 1];
	}
	pool_sim_destroy(sim);
	assert_true(distinct > SHOTS * 9 / 10); // the fingerprints tell shots apart

	pthread_t threads[THREADS];
	worker workers[THREADS];
	for (int t = 0; t < THREADS; ++t) {
		workers[t] = (worker){t, 0};
		assert_int_equal(pthread_create(&threads[t], NULL, run_worker, &workers[t]), 0);
	}
	for (int t = 0; t < THREADS; ++t) {
		assert_int_equal(pthread_join(threads[t], NULL), 0);
		assert_false(workers[t].failed);
	}
	for (int i = 0; i < SHOTS; ++i)
		if (concurrent[i] != sequential[i])
			fail_msg("shot %d: concurrent result %016llx differs from sequential %016llx", i,
			         (unsigned long long)concurrent[i], (unsigned long long)sequential[i]);
}

int main(void) {
	const struct CMUnitTest tests[] = {cmocka_unit_test(test_concurrent_shots_match_sequential)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
