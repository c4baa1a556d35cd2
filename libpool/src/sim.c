// The event-driven simulation: balls, event queue, event processing and shot history.
//
// Scheme. Every ball owns one slot of an indexed min-heap holding its next predicted event:
// the earliest of its own events (state change, cushion, pocket), computed once when its motion
// segment starts, and its earliest contact with another ball. After an event only the balls it
// involved and the balls whose pending event involved them are re-predicted (PHYSICS.md).
// A ball-ball prediction is only searched up to the earlier of the two balls' own next events,
// since either ball changes trajectory there and is re-predicted then.
//
// Simultaneous and touching contacts. Events at the same instant are processed one at a time in
// the heap's total order (time, kind, ball ids, slot). A touching pair (gap <= POOL_TOUCH_TOLERANCE)
// collides "now" only while its normal relative velocity approaches faster than
// POOL_APPROACH_EPS; the impulse reverses that velocity (times e), so the pair is then separating
// and is not found again at this instant, while its neighbours, now pushed, are. A frozen rack is
// thus resolved by sequential pairwise impulses. Termination: every such same-instant collision
// removes a positive share (1 - e^2 and friction) of the pair's approach energy and needs an
// approach speed above POOL_APPROACH_EPS, so the chain is finite for e < 1; for e = 1 and every
// other pathological input, max_events ends the shot (POOL_STOP_MAX_EVENTS). Finite is not
// small: with low restitution a line of touching balls is the inelastic collapse of granular
// gases (McNamara & Young 1992), and sequential impulses converge only geometrically, slower as
// e falls (a 7-ball line takes 28 collisions at e = 0.5 but 8,905 at e = 0.2, README). LINK will
// solve such a cluster as one LCP; until then max_events bounds the cost.
//
// Persistent (pushing) contact. When cloth friction drives two touching balls (or a ball and a
// cushion) into each other, exact impulses form a Zeno sequence (collisions ever closer in time
// with geometrically shrinking speeds) whose limit is a resting contact that point impulses
// cannot represent; past it the bodies would interpenetrate. Until LINK handles such contacts,
// planar mode gives every contact pushed back together a separation speed of at least
// |a_n| POOL_CONTACT_MIN_INTERVAL / 2 (a_n the relative normal acceleration), so the next contact
// is at least POOL_CONTACT_MIN_INTERVAL later. This only affects contacts slower than a few mm/s
// and can add at most (m/4) (mu_slide g POOL_CONTACT_MIN_INTERVAL)^2 J per event (~1e-7 J);
// such events are flagged (sim_internal.h) so tests can hold every other event to strict energy
// non-increase.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "collision.h"
#include "error.h"
#include "event_queue.h"
#include "motion.h"
#include "pool/sim.h"
#include "predict.h"
#include "sim_internal.h"
#include "vec3.h"

typedef struct ball_rt {
	double t0;                // s, start of the current motion segment
	int hist;                 // index of the segment's start state in the history
	int active;               // still on the table
	double own_time;          // s, next own event (state change, cushion, pocket); absolute
	pool_event_type own_kind; // its kind
	pool_rail own_rail;       // for a cushion or pocket event
	pool_pocket own_pocket;   // for a pocket event
	int partner;              // other ball of the pending event in the queue slot, or -1
	pool_vec3 acc;            // m/s^2, centre acceleration over the segment (for predictions)
} ball_rt;

struct pool_sim {
	pool_sim_def def;
	pool_allocator alloc;
	double dc; // m, horizontal centre distance from a nose line at contact

	int n, cap_balls;
	pool_ball_state *cur; // segment start states (pool_sim_balls)
	ball_rt *rt;
	pool_event_key *keys;
	int *heap, *hpos, *work;
	pool_event_queue queue;

	pool_event *events;
	unsigned char *event_flags; // POOL_EVENT_FLAG_*
	int n_events, cap_events;
	pool_ball_state *states; // history: initial states, then every event's after-states
	double *state_time;
	int *state_prev; // previous history entry of the same ball, or -1
	int n_states, cap_states;

	double time;      // s, last processed event
	double processed; // s, events up to here are processed (INFINITY at rest)
	pool_stop_reason stop;
	int predicted; // the queue holds predictions for every ball
	int started;   // an event was recorded: balls can no longer be added
};

static void *default_alloc(size_t size, void *context) {
	(void)context;
	return malloc(size);
}
static void default_free(void *memory, void *context) {
	(void)context;
	free(memory);
}

static void *mem_alloc(const pool_allocator *a, size_t size) { return a->alloc(size ? size : 1, a->context); }
static void mem_free(const pool_allocator *a, void *p) {
	if (p)
		a->free(p, a->context);
}

pool_sim_def pool_default_sim_def(void) {
	pool_sim_def def;
	memset(&def, 0, sizeof def);
	def.table = pool_default_table_def();
	def.params = pool_default_params();
	def.airborne = false;
	def.max_time = 120.0;
	def.max_events = 100000;
	return def;
}

static pool_result validate_def(const pool_sim_def *def, pool_error *error) {
	pool_result r;
	if (!def)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "def: missing");
	if ((r = pool_table_def_validate(&def->table, error)) || (r = pool_params_validate(&def->params, error)))
		return r;
	const double R = def->params.ball_radius;
	if (!(def->table.cushion_height < 2.0 * R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "table.cushion_height: must be < 2 params.ball_radius (%g m)", 2.0 * R);
	if (!(def->table.length > 2.0 * R && def->table.width > 2.0 * R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "table.width: must be > 2 params.ball_radius");
	if (def->airborne)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "options.airborne: airborne motion not implemented yet");
	if (isnan(def->max_time) || !(def->max_time > 0.0))
		return pool_error_set(error, isnan(def->max_time) ? POOL_ERR_NON_FINITE : POOL_ERR_INVALID_ARGUMENT,
		                      "options.max_time: must be > 0");
	if (def->max_events <= 0)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "options.max_events: must be > 0");
	if ((def->allocator.alloc == NULL) != (def->allocator.free == NULL))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "allocator: alloc and free must both be set");
	return pool_error_ok(error);
}

static void clear(pool_sim *sim) {
	sim->n = 0;
	sim->n_events = 0;
	sim->n_states = 0;
	sim->time = 0.0;
	sim->processed = 0.0;
	sim->stop = POOL_STOP_NONE;
	sim->predicted = 0;
	sim->started = 0;
}

static void set_def(pool_sim *sim, const pool_sim_def *def) {
	pool_allocator keep = sim->alloc;
	sim->def = *def;
	sim->def.allocator = keep; // buffers stay with the allocator that made them
	sim->dc = pool_cushion_contact_distance(def->params.ball_radius, def->table.cushion_height);
}

pool_result pool_sim_create(const pool_sim_def *def, pool_sim **out, pool_error *error) {
	if (!out)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "sim: missing output pointer");
	*out = NULL;
	pool_result r = validate_def(def, error);
	if (r)
		return r;
	pool_allocator a = def->allocator;
	if (!a.alloc) {
		a.alloc = default_alloc;
		a.free = default_free;
		a.context = NULL;
	}
	pool_sim *sim = mem_alloc(&a, sizeof *sim);
	if (!sim)
		return pool_error_set(error, POOL_ERR_OUT_OF_MEMORY, "sim: out of memory");
	memset(sim, 0, sizeof *sim);
	sim->alloc = a;
	set_def(sim, def);
	clear(sim);
	*out = sim;
	return pool_error_ok(error);
}

void pool_sim_destroy(pool_sim *sim) {
	if (!sim)
		return;
	const pool_allocator a = sim->alloc;
	void *arrays[] = {sim->cur, sim->rt, sim->keys, sim->heap, sim->hpos, sim->work,
	                  sim->events, sim->event_flags, sim->states, sim->state_time, sim->state_prev};
	for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
		mem_free(&a, arrays[i]);
	mem_free(&a, sim);
}

pool_result pool_sim_reset(pool_sim *sim, const pool_sim_def *def, pool_error *error) {
	if (!sim)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "sim: missing");
	if (def) {
		pool_result r = validate_def(def, error);
		if (r)
			return r;
		set_def(sim, def);
	}
	clear(sim);
	return pool_error_ok(error);
}

// Replaces *arrays[i] (each elems[i] bytes per element, `used` of them live) by arrays of
// new_cap elements; all or nothing, so a failed allocation leaves the simulation intact.
static pool_result grow_arrays(pool_sim *sim, void **arrays[], const size_t elems[], int count, int used, int new_cap) {
	void *fresh[12];
	for (int i = 0; i < count; ++i) {
		fresh[i] = mem_alloc(&sim->alloc, elems[i] * (size_t)new_cap);
		if (!fresh[i]) {
			for (int j = 0; j < i; ++j)
				mem_free(&sim->alloc, fresh[j]);
			return POOL_ERR_OUT_OF_MEMORY;
		}
	}
	for (int i = 0; i < count; ++i) {
		if (*arrays[i] && used > 0)
			memcpy(fresh[i], *arrays[i], elems[i] * (size_t)used);
		mem_free(&sim->alloc, *arrays[i]);
		*arrays[i] = fresh[i];
	}
	return POOL_OK;
}

static int next_cap(int cap, int need) {
	int c = cap > 0 ? cap : 16;
	while (c < need)
		c *= 2;
	return c;
}

static pool_result reserve_balls(pool_sim *sim, int need) {
	if (need <= sim->cap_balls)
		return POOL_OK;
	int cap = next_cap(sim->cap_balls, need);
	void **arrays[] = {(void **)&sim->cur, (void **)&sim->rt, (void **)&sim->keys,
	                   (void **)&sim->heap, (void **)&sim->hpos, (void **)&sim->work};
	const size_t elems[] = {sizeof(pool_ball_state), sizeof(ball_rt), sizeof(pool_event_key),
	                        sizeof(int), sizeof(int), sizeof(int)};
	pool_result r = grow_arrays(sim, arrays, elems, 6, sim->n, cap);
	if (r == POOL_OK)
		sim->cap_balls = cap;
	return r;
}

static pool_result reserve_history(pool_sim *sim, int events, int states) {
	if (sim->n_events + events > sim->cap_events) {
		int cap = next_cap(sim->cap_events, sim->n_events + events);
		void **arrays[] = {(void **)&sim->events, (void **)&sim->event_flags};
		const size_t elems[] = {sizeof(pool_event), 1};
		if (grow_arrays(sim, arrays, elems, 2, sim->n_events, cap))
			return POOL_ERR_OUT_OF_MEMORY;
		sim->cap_events = cap;
	}
	if (sim->n_states + states > sim->cap_states) {
		int cap = next_cap(sim->cap_states, sim->n_states + states);
		void **arrays[] = {(void **)&sim->states, (void **)&sim->state_time, (void **)&sim->state_prev};
		const size_t elems[] = {sizeof(pool_ball_state), sizeof(double), sizeof(int)};
		if (grow_arrays(sim, arrays, elems, 3, sim->n_states, cap))
			return POOL_ERR_OUT_OF_MEMORY;
		sim->cap_states = cap;
	}
	return POOL_OK;
}

static int on_cloth(pool_motion m) { return m <= POOL_MOTION_ROLLING; }
static int translating(pool_motion m) { return m == POOL_MOTION_SLIDING || m == POOL_MOTION_ROLLING; }

// Starts ball i's new motion segment at time t with state s: computes its own next event.
static void start_segment(pool_sim *sim, int i, const pool_ball_state *s, double t) {
	const pool_params *p = &sim->def.params;
	ball_rt *b = &sim->rt[i];
	sim->cur[i] = *s;
	b->t0 = t;
	b->acc = pool_motion_accel(p, s);
	b->own_time = INFINITY;
	b->own_kind = POOL_EVENT_SPIN_STOP;
	b->own_rail = POOL_RAIL_NONE;
	b->own_pocket = POOL_POCKET_NONE;
	if (!b->active || !on_cloth(s->motion))
		return;
	pool_event_type kind;
	double dt = pool_motion_next_change(p, s, &kind);
	if (translating(s->motion)) {
		pool_rail rail;
		pool_pocket pocket;
		double tc = pool_predict_cushion(&sim->def.table, p->ball_radius, s, pool_motion_accel(p, s), dt, &rail, &pocket);
		// A state change at the same instant goes first (its kind orders first).
		if (tc < dt) {
			dt = tc;
			kind = pocket != POOL_POCKET_NONE ? POOL_EVENT_POCKET : POOL_EVENT_BALL_CUSHION;
			b->own_rail = rail;
			b->own_pocket = pocket;
		}
	}
	b->own_time = t + dt;
	b->own_kind = kind;
}

static void record_state(pool_sim *sim, int i, double t) {
	int k = sim->n_states++;
	sim->states[k] = sim->cur[i];
	sim->state_time[k] = t;
	sim->state_prev[k] = sim->rt[i].hist;
	sim->rt[i].hist = k;
}

// Ball i's state at time t (within its current segment), in closed form from the segment start.
static void state_now(const pool_sim *sim, int i, double t, pool_ball_state *out) {
	pool_motion_evolve(&sim->def.params, &sim->cur[i], t - sim->rt[i].t0, out);
}

// Ball i's centre position and velocity at time t (within its segment), from its polynomial.
static void path_now(const pool_sim *sim, int i, double t, pool_vec3 *pos, pool_vec3 *vel) {
	const pool_ball_state *s = &sim->cur[i];
	const ball_rt *b = &sim->rt[i];
	const double dt = t - b->t0;
	if (dt == 0.0 || !translating(s->motion)) {
		*pos = s->pos;
		*vel = s->vel;
		return;
	}
	*pos = pool_v3_madd(pool_v3_madd(s->pos, dt, s->vel), 0.5 * dt * dt, b->acc);
	*vel = pool_v3_madd(s->vel, dt, b->acc);
}

// Recomputes ball i's queue slot at time `now`: its own event or its earliest ball contact.
static void repredict(pool_sim *sim, int i, double now) {
	const pool_params *p = &sim->def.params;
	ball_rt *bi = &sim->rt[i];
	pool_event_key best = {INFINITY, POOL_EVENT_SPIN_STOP, sim->cur[i].id, sim->cur[i].id, i};
	bi->partner = -1;
	if (bi->active) {
		best.time = bi->own_time;
		best.kind = (int)bi->own_kind;
		// Centre paths as polynomials in (t - now); within both segments no clamping applies.
		pool_vec3 pi, vi;
		path_now(sim, i, now, &pi, &vi);
		const pool_vec3 ai = bi->acc;
		const int mi = translating(sim->cur[i].motion);
		const double horizon_i = fmin(bi->own_time, sim->def.max_time);
		for (int j = 0; j < sim->n; ++j) {
			const ball_rt *bj = &sim->rt[j];
			if (j == i || !bj->active || (!mi && !translating(sim->cur[j].motion)))
				continue;
			// A contact after the best event so far cannot be the earliest: shrink the window.
			double T = fmin(fmin(horizon_i, bj->own_time), best.time) - now;
			if (!(T >= 0.0))
				continue;
			pool_vec3 pj, vj;
			path_now(sim, j, now, &pj, &vj);
			// Same operand order whichever ball predicts, so both get the same time.
			pool_vec3 dp = pool_v3_sub(pi, pj), dv = pool_v3_sub(vi, vj), da = pool_v3_scale(pool_v3_sub(ai, bj->acc), 0.5);
			if (j < i) {
				dp = pool_v3_scale(dp, -1.0);
				dv = pool_v3_scale(dv, -1.0);
				da = pool_v3_scale(da, -1.0);
			}
			double tau = pool_predict_ball_ball(dp, dv, da, p->ball_radius, T);
			if (!(tau <= T))
				continue;
			int32_t a = sim->cur[i].id, b = sim->cur[j].id;
			pool_event_key k = {now + tau, POOL_EVENT_BALL_BALL, a < b ? a : b, a < b ? b : a, i};
			if (pool_event_key_cmp(&k, &best) < 0) {
				best = k;
				bi->partner = j;
			}
		}
	}
	pool_event_queue_update(&sim->queue, i, &best);
}

static void predict_all(pool_sim *sim) {
	sim->queue.keys = sim->keys;
	sim->queue.heap = sim->heap;
	sim->queue.pos = sim->hpos;
	for (int i = 0; i < sim->n; ++i) {
		sim->keys[i] = (pool_event_key){INFINITY, 0, sim->cur[i].id, sim->cur[i].id, i};
		sim->rt[i].partner = -1;
	}
	pool_event_queue_build(&sim->queue, sim->n);
	double now = sim->time;
	for (int i = 0; i < sim->n; ++i)
		repredict(sim, i, now);
	sim->predicted = 1;
}

// After an event involving balls inv[0..m): re-predict them and every ball whose pending
// event involved one of them.
static void after_event(pool_sim *sim, const int *inv, int m, double now) {
	int count = 0;
	for (int x = 0; x < sim->n; ++x) {
		int hit = 0;
		for (int k = 0; k < m; ++k)
			hit |= x == inv[k] || sim->rt[x].partner == inv[k];
		if (hit)
			sim->work[count++] = x;
	}
	for (int k = 0; k < count; ++k)
		repredict(sim, sim->work[k], now);
}

static int find_ball(const pool_sim *sim, int32_t id) {
	for (int i = 0; i < sim->n; ++i)
		if (sim->cur[i].id == id)
			return i;
	return -1;
}

pool_result pool_sim_add_ball(pool_sim *sim, const pool_ball_state *ball, pool_error *error) {
	if (!sim || !ball)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "balls: missing argument");
	const int idx = sim->n;
	if (sim->started)
		return pool_error_set(error, POOL_ERR_STATE, "balls[%d]: balls can only be added before the shot starts", idx);
	if (!pool_v3_finite(ball->pos))
		return pool_error_set(error, POOL_ERR_NON_FINITE, "balls[%d].pos: must be finite", idx);
	if (!pool_v3_finite(ball->vel))
		return pool_error_set(error, POOL_ERR_NON_FINITE, "balls[%d].vel: must be finite", idx);
	if (!pool_v3_finite(ball->omega))
		return pool_error_set(error, POOL_ERR_NON_FINITE, "balls[%d].omega: must be finite", idx);
	const double R = sim->def.params.ball_radius;
	if (pool_v3_len(ball->vel) > POOL_MAX_SPEED)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "balls[%d].vel: speed above the %g m/s limit (POOL_MAX_SPEED)",
		                      idx, POOL_MAX_SPEED);
	if (pool_v3_len(ball->omega) * R > POOL_MAX_SPEED)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "balls[%d].omega: spin surface speed |omega| R above the %g m/s limit (POOL_MAX_SPEED)", idx,
		                      POOL_MAX_SPEED);
	int dup = find_ball(sim, ball->id);
	if (dup >= 0)
		return pool_error_set(error, POOL_ERR_DUPLICATE_ID, "balls[%d].id: duplicate id %d", idx, (int)ball->id);
	const double L = sim->def.table.length, W = sim->def.table.width;
	const double tol = POOL_TOUCH_TOLERANCE;
	if (fabs(ball->pos.z - R) > tol)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "balls[%d].pos: z must be the ball radius (%g m): airborne motion not implemented yet", idx, R);
	// Dropping a vertical velocity silently would simulate another shot than the caller asked for.
	if (fabs(ball->vel.z) > POOL_APPROACH_EPS)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "balls[%d].vel: vertical velocity %g m/s needs airborne motion, not implemented yet",
		                      idx, ball->vel.z);
	const double x = ball->pos.x, y = ball->pos.y;
	if (x < sim->dc - tol || x > L - sim->dc + tol || y < sim->dc - tol || y > W - sim->dc + tol)
		return pool_error_set(error, POOL_ERR_OFF_TABLE, "balls[%d].pos: off the table", idx);
	for (int j = 0; j < sim->n; ++j) {
		double d = pool_v3_len(pool_v3_sub(ball->pos, sim->cur[j].pos));
		if (d < 2.0 * R - tol)
			return pool_error_set(error, POOL_ERR_OVERLAP, "balls[%d].pos: overlaps ball %d by %.3g m", idx,
			                      (int)sim->cur[j].id, 2.0 * R - d);
	}
	if (reserve_balls(sim, idx + 1) || reserve_history(sim, 0, 1))
		return pool_error_set(error, POOL_ERR_OUT_OF_MEMORY, "balls[%d]: out of memory", idx);
	pool_ball_state s = *ball;
	s.pos.z = R;
	s.vel.z = 0.0; // planar mode: no vertical velocity (at most POOL_APPROACH_EPS was given)
	s.motion = POOL_MOTION_STATIONARY;
	pool_motion_derive(&sim->def.params, &s);
	sim->n++;
	ball_rt *b = &sim->rt[idx];
	memset(b, 0, sizeof *b);
	b->active = 1;
	b->hist = -1;
	b->partner = -1;
	start_segment(sim, idx, &s, sim->time);
	record_state(sim, idx, sim->time);
	sim->predicted = 0;
	return pool_error_ok(error);
}

static void push_event(pool_sim *sim, double t, pool_event_type type, pool_rail rail, pool_pocket pocket,
                       const int *inv, int m) {
	sim->event_flags[sim->n_events] = 0;
	pool_event *e = &sim->events[sim->n_events++];
	memset(e, 0, sizeof *e); // padding too: event lists compare bit for bit
	e->time = t;
	e->type = type;
	e->rail = rail;
	e->pocket = pocket;
	e->ball_count = m;
	e->first_state = sim->n_states;
	for (int k = 0; k < m; ++k)
		record_state(sim, inv[k], t);
}

pool_result pool_sim_strike(pool_sim *sim, int32_t ball_id, const pool_strike *strike, pool_error *error) {
	if (!sim || !strike)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "strike: missing argument");
	int i = find_ball(sim, ball_id);
	if (i < 0)
		return pool_error_set(error, POOL_ERR_UNKNOWN_BALL, "strike.ball: no ball has id %d", (int)ball_id);
	pool_vec3 v, w;
	pool_result r = pool_strike_velocities(&sim->def.params, strike, &v, &w, error);
	if (r)
		return r;
	const double now = isfinite(sim->processed) ? fmax(sim->processed, sim->time) : sim->time;
	pool_ball_state s;
	state_now(sim, i, now, &s);
	if (!sim->rt[i].active || (s.motion != POOL_MOTION_STATIONARY && s.motion != POOL_MOTION_SPINNING))
		return pool_error_set(error, POOL_ERR_STATE, "strike.ball: ball %d is not at rest on the cloth", (int)ball_id);
	if (reserve_history(sim, 1, 1))
		return pool_error_set(error, POOL_ERR_OUT_OF_MEMORY, "strike: out of memory");
	s.vel = v;
	s.vel.z = 0.0; // planar mode drops the vertical component
	s.omega = pool_v3_add(s.omega, w);
	pool_motion_derive(&sim->def.params, &s);
	start_segment(sim, i, &s, now);
	push_event(sim, now, POOL_EVENT_STRIKE, POOL_RAIL_NONE, POOL_POCKET_NONE, &i, 1);
	sim->time = now;
	sim->processed = now;
	sim->started = 1;
	sim->stop = POOL_STOP_NONE;
	if (sim->predicted)
		after_event(sim, &i, 1, now);
	return pool_error_ok(error);
}

// Planar stand-in for persistent contact (see the top of this file): if the bodies' cloth
// accelerations push them back together, they leave at least fast enough not to meet again
// within POOL_CONTACT_MIN_INTERVAL. n: horizontal unit normal towards body 1; s2 NULL for a
// cushion. Returns 1 when the floor was applied.
static int separation_floor(const pool_params *p, pool_ball_state *s1, pool_ball_state *s2, pool_vec3 n) {
	pool_vec3 a = pool_motion_accel(p, s1);
	pool_vec3 v = s1->vel;
	if (s2) {
		a = pool_v3_sub(a, pool_motion_accel(p, s2));
		v = pool_v3_sub(v, s2->vel);
	}
	const double an = pool_v3_dot(a, n), vn = pool_v3_dot(v, n);
	if (!(an < 0.0))
		return 0;
	// At least POOL_SEPARATION_MIN, or the next prediction would find the same contact "now"
	// again (contact.h) when the pull is weaker than 2 POOL_SEPARATION_MIN / the interval.
	const double floor = fmax(-an * POOL_CONTACT_MIN_INTERVAL * 0.5, POOL_SEPARATION_MIN);
	if (vn >= floor)
		return 0;
	const double dv = floor - vn;
	if (s2) {
		s1->vel = pool_v3_madd(s1->vel, 0.5 * dv, n);
		s2->vel = pool_v3_madd(s2->vel, -0.5 * dv, n);
		pool_motion_derive(p, s2);
	} else {
		s1->vel = pool_v3_madd(s1->vel, dv, n);
	}
	pool_motion_derive(p, s1);
	return 1;
}

double pool_floor_energy_bound(const pool_params *p) {
	const double an = 2.0 * fmax(p->mu_slide, p->mu_roll) * p->g;
	const double f = fmax(an * POOL_CONTACT_MIN_INTERVAL * 0.5, POOL_SEPARATION_MIN);
	return 0.25 * p->ball_mass * f * f;
}

// Applies the event in slot `slot` (its key is the queue's minimum) at its time.
static void process(pool_sim *sim, int slot) {
	const pool_params *p = &sim->def.params;
	const pool_event_key key = sim->keys[slot];
	const double now = key.time;
	const double R = p->ball_radius, m = p->ball_mass;
	ball_rt *b = &sim->rt[slot];
	pool_event_type type = (pool_event_type)key.kind;
	pool_rail rail = POOL_RAIL_NONE;
	pool_pocket pocket = POOL_POCKET_NONE;
	int inv[2] = {slot, -1}, count = 1, floored = 0;
	pool_ball_state s[2];
	state_now(sim, slot, now, &s[0]);
	switch (type) {
	case POOL_EVENT_SLIDE_ROLL:
	case POOL_EVENT_ROLL_STOP:
	case POOL_EVENT_SPIN_STOP: pool_motion_apply_change(p, &s[0], type); break;
	case POOL_EVENT_BALL_CUSHION: {
		rail = b->own_rail;
		pool_vec3 n = pool_cushion_normal(&sim->def.table, s[0].pos, rail);
		pool_collide(&s[0], R, m, NULL, R, 0.0, n, p->e_cushion, p->mu_cushion);
		s[0].vel.z = 0.0;
		pool_motion_derive(p, &s[0]);
		pool_vec3 nh = pool_v3_xy(n);
		floored = separation_floor(p, &s[0], NULL, pool_v3_scale(nh, 1.0 / pool_v3_len(nh)));
		break;
	}
	case POOL_EVENT_POCKET:
		rail = POOL_RAIL_NONE;
		pocket = b->own_pocket;
		s[0].vel = pool_v3(0.0, 0.0, 0.0);
		s[0].omega = pool_v3(0.0, 0.0, 0.0);
		s[0].motion = POOL_MOTION_POCKETED;
		b->active = 0;
		break;
	case POOL_EVENT_BALL_BALL: {
		int j = b->partner;
		// Body 1 is the ball with the smaller id, so the event reads the same from both slots.
		if (sim->cur[j].id < sim->cur[slot].id) {
			inv[0] = j;
			inv[1] = slot;
		} else {
			inv[1] = j;
		}
		count = 2;
		state_now(sim, inv[0], now, &s[0]);
		state_now(sim, inv[1], now, &s[1]);
		pool_vec3 n = pool_v3_sub(s[0].pos, s[1].pos);
		n = pool_v3_scale(n, 1.0 / pool_v3_len(n));
		pool_collide(&s[0], R, m, &s[1], R, 1.0, n, p->e_ball, p->mu_ball);
		for (int k = 0; k < 2; ++k) {
			s[k].vel.z = 0.0;
			pool_motion_derive(p, &s[k]);
		}
		floored = separation_floor(p, &s[0], &s[1], n);
		break;
	}
	default: break;
	}
	for (int k = 0; k < count; ++k)
		start_segment(sim, inv[k], &s[k], now);
	push_event(sim, now, type, rail, pocket, inv, count);
	if (floored)
		sim->event_flags[sim->n_events - 1] |= POOL_EVENT_FLAG_FLOOR;
	sim->time = now;
	sim->processed = now;
	after_event(sim, inv, count, now);
}

int pool_sim_step(pool_sim *sim) {
	if (!sim)
		return POOL_ERR_INVALID_ARGUMENT;
	if (sim->stop != POOL_STOP_NONE)
		return 0;
	if (!sim->predicted)
		predict_all(sim);
	const pool_event_key *top = sim->n > 0 ? &sim->keys[pool_event_queue_top(&sim->queue)] : NULL;
	if (!top || !isfinite(top->time)) {
		sim->stop = POOL_STOP_REST;
		sim->processed = INFINITY;
		return 0;
	}
	// The time limit first: when the next event lies beyond max_time the event limit cut nothing,
	// and the shot is the one cut at max_time (its states known up to max_time).
	if (top->time > sim->def.max_time) {
		sim->stop = POOL_STOP_MAX_TIME;
		sim->processed = fmax(sim->processed, sim->def.max_time);
		return 0;
	}
	if (sim->n_events >= sim->def.max_events) {
		sim->stop = POOL_STOP_MAX_EVENTS;
		return 0;
	}
	if (reserve_history(sim, 1, 2))
		return POOL_ERR_OUT_OF_MEMORY;
	sim->started = 1;
	process(sim, pool_event_queue_top(&sim->queue));
	return 1;
}

pool_result pool_sim_run(pool_sim *sim) {
	int r;
	while ((r = pool_sim_step(sim)) > 0) {
	}
	return r < 0 ? (pool_result)r : POOL_OK;
}

pool_result pool_sim_run_until(pool_sim *sim, double t) {
	if (!sim || isnan(t))
		return POOL_ERR_INVALID_ARGUMENT;
	for (;;) {
		if (sim->stop != POOL_STOP_NONE)
			return POOL_OK;
		if (!sim->predicted)
			predict_all(sim);
		if (sim->n > 0 && sim->keys[pool_event_queue_top(&sim->queue)].time > t &&
		    isfinite(sim->keys[pool_event_queue_top(&sim->queue)].time) &&
		    sim->keys[pool_event_queue_top(&sim->queue)].time <= sim->def.max_time)
			break;
		int r = pool_sim_step(sim);
		if (r < 0)
			return (pool_result)r;
		if (r == 0)
			return POOL_OK;
	}
	if (t > sim->processed)
		sim->processed = t;
	return POOL_OK;
}

pool_stop_reason pool_sim_stop_reason(const pool_sim *sim) { return sim ? sim->stop : POOL_STOP_NONE; }

double pool_sim_time(const pool_sim *sim) { return sim ? sim->time : 0.0; }

double pool_sim_end_time(const pool_sim *sim) {
	if (!sim)
		return 0.0;
	return sim->stop == POOL_STOP_MAX_TIME ? fmax(sim->time, sim->def.max_time) : sim->time;
}

int pool_sim_ball_count(const pool_sim *sim) { return sim ? sim->n : 0; }

const pool_ball_state *pool_sim_balls(const pool_sim *sim) { return sim ? sim->cur : NULL; }

pool_result pool_sim_state_at(const pool_sim *sim, double t, pool_ball_state *out) {
	if (!sim || !out || isnan(t) || t < 0.0)
		return POOL_ERR_INVALID_ARGUMENT;
	if (t > sim->processed)
		return POOL_ERR_STATE;
	for (int i = 0; i < sim->n; ++i) {
		int k = sim->rt[i].hist;
		while (sim->state_time[k] > t && sim->state_prev[k] >= 0)
			k = sim->state_prev[k];
		pool_motion_evolve(&sim->def.params, &sim->states[k], t - sim->state_time[k], &out[i]);
	}
	return POOL_OK;
}

const pool_event *pool_sim_events(const pool_sim *sim, int *count) {
	if (count)
		*count = sim ? sim->n_events : 0;
	return sim ? sim->events : NULL;
}

const pool_ball_state *pool_sim_event_states(const pool_sim *sim, const pool_event *event) {
	if (!sim || !event || event->first_state < 0 || event->first_state >= sim->n_states)
		return NULL;
	return &sim->states[event->first_state];
}

int pool_sim_event_flags(const pool_sim *sim, int index) {
	return sim && index >= 0 && index < sim->n_events ? sim->event_flags[index] : 0;
}
