// libpool as a comparison engine: event-driven and exact, so dt is ignored. The scenario is read
// with the shared parser (tools/common/scenario.h) and set up exactly as pool-sim does.
// Every pool_sim_step is timed here (the library has no clock), so the harness can say what share
// of libpool's time its LINK steps (persistent contact) took.
#define _POSIX_C_SOURCE 200809L // clock_gettime
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pool_engine_plugin.h"
#include "pool/scenario.h"
// The LINK statistics (issue 11) arrive with pool/link.h; a libpool without it has no clusters,
// and the plugin then leaves the optional export out (its records say null).
#if __has_include("pool/link.h")
#include "pool/link.h"
#define LIBPOOL_PLUGIN_HAS_LINK 1
#endif

typedef struct libpool_engine {
	pool_scenario scenario;  // parsed document (owns the initial balls)
	pool_sim *sim;           // the simulation
	double now;              // s, the time advance/run_to_rest reached
	pool_ball_state *states; // scratch for pool_sim_state_at, ball_count long
	double max_penetration;  // m, over the ball-ball events scanned so far
	int scanned;             // events already scanned for penetration
	double step_seconds;     // s, wall-clock time of every pool_sim_step and pool_sim_run_until call
	double link_seconds;     // s, the part of it in steps that produced a LINK event
	char error[256];         // last failure
} libpool_engine;

// A failed run: what the library says it met (pool_sim_last_error: a LINK step's unsolved LCP,
// memory running out...), else the code's name.
static int fail(libpool_engine *e, pool_result r) {
	const char *said = pool_sim_last_error(e->sim);
	snprintf(e->error, sizeof e->error, "libpool: %s", said[0] ? said : pool_result_str(r));
	return -1;
}

// Interpenetration right after each ball-ball event (exact contacts give rounding only).
// The monotonic clock, not CPU time: it is read twice per event, and on Linux only the monotonic
// clock is answered without a system call (the harness's own CPU figures are process CPU time).
static double clock_now(void) {
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static bool is_link_event(pool_event_type type) {
	return type == POOL_EVENT_LINK_BEGIN || type == POOL_EVENT_LINK_STEP || type == POOL_EVENT_LINK_END;
}

// pool_sim_run_until(t), one timed pool_sim_step at a time: a step that produced a LINK event
// counts as link time. The loop stops after the first event past t (pool_sim_state_at walks the
// history back, and events() reports none past the time reached); pool_sim_run_until then only
// marks t as processed, or ends a shot with nothing left before max_time.
static pool_result run_timed(libpool_engine *e, double t) {
	while (pool_sim_stop_reason(e->sim) == POOL_STOP_NONE && pool_sim_time(e->sim) <= t) {
		int before = 0, after = 0;
		pool_sim_events(e->sim, &before);
		const double t0 = clock_now();
		const int r = pool_sim_step(e->sim);
		const double spent = clock_now() - t0;
		e->step_seconds += spent;
		if (r < 0)
			return (pool_result)r;
		const pool_event *list = pool_sim_events(e->sim, &after);
		for (int i = before; i < after; ++i)
			if (is_link_event(list[i].type)) {
				e->link_seconds += spent;
				break;
			}
		if (r == 0)
			break;
	}
	const double t0 = clock_now();
	const pool_result r = pool_sim_run_until(e->sim, t);
	e->step_seconds += clock_now() - t0;
	return r;
}

static void scan_penetration(libpool_engine *e) {
	int count = 0;
	const pool_event *events = pool_sim_events(e->sim, &count);
	const double diameter = 2.0 * e->scenario.def.params.ball_radius;
	for (; e->scanned < count; ++e->scanned) {
		const pool_event *ev = &events[e->scanned];
		if (ev->type != POOL_EVENT_BALL_BALL || ev->ball_count < 2)
			continue;
		const pool_ball_state *s = pool_sim_event_states(e->sim, ev);
		const double dx = s[0].pos.x - s[1].pos.x, dy = s[0].pos.y - s[1].pos.y, dz = s[0].pos.z - s[1].pos.z;
		const double overlap = diameter - sqrt(dx * dx + dy * dy + dz * dz);
		if (overlap > e->max_penetration)
			e->max_penetration = overlap;
	}
}

static void destroy(void *engine) {
	libpool_engine *e = engine;
	if (!e)
		return;
	pool_sim_destroy(e->sim);
	pool_scenario_free(&e->scenario);
	free(e->states);
	free(e);
}

static void *create(const char *json, const pool_engine_config *config, char *err, size_t err_size) {
	(void)config; // event-driven: no time step
	libpool_engine *e = calloc(1, sizeof *e);
	if (!e) {
		snprintf(err, err_size, "libpool: out of memory");
		return NULL;
	}
	if (pool_scenario_parse(json, strlen(json), &e->scenario, err, err_size) != 0) {
		destroy(e);
		return NULL;
	}
	pool_error perr = {{0}};
	pool_result r = pool_scenario_setup(&e->scenario, &e->sim, &perr);
	if (r != POOL_OK) {
		snprintf(err, err_size, "libpool: %s", perr.message[0] ? perr.message : pool_result_str(r));
		destroy(e);
		return NULL;
	}
	e->states = calloc((size_t)(e->scenario.ball_count > 0 ? e->scenario.ball_count : 1), sizeof *e->states);
	if (!e->states) {
		snprintf(err, err_size, "libpool: out of memory");
		destroy(e);
		return NULL;
	}
	return e;
}

static int advance(void *engine, double t) {
	libpool_engine *e = engine;
	if (t < e->now) {
		snprintf(e->error, sizeof e->error, "libpool: cannot go back from %g s to %g s", e->now, t);
		return -1;
	}
	pool_result r = run_timed(e, t);
	if (r != POOL_OK)
		return fail(e, r);
	// Past the scenario's max_time the shot is frozen where libpool stopped it.
	e->now = t < e->scenario.def.max_time ? t : e->scenario.def.max_time;
	scan_penetration(e);
	return 0;
}

static int run_to_rest(void *engine, double max_time) {
	libpool_engine *e = engine;
	pool_result r = run_timed(e, max_time);
	if (r != POOL_OK)
		return fail(e, r);
	scan_penetration(e);
	if (pool_sim_stop_reason(e->sim) == POOL_STOP_REST) {
		const double rest = pool_sim_time(e->sim);
		e->now = rest > e->now ? rest : e->now;
	} else {
		const double end = max_time < e->scenario.def.max_time ? max_time : e->scenario.def.max_time;
		e->now = end > e->now ? end : e->now;
	}
	return 0;
}

static int balls(void *engine, pool_engine_ball *out, int capacity) {
	libpool_engine *e = engine;
	const int n = pool_sim_ball_count(e->sim);
	if (pool_sim_state_at(e->sim, e->now, e->states) != POOL_OK)
		return 0;
	for (int i = 0; i < n && i < capacity; ++i) {
		const pool_ball_state *s = &e->states[i];
		out[i].id = s->id;
		out[i].state = (int32_t)s->motion;
		out[i].pos[0] = s->pos.x, out[i].pos[1] = s->pos.y, out[i].pos[2] = s->pos.z;
		out[i].vel[0] = s->vel.x, out[i].vel[1] = s->vel.y, out[i].vel[2] = s->vel.z;
		out[i].omega[0] = s->omega.x, out[i].omega[1] = s->omega.y, out[i].omega[2] = s->omega.z;
	}
	return n;
}

static int events(void *engine, pool_engine_event *out, int capacity) {
	libpool_engine *e = engine;
	int count = 0, n = 0;
	const pool_event *list = pool_sim_events(e->sim, &count);
	for (int i = 0; i < count; ++i) {
		int type;
		switch (list[i].type) {
		case POOL_EVENT_SLIDE_ROLL: type = POOL_ENGINE_EVENT_SLIDE_ROLL; break;
		case POOL_EVENT_ROLL_STOP: type = POOL_ENGINE_EVENT_ROLL_STOP; break;
		case POOL_EVENT_BALL_BALL: type = POOL_ENGINE_EVENT_BALL_BALL; break;
		case POOL_EVENT_BALL_CUSHION: type = POOL_ENGINE_EVENT_BALL_CUSHION; break;
		case POOL_EVENT_POCKET: type = POOL_ENGINE_EVENT_POCKET; break;
		case POOL_EVENT_BALL_TABLE: type = POOL_ENGINE_EVENT_BALL_TABLE; break;
		default: continue; // strike, spin_stop, off_table and LINK events have no counterpart
		}
		if (list[i].time > e->now)
			break;
		if (n < capacity && out) {
			const pool_ball_state *s = pool_sim_event_states(e->sim, &list[i]);
			out[n].t = list[i].time;
			out[n].type = type;
			out[n].ball_a = list[i].ball_count > 0 ? s[0].id : -1;
			out[n].ball_b = type == POOL_ENGINE_EVENT_BALL_BALL && list[i].ball_count > 1 ? s[1].id
			                : type == POOL_ENGINE_EVENT_BALL_CUSHION && list[i].rail != POOL_RAIL_NONE
			                    ? POOL_ENGINE_CUSHION(list[i].rail)
			                    : -1;
		}
		++n;
	}
	return n;
}

static void stats(void *engine, pool_engine_stats *out) {
	libpool_engine *e = engine;
	int count = 0;
	pool_sim_events(e->sim, &count);
	out->steps = count;
	out->max_penetration = e->max_penetration > 0.0 ? e->max_penetration : 0.0;
	out->sim_time = e->now;
}

static const char *last_error(void *engine) {
	return engine ? ((libpool_engine *)engine)->error : "";
}

static const pool_engine_api api = {
	.abi_version = POOL_ENGINE_ABI_VERSION,
	.name = "libpool",
	.description = "libpool event-driven, exact closed-form motion between events (docs/physics.md); "
	               "rigid cushions, point contacts, no air drag or swerve (squirt with models.squirt "
	               "endmass); simultaneous contacts "
	               "are resolved one after the other (pairwise, in a fixed order: one admissible outcome)",
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

#ifdef LIBPOOL_PLUGIN_HAS_LINK
// The LINK steps' share of the run (POOL_ENGINE_LINK_ENTRY): the plugin's timing of each step,
// the library's own counts.
__attribute__((visibility("default"))) int pool_engine_link_stats(void *engine, pool_engine_link_info *out) {
	libpool_engine *e = engine;
	if (!e || !out)
		return -1;
	pool_link_stats link;
	if (pool_sim_link_stats(e->sim, &link) != POOL_OK)
		return -1;
	int count = 0;
	const pool_event *list = pool_sim_events(e->sim, &count);
	int64_t events = 0;
	for (int i = 0; i < count; ++i)
		events += is_link_event(list[i].type);
	out->step_seconds = e->step_seconds;
	out->link_seconds = e->link_seconds;
	out->link_steps = link.steps;
	out->link_events = events;
	out->clusters = link.clusters;
	return 0;
}
#endif

// Every optional model is libpool's own: the scenario's "models" reach the simulation through
// the shared parser (pool_scenario_setup), so none is missing.
__attribute__((visibility("default"))) int pool_engine_unsupported_models(const char *scenario_json,
                                                                          char *out, size_t out_size) {
	(void)scenario_json;
	if (out && out_size > 0)
		out[0] = '\0';
	return 0;
}
