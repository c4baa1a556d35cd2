// A deliberately misbehaving engine plugin for the isolation tests of pool-compare: like the
// frozen example (balls never move) unless it is told to fail. What it does is chosen by the
// environment variable POOL_FAULTY_MODE, else by the time step it is created with, so that one
// pool-compare run (--dt 1e-3,2e-3,...,1e-2) meets every failure:
//
//   dt    mode       what the plugin does
//   1e-3  ok         works (a frozen engine)
//   2e-3  segv       writes through a null pointer in advance()            -> killed by SIGSEGV
//   3e-3  abort      abort() in advance()                                  -> killed by SIGABRT
//   4e-3  exit3      exit(3) in advance()                                  -> exit(3)
//   5e-3  hang       sleeps forever in advance()                           -> timed out after N s
//   6e-3  nan        ball positions NaN once time has advanced             -> non-finite state
//   7e-3  inf        velocities +inf once time has advanced                -> non-finite state
//   8e-3  overcount  balls() reports one ball more than the scenario has   -> an error row
//   9e-3  unwritten  balls() reports every ball and writes none of them    -> an error row
//   1e-2  badevents  events() reports 5 events and writes none             -> an error row
//
// Any other dt: ok. It lives with the test modules (compare/test-plugins), not the engines.
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pool_engine_plugin.h"
#include "pool/scenario.h"

typedef enum { OK, SEGV, ABORT, EXIT3, HANG, NAN_STATE, INF_STATE, OVERCOUNT, UNWRITTEN, BAD_EVENTS } mode;

static const char *const mode_names[] = {"ok",  "segv", "abort",     "exit3",     "hang",
                                         "nan", "inf",  "overcount", "unwritten", "badevents"};

typedef struct faulty {
	pool_scenario scenario;
	double now;
	mode mode;
} faulty;

static mode pick_mode(double dt) {
	const char *name = getenv("POOL_FAULTY_MODE");
	if (name && name[0]) {
		for (size_t i = 0; i < sizeof mode_names / sizeof mode_names[0]; ++i)
			if (strcmp(name, mode_names[i]) == 0)
				return (mode)i;
		return OK;
	}
	const long k = lround(dt * 1000.0);
	return k >= 1 && k <= 10 && fabs(dt * 1000.0 - (double)k) < 1e-6 ? (mode)(k - 1) : OK;
}

static void *create(const char *json, const pool_engine_config *config, char *err, size_t err_size) {
	faulty *f = calloc(1, sizeof *f);
	if (!f) {
		snprintf(err, err_size, "faulty: out of memory");
		return NULL;
	}
	if (pool_scenario_parse(json, strlen(json), &f->scenario, err, err_size) != 0) {
		free(f);
		return NULL;
	}
	f->mode = pick_mode(config->dt);
	return f;
}

static int advance(void *engine, double t) {
	faulty *f = engine;
	switch (f->mode) {
	case SEGV: {
		volatile int *volatile nowhere = NULL;
		*nowhere = 42;
		break;
	}
	case ABORT:
		abort();
	case EXIT3:
		exit(3);
	case HANG:
		for (;;)
			pause();
	default:
		break;
	}
	f->now = t;
	return 0;
}

static int run_to_rest(void *engine, double max_time) {
	(void)max_time;
	return advance(engine, ((faulty *)engine)->now);
}

static int balls(void *engine, pool_engine_ball *out, int capacity) {
	const faulty *f = engine;
	const int n = f->scenario.ball_count;
	if (f->mode == UNWRITTEN)
		return n;
	for (int i = 0; i < n && i < capacity; ++i) {
		const pool_ball_state *b = &f->scenario.balls[i];
		out[i] = (pool_engine_ball){.id = b->id, .state = 0, .pos = {b->pos.x, b->pos.y, b->pos.z}};
		if (f->mode == NAN_STATE && f->now > 0.0)
			out[i].pos[0] = out[i].pos[1] = NAN;
		if (f->mode == INF_STATE && f->now > 0.0)
			out[i].vel[0] = INFINITY;
	}
	return f->mode == OVERCOUNT ? n + 1 : n;
}

static int events(void *engine, pool_engine_event *out, int capacity) {
	(void)out;
	(void)capacity;
	return ((faulty *)engine)->mode == BAD_EVENTS ? 5 : 0;
}

static void stats(void *engine, pool_engine_stats *out) {
	*out = (pool_engine_stats){.steps = 0, .max_penetration = 0.0, .sim_time = ((faulty *)engine)->now};
}

static const char *last_error(void *engine) {
	(void)engine;
	return "";
}

static void destroy(void *engine) {
	faulty *f = engine;
	if (f)
		pool_scenario_free(&f->scenario);
	free(f);
}

static const pool_engine_api api = {
	.abi_version = POOL_ENGINE_ABI_VERSION,
	.name = "faulty",
	.description = "test plugin: crashes, exits, hangs or returns bad states on purpose (POOL_FAULTY_MODE or dt)",
	.event_driven = 0,
	.create = create,
	.advance = advance,
	.run_to_rest = run_to_rest,
	.balls = balls,
	.events = events,
	.stats = stats,
	.last_error = last_error,
	.destroy = destroy,
};

__attribute__((visibility("default"))) const pool_engine_api *pool_engine_plugin(void) {
	return &api;
}
