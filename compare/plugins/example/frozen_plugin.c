// The smallest complete engine plugin: a "frozen" engine whose balls never move (the strike is
// ignored). It shows the whole ABI of compare/include/pool_engine_plugin.h; a real engine builds
// its world in create() and steps it in advance() / run_to_rest().
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pool_engine_plugin.h"
#include "pool/scenario.h"

typedef struct frozen {
	pool_scenario scenario; // the parsed libpool-scenario/1 document
	double now;             // s
} frozen;

static void *create(const char *json, const pool_engine_config *config, char *err, size_t err_size) {
	(void)config;
	frozen *f = calloc(1, sizeof *f);
	if (!f) {
		snprintf(err, err_size, "frozen: out of memory");
		return NULL;
	}
	if (pool_scenario_parse(json, strlen(json), &f->scenario, err, err_size) != 0) {
		free(f);
		return NULL;
	}
	return f;
}

static int advance(void *engine, double t) {
	((frozen *)engine)->now = t;
	return 0;
}

static int run_to_rest(void *engine, double max_time) {
	(void)engine; // already at rest
	(void)max_time;
	return 0;
}

static int balls(void *engine, pool_engine_ball *out, int capacity) {
	const frozen *f = engine;
	for (int i = 0; i < f->scenario.ball_count && i < capacity; ++i) {
		const pool_ball_state *b = &f->scenario.balls[i];
		out[i] = (pool_engine_ball){.id = b->id, .state = 0, .pos = {b->pos.x, b->pos.y, b->pos.z}};
	}
	return f->scenario.ball_count;
}

static int events(void *engine, pool_engine_event *out, int capacity) {
	(void)engine; // nothing ever happens
	(void)out;
	(void)capacity;
	return 0;
}

static void stats(void *engine, pool_engine_stats *out) {
	*out = (pool_engine_stats){.steps = 0, .max_penetration = 0.0, .sim_time = ((frozen *)engine)->now};
}

static const char *last_error(void *engine) {
	(void)engine;
	return "";
}

static void destroy(void *engine) {
	frozen *f = engine;
	if (f)
		pool_scenario_free(&f->scenario);
	free(f);
}

static const pool_engine_api api = {
	.abi_version = POOL_ENGINE_ABI_VERSION,
	.name = "frozen",
	.description = "example plugin: balls never move (models nothing)",
	.event_driven = 1,
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
