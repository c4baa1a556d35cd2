// The world: storage, the shot's history and the public API of pool/sim.h (world.h says how the
// simulation is split). Events are processed in the schedule's order, one at a time; each is
// applied by its kind's handler and the bodies it involved start new segments.
//
// Simultaneous and touching contacts. Events at the same instant are processed one at a time in
// the heap's total order (time, kind, body order ids, slot). Whether touching bodies collide
// "now" is decided by the one rule of contact.h; an impulse reverses the pair's normal velocity
// (times e), so the pair is then separating and is not found again at this instant, while its
// neighbours, now pushed, are. A frozen rack is thus resolved by sequential pairwise impulses.
// Termination: every such same-instant collision removes a positive share (1 - e^2 and friction)
// of the pair's approach energy and needs an approach speed above POOL_APPROACH_EPS, so the chain
// is finite for e < 1; for e = 1 and every other pathological input, max_events ends the shot
// (POOL_STOP_MAX_EVENTS). Finite is not small: with low restitution a line of touching balls is
// the inelastic collapse of granular gases (McNamara & Young 1992), and sequential impulses
// converge only geometrically, slower as e falls (a 7-ball line takes 28 collisions at e = 0.5 but
// 8,905 at e = 0.2 without LINK, docs/measurements.md); the LINK trigger (link.h) turns a pair
// colliding again and again into a cluster solved as one LCP per step, and max_events bounds
// every other case. Persistent (pushing, resting) contact: link.h.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact.h"
#include "error.h"
#include "geometry.h"
#include "handlers.h"
#include "invariants.h"
#include "memory.h"
#include "models.h"
#include "motion.h"
#include "pool/sim.h"
#include "schedule.h"
#include "vec3.h"
#include "world.h"

static void *default_alloc(size_t size, void *context) {
	(void)context;
	return malloc(size);
}
static void default_free(void *memory, void *context) {
	(void)context;
	free(memory);
}

pool_sim_def pool_default_sim_def(void) {
	pool_sim_def def;
	memset(&def, 0, sizeof def);
	def.table = pool_default_table_def();
	def.params = pool_default_params();
	def.airborne = false;
	def.max_time = 120.0;
	def.max_events = 100000;
	def.models = pool_default_models();
	return def;
}

/// The highest nose accepted, in ball radii (validate_def says why).
#define POOL_NOSE_HEIGHT_MAX 1.9

static pool_result validate_def(const pool_sim_def *def, pool_error *error) {
	pool_result r;
	if (!def)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "def: missing");
	if ((r = pool_table_def_validate(&def->table, error)) || (r = pool_params_validate(&def->params, error)))
		return r;
	// The nose must hold a ball back (docs/physics.md "Frame, units, defaults"). At or below
	// the ball's centre it pushes a ball pressed into it upwards, up and over the cushion, whose
	// top libpool does not model; near the ball's top its contact pushes the ball into the cloth
	// far harder than it holds it back (at 1.9 R, 2.3 times: the normal is 64 degrees from the
	// horizontal), and the ball wedges between nose and cloth, which rigid contacts resolve
	// only in the limit (the soak's shots fail from 1.998 R up). Measured tables are 1.2-1.4 R.
	// Such tables are refused rather than simulated wrongly.
	const double R = def->params.ball_radius;
	if (!(def->table.cushion_height > R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "table.cushion_height: must be > params.ball_radius (%g m): a nose at or below the "
		                      "ball's centre pushes the ball up and over the cushion (docs/physics.md)",
		                      R);
	if (!(def->table.cushion_height <= POOL_NOSE_HEIGHT_MAX * R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "table.cushion_height: must be <= %g params.ball_radius (%g m): a nose near the ball's "
		                      "top wedges the ball against the cloth instead of holding it back (docs/physics.md)",
		                      POOL_NOSE_HEIGHT_MAX, POOL_NOSE_HEIGHT_MAX * R);
	if (!(def->table.length > 2.0 * R && def->table.width > 2.0 * R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "table.width: must be > 2 params.ball_radius");
	if (isnan(def->max_time) || !(def->max_time > 0.0))
		return pool_error_set(error, isnan(def->max_time) ? POOL_ERR_NON_FINITE : POOL_ERR_INVALID_ARGUMENT,
		                      "def.max_time: must be > 0");
	if (def->max_events <= 0)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "def.max_events: must be > 0");
	if ((def->allocator.alloc == NULL) != (def->allocator.free == NULL))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "allocator: alloc and free must both be set");
	if ((r = pool_models_validate(&def->models, error)))
		return r;
	// The nose curve can be built for this ball (jaws tangent within their parts, facings that
	// reach the holes, mouths and throats wider than the ball).
	pool_table_shape shape;
	if ((r = pool_table_shape_build(&def->table, R, &shape, error)))
		return r;
	return pool_error_ok(error);
}

// ---- what LINK may ask of the world (link.h)

static void link_state_at(void *ctx, int i, double t, pool_ball_state *out) { pool_world_state_now(ctx, i, t, out); }

static void link_begin_segment(void *ctx, int i, const pool_ball_state *s, double t) {
	pool_schedule_begin_segment(ctx, i, s, t);
}

static void link_refresh(void *ctx, const int *balls, int m, double t) { pool_schedule_refresh(ctx, balls, m, t); }

static void link_changed(void *ctx, const int *balls, int m, double t) { pool_schedule_after_event(ctx, balls, m, t); }

// Records an event of balls[0..m) at t in their segment-start states. The callers reserve the
// room first (pool_sim_step for an event and the LINK events it brings); should that fall short
// and the history not grow, the shot fails rather than write past its arrays.
static pool_result record(pool_sim *sim, double t, pool_event_type type, pool_rail rail, pool_pocket pocket,
                          pool_cushion_part part, const int *balls, int m) {
	const pool_result r =
	    pool_history_record(&sim->history, &sim->alloc, t, type, rail, pocket, part, balls, m, sim->cur);
	if (r)
		sim->failed = r;
	return r;
}

static pool_result link_record(void *ctx, double t, pool_event_type type, pool_pocket pocket, const int *balls, int m) {
	return record(ctx, t, type, POOL_RAIL_NONE, pocket, POOL_PART_NONE, balls, m);
}

static pool_result link_reserve(void *ctx, int events, int states) {
	pool_sim *sim = ctx;
	return pool_history_reserve(&sim->history, &sim->alloc, events, states);
}

static int link_room(void *ctx) {
	const pool_sim *sim = ctx;
	return sim->def.max_events - sim->history.n_events;
}

static void bind_link(pool_sim *sim) {
	const pool_link_world world = {sim,         link_state_at, link_begin_segment, link_refresh,
	                               link_changed, link_record,  link_reserve,       link_room};
	pool_link_init(&sim->link, &sim->def, &sim->shape, sim->dc, &sim->alloc, &world);
}

// ---- lifetime

static void clear(pool_sim *sim) {
	sim->n = 0;
	sim->time = 0.0;
	sim->processed = 0.0;
	sim->stop = POOL_STOP_NONE;
	sim->predicted = 0;
	sim->started = 0;
	sim->noop_streak = 0;
	sim->noop_time = -INFINITY;
	sim->failed = POOL_OK;
	sim->last_error.message[0] = '\0';
	pool_history_clear(&sim->history);
	pool_link_clear(&sim->link);
}

static void set_def(pool_sim *sim, const pool_sim_def *def) {
	pool_allocator keep = sim->alloc;
	sim->def = *def;
	sim->def.allocator = keep; // buffers stay with the allocator that made them
	sim->dc = pool_table_contact_distance(&def->table, def->params.ball_radius);
	(void)pool_table_shape_build(&def->table, def->params.ball_radius, &sim->shape, NULL); // validated
	bind_link(sim);
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
	pool_sim *sim = pool_mem_alloc(&a, sizeof *sim);
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
	void *arrays[] = {sim->cur, sim->body, sim->keys, sim->heap, sim->hpos, sim->work, sim->reach, sim->in_play, sim->moving};
	pool_link_free(&sim->link);
	pool_history_free(&sim->history, &a);
	pool_broadphase_free(&sim->broad, &a);
	for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
		pool_mem_free(&a, arrays[i]);
	pool_mem_free(&a, sim);
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

static pool_result reserve_balls(pool_sim *sim, int need) {
	if (need > sim->cap_balls) {
		const int cap = pool_mem_next_cap(sim->cap_balls, need);
		// The bit sets get a word per ball, more than they need, so that one call grows every array.
		void **arrays[] = {(void **)&sim->cur,  (void **)&sim->body, (void **)&sim->keys,  (void **)&sim->heap,
		                   (void **)&sim->hpos, (void **)&sim->work, (void **)&sim->reach, (void **)&sim->in_play,
		                   (void **)&sim->moving};
		const size_t elems[] = {sizeof(pool_ball_state), sizeof(pool_body), sizeof(pool_event_key), sizeof(int),
		                        sizeof(int),             sizeof(int),       sizeof(pool_reach),     sizeof(uint64_t),
		                        sizeof(uint64_t)};
		if (pool_mem_grow(&sim->alloc, arrays, elems, 9, sim->n, cap))
			return POOL_ERR_OUT_OF_MEMORY;
		sim->cap_balls = cap;
	}
	if (pool_history_reserve_balls(&sim->history, &sim->alloc, need, sim->n) || pool_link_reserve(&sim->link, need))
		return POOL_ERR_OUT_OF_MEMORY;
	return POOL_OK;
}

void pool_world_state_now(const pool_sim *sim, int i, double t, pool_ball_state *out) {
	const pool_segment *seg = &sim->body[i].seg;
	pool_segment_state(seg, &sim->def.params, t - seg->t0, out);
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
	// One pass over the balls placed: a duplicate id, reported now, and the first ball this one
	// overlaps, reported after the table's checks. Most balls are at least 2R apart, which their
	// squared distance tells without a square root (sqrt is monotone, and 2R is far above
	// 2R - tol): the same answer for every pair.
	const double tol = POOL_TOUCH_TOLERANCE, apart2 = 4.0 * R * R;
	int dup = 0, overlap = -1;
	double overlap_d = 0.0;
	for (int j = 0; j < sim->n; ++j) {
		dup |= sim->cur[j].id == ball->id;
		const pool_vec3 dp = pool_v3_sub(ball->pos, sim->cur[j].pos);
		const double dd = pool_v3_dot(dp, dp);
		if (dd >= apart2 || overlap >= 0)
			continue;
		const double d = sqrt(dd);
		if (d < 2.0 * R - tol) {
			overlap = j;
			overlap_d = d;
		}
	}
	if (dup)
		return pool_error_set(error, POOL_ERR_DUPLICATE_ID, "balls[%d].id: duplicate id %d", idx, (int)ball->id);
	const double L = sim->def.table.length, W = sim->def.table.width;
	if (pool_world_planar(sim)) {
		if (fabs(ball->pos.z - R) > tol)
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
			                      "balls[%d].pos: z must be the ball radius (%g m) in planar mode (def.airborne puts balls off the cloth)", idx, R);
		// Dropping a vertical velocity silently would simulate another shot than the caller asked for.
		if (fabs(ball->vel.z) > POOL_APPROACH_EPS)
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
			                      "balls[%d].vel: vertical velocity %g m/s needs airborne motion (def.airborne)",
			                      idx, ball->vel.z);
	} else if (!(ball->pos.z >= R - tol)) {
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "balls[%d].pos: z below the ball radius (%g m): under the cloth",
		                      idx, R);
	}
	const double x = ball->pos.x, y = ball->pos.y;
	// On the cloth inside the contact lines; with pockets "jaws" also in a mouth or on a shelf,
	// clear of the facings and jaws and not over a hole (where a ball can come to rest).
	if ((x < sim->dc - tol || x > L - sim->dc + tol || y < sim->dc - tol || y > W - sim->dc + tol) &&
	    !(sim->def.table.pockets == POOL_POCKETS_JAWS && pool_shape_on_cloth(&sim->shape, x, y, tol)))
		return pool_error_set(error, POOL_ERR_OFF_TABLE, "balls[%d].pos: off the table", idx);
	// Above the cloth a ball inside its contact lines can still be inside a cushion's nose (on the
	// cloth the lines are exactly where it touches one).
	if (ball->pos.z > R + tol) {
		pool_rail nose_rail;
		const double nose_gap = pool_table_nose_gap(&sim->def.table, ball->pos, R, &nose_rail);
		if (!(nose_gap >= -tol))
			return pool_error_set(error, POOL_ERR_OVERLAP, "balls[%d].pos: inside the %s cushion's nose by %.3g m", idx,
			                      pool_rail_name(nose_rail), -nose_gap);
	}
	if (overlap >= 0)
		return pool_error_set(error, POOL_ERR_OVERLAP, "balls[%d].pos: overlaps ball %d by %.3g m", idx,
		                      (int)sim->cur[overlap].id, 2.0 * R - overlap_d);
	if (reserve_balls(sim, idx + 1) || pool_history_reserve(&sim->history, &sim->alloc, 0, 1))
		return pool_error_set(error, POOL_ERR_OUT_OF_MEMORY, "balls[%d]: out of memory", idx);
	pool_ball_state s = *ball;
	if (pool_world_planar(sim))
		s.pos.z = R; // and v_z (at most POOL_APPROACH_EPS was given) is dropped below
	s.motion = POOL_MOTION_STATIONARY;
	pool_motion_after_impulse(&sim->def, &s);
	sim->n++;
	// The segment and its own event are begin_own's (pool_schedule_begin_segment), whole.
	pool_body *b = &sim->body[idx];
	b->partner = -1;
	b->changed = 0;
	pool_link_add_ball(&sim->link, idx);
	pool_schedule_begin_segment(sim, idx, &s, sim->time);
	pool_history_place(&sim->history, idx, &s, sim->time);
	sim->predicted = 0;
	return pool_error_ok(error);
}

pool_result pool_sim_strike(pool_sim *sim, int32_t ball_id, const pool_strike *strike, pool_error *error) {
	if (!sim || !strike)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "strike: missing argument");
	int i = find_ball(sim, ball_id);
	if (i < 0)
		return pool_error_set(error, POOL_ERR_UNKNOWN_BALL, "strike.ball: no ball has id %d", (int)ball_id);
	pool_vec3 v, w;
	pool_result r = pool_strike_velocities_modelled(&sim->def.params, sim->def.models.squirt, strike, &v, &w, error);
	if (r)
		return r;
	const double now = isfinite(sim->processed) ? fmax(sim->processed, sim->time) : sim->time;
	pool_ball_state s;
	pool_world_state_now(sim, i, now, &s);
	if (!sim->body[i].active || (s.motion != POOL_MOTION_STATIONARY && s.motion != POOL_MOTION_SPINNING))
		return pool_error_set(error, POOL_ERR_STATE, "strike.ball: ball %d is not at rest on the cloth", (int)ball_id);
	if (pool_history_reserve(&sim->history, &sim->alloc, 1, 1))
		return pool_error_set(error, POOL_ERR_OUT_OF_MEMORY, "strike: out of memory");
	s.vel = v;
	s.omega = pool_v3_add(s.omega, w);
	// Planar mode drops the vertical component; with airborne motion an elevated cue drives the
	// ball into the cloth (v_z < 0): a ball_table impact at this very instant (jump and massé).
	pool_motion_after_impulse(&sim->def, &s);
	pool_schedule_begin_segment(sim, i, &s, now);
	record(sim, now, POOL_EVENT_STRIKE, POOL_RAIL_NONE, POOL_POCKET_NONE, POOL_PART_NONE, &i, 1);
	sim->time = now;
	sim->processed = now;
	sim->started = 1;
	sim->stop = POOL_STOP_NONE;
	if (sim->predicted)
		pool_schedule_after_event(sim, &i, 1, now);
	return pool_error_ok(error);
}

/// Consecutive no-op contacts (grazes) skipped before one is recorded anyway.
#define NOOP_LIMIT 8

// 1 when the handler changed nothing of the states before[0..count) of the balls inv[0..count)
// (its results s) but what deriving a state from the same velocities changes (a vertical speed
// below POOL_APPROACH_EPS dropped on the cloth): no impulse acted.
static int no_impulse(const pool_sim *sim, const int *inv, const pool_ball_state *s, const pool_ball_state *before,
                      int count) {
	// (The common case, an impulse, changes a velocity by more than the clean-up of deriving a
	// state does: vertical speeds below POOL_APPROACH_EPS, components below POOL_REST_EPS. It is
	// told first, before comparing the states whole.)
	const double R = sim->def.params.ball_radius;
	for (int k = 0; k < count; ++k)
		if (fabs(s[k].vel.x - before[k].vel.x) > POOL_APPROACH_EPS || fabs(s[k].vel.y - before[k].vel.y) > POOL_APPROACH_EPS ||
		    R * pool_v3_len(pool_v3_sub(s[k].omega, before[k].omega)) > POOL_APPROACH_EPS)
			return 0;
	if (memcmp(s, before, sizeof s[0] * (size_t)count) == 0)
		return 1;
	pool_ball_state tidy[2];
	for (int k = 0; k < count; ++k) {
		tidy[k] = before[k];
		pool_motion_after_impulse(&sim->def, &tidy[k]);
	}
	pool_link_keep_linked(&sim->link, inv, tidy, count);
	return memcmp(s, tidy, sizeof s[0] * (size_t)count) == 0;
}

// Applies the event in slot `slot` (its key is the queue's minimum) at its time.
static pool_result process(pool_sim *sim, int slot) {
	const pool_event_key key = sim->keys[slot];
	const double now = key.time;
	pool_body *b = &sim->body[slot];
	const pool_event_type type = (pool_event_type)key.kind;
	if (type == POOL_EVENT_LINK_STEP) {
		const pool_result r = pool_link_step_event(&sim->link, slot, now);
		sim->time = now;
		sim->processed = now;
		return r;
	}
	pool_event_context ctx = {&sim->def, POOL_RAIL_NONE, POOL_POCKET_NONE, &sim->shape, -1};
	if (type == POOL_EVENT_BALL_CUSHION || type == POOL_EVENT_POCKET)
		ctx.rail = b->own_rail;
	if (type == POOL_EVENT_POCKET)
		ctx.pocket = b->own_pocket;
	if (type == POOL_EVENT_BALL_CUSHION && b->own_part >= 0) {
		ctx.part = b->own_part;
		ctx.pocket = b->own_pocket; // the pocket of a facing or jaw
	}
	int inv[2] = {slot, -1}, count = 1;
	if (type == POOL_EVENT_BALL_BALL) {
		// Body 1 is the ball with the smaller id, so the event reads the same from both slots.
		const int j = b->partner;
		if (sim->cur[j].id < sim->cur[slot].id) {
			inv[0] = j;
			inv[1] = slot;
		} else {
			inv[1] = j;
		}
		count = 2;
	}
	// A ball LINK holds: its cluster's step ends here, at the length it lasted, and the event
	// acts on the states the step left (a cluster's balls are the solver's, not the world's).
	int held = 0; // one of the balls is LINK's (most events: none)
	for (int k = 0; k < count; ++k)
		held |= pool_link_cluster_of(&sim->link, inv[k]) >= 0;
	const pool_result cut = held ? pool_link_cut(&sim->link, inv, count, now) : POOL_OK;
	if (cut || pool_link_starved(&sim->link))
		return cut;
	// A contact's states before its handler: the no-impulse test reads them (below).
	const int contact = type == POOL_EVENT_BALL_BALL || type == POOL_EVENT_BALL_CUSHION;
	pool_ball_state s[2], before[2];
	for (int k = 0; k < count; ++k) {
		pool_world_state_now(sim, inv[k], now, &s[k]);
		if (contact)
			before[k] = s[k];
	}
	const pool_event_handler handle = pool_event_handler_for(type);
	// Impulses act on touching balls only: a pair whose predicted meeting rounded to an instant
	// at which it is already apart (beyond POOL_TOUCH_TOLERANCE) is a graze, predicted again.
	const int apart = type == POOL_EVENT_BALL_BALL &&
	                  pool_v3_len(pool_v3_sub(s[0].pos, s[1].pos)) - 2.0 * sim->def.params.ball_radius > POOL_TOUCH_TOLERANCE;
	const int flags = handle && !apart ? handle(&ctx, type, s, count) : 0;
	if (held)
		pool_link_keep_linked(&sim->link, inv, s, count); // (a handler derives a motion state from velocities)
	// A graze: the prediction found the pair touching while approaching by a rounding-level
	// speed, and at the event they are already parting, so Petit's law gave no impulse and the
	// states are unchanged. That is no collision: nothing is recorded (a player's "first ball
	// hit" must not be a ball that was never touched) and the pair is predicted again from here,
	// where the contact rule sees it parting. A run of such no-ops at one instant (never seen)
	// would be recorded after NOOP_LIMIT, so the shot still makes progress to max_events.
	// Only a contact's graze or pressed pair reads it (a state change, a pocket, a landing never).
	const int unchanged = contact && flags == 0 && no_impulse(sim, inv, s, before, count);
	// Pressed together, not parting: a resting contact that impulses cannot hold (the cloth
	// drives the pair, or the ball into the rail, and Petit's law has nothing to act on). It is
	// persistent contact by definition: LINK takes it at once (no event of its own is recorded).
	pool_result taken = POOL_OK;
	if (unchanged && pool_link_take_pressed(&sim->link, type, inv, s, count, now, &taken)) {
		sim->noop_streak = 0;
		sim->time = now;
		sim->processed = now;
		return taken;
	}
	if (type == POOL_EVENT_BALL_BALL && unchanged && now > sim->noop_time) {
		sim->noop_streak = 0; // (a run at one instant is what the limit bounds)
		sim->noop_time = now;
	}
	if (type == POOL_EVENT_BALL_BALL && unchanged && sim->noop_streak < NOOP_LIMIT) {
		sim->noop_streak++;
		sim->time = now;
		sim->processed = now;
		pool_schedule_after_event(sim, inv, count, now);
		return POOL_OK;
	}
	sim->noop_streak = 0;
	for (int k = 0; k < count; ++k)
		pool_schedule_begin_segment(sim, inv[k], &s[k], now);
	// A pocket event names its pocket, not the rail whose mouth it was; a cushion event with
	// pockets "jaws" or "none" the kind of the nose curve's part it touched.
	const pool_cushion_part part =
	    type == POOL_EVENT_BALL_CUSHION && ctx.part >= 0 ? sim->shape.parts[ctx.part].part : POOL_PART_NONE;
	record(sim, now, type, type == POOL_EVENT_POCKET ? POOL_RAIL_NONE : ctx.rail, ctx.pocket, part, inv, count);
	sim->time = now;
	sim->processed = now;
	pool_schedule_after_event(sim, inv, count, now);
	// LINK looks at contacts (its trigger, a ball joining a cluster) and at the balls it holds.
	return contact || held ? pool_link_after_event(&sim->link, type, ctx.rail, inv, s, count, now) : POOL_OK;
}

// Says in sim->last_error what made the step at `now` fail with r.
static pool_result step_failed(pool_sim *sim, pool_result r, double now) {
	if (r == POOL_ERR_OUT_OF_MEMORY) {
		pool_error_set(&sim->last_error, r,
		               "t = %.17g s: out of memory; nothing of this step was done, it runs again once memory is back",
		               now);
	} else if (r == POOL_ERR_INTERNAL) {
		double residual = 0.0;
		int balls = 0, contacts = 0;
		pool_link_failure(&sim->link, &residual, &balls, &contacts);
		pool_error_set(&sim->last_error, r,
		               "link step at t = %.17g s: the LCP of a cluster of %d balls (%d contacts) has no solution within "
		               "its residual limit %g (best residual %.3g): the shot cannot go on",
		               now, balls, contacts, POOL_LINK_RESIDUAL_MAX, residual);
	} else {
		pool_error_set(&sim->last_error, r, "event at t = %.17g s: %s", now, pool_result_str(r));
	}
	return r;
}

static int step(pool_sim *sim) {
	if (sim->failed)
		return sim->failed; // (last_error says why, since the step that failed)
	sim->last_error.message[0] = '\0';
	if (sim->stop != POOL_STOP_NONE)
		return 0;
	if (!sim->predicted)
		pool_schedule_predict_all(sim);
	const int slot = sim->n > 0 ? pool_schedule_next(sim) : -1;
	const pool_event_key *top = slot >= 0 ? &sim->keys[slot] : NULL;
	if (!top || !isfinite(top->time)) {
		// Nothing will happen again: no ball in the air, none moving (a flight always ends, and
		// a prediction cut at max_time reports an event beyond it, pool_schedule_beyond).
		for (int i = 0; i < sim->n; ++i)
			POOL_ASSERT_MSG(!sim->body[i].active || (sim->cur[i].motion != POOL_MOTION_AIRBORNE &&
			                                         pool_v3_len(sim->cur[i].vel) == 0.0),
			                "at rest, every ball still");
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
	if (sim->history.n_events >= sim->def.max_events) {
		sim->stop = POOL_STOP_MAX_EVENTS;
		return 0;
	}
	// Room for the event and the LINK events it can bring (each with up to every ball's state):
	// a collision between two clusters' balls cuts both steps (two link_step), dissolves both (two
	// link_end) and may start a cluster (link_begin); a step releases its loose balls (link_end)
	// and records itself. So nothing past this point runs out of memory but a link step's LCP
	// workspace (and the history, should a step's mergers and strays need more: it grows then).
	if (pool_history_reserve(&sim->history, &sim->alloc, 6, 2 + 5 * sim->n))
		return step_failed(sim, POOL_ERR_OUT_OF_MEMORY, top->time);
	sim->started = 1;
	// A failed link step (its LCP unsolved, or out of memory) ends the shot with that error:
	// never silently wrong velocities.
	const int recorded = sim->history.n_events;
	const double now = top->time;
	const pool_result r = process(sim, slot);
	if (pool_link_starved(&sim->link)) {
		// LINK needed an event the limit has no room for and did nothing: the event limit cut
		// the shot here (whatever comes next, even after max_time).
		sim->stop = POOL_STOP_MAX_EVENTS;
		return r ? step_failed(sim, r, now) : sim->history.n_events > recorded;
	}
	if (r) {
		// Out of memory leaves the step undone (it runs again once memory is back); a failed
		// solve is final.
		if (r != POOL_ERR_OUT_OF_MEMORY)
			sim->failed = r;
		return step_failed(sim, r, now);
	}
	return 1;
}

int pool_sim_step(pool_sim *sim) {
	if (!sim)
		return POOL_ERR_INVALID_ARGUMENT;
	const int r = step(sim);
	if (r >= 0)
		pool_world_check(sim); // (the sanitizer build: every invariant after every step)
	return r;
}

pool_result pool_sim_run(pool_sim *sim) {
	int r;
	while ((r = pool_sim_step(sim)) > 0) {
	}
	return r < 0 ? (pool_result)r : POOL_OK;
}

pool_result pool_sim_run_until(pool_sim *sim, double t) {
	if (!sim)
		return POOL_ERR_INVALID_ARGUMENT;
	if (isnan(t))
		return pool_error_set(&sim->last_error, POOL_ERR_INVALID_ARGUMENT, "run_until: t must be a time in s, not NaN");
	sim->last_error.message[0] = '\0';
	for (;;) {
		if (sim->stop != POOL_STOP_NONE)
			return POOL_OK;
		if (!sim->predicted)
			pool_schedule_predict_all(sim);
		// The next event lies after t (and is one the shot will process): the states at t are known.
		const double next = sim->n > 0 ? sim->keys[pool_schedule_next(sim)].time : INFINITY;
		if (next > t && isfinite(next) && next <= sim->def.max_time)
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

// The last_error of a read-only call: what a caller reads after it failed. The simulation is
// not changed otherwise (and, like every call, is not to be shared between threads at once).
static pool_error *read_error(const pool_sim *sim) { return &((pool_sim *)sim)->last_error; }

// Whether states at t can be read: t a time, and processed (last_error otherwise).
static pool_result readable(const pool_sim *sim, const char *what, double t) {
	if (isnan(t) || t < 0.0)
		return pool_error_set(read_error(sim), POOL_ERR_INVALID_ARGUMENT, "%s: t = %g s: must be a time >= 0", what, t);
	if (t > sim->processed)
		return pool_error_set(read_error(sim), POOL_ERR_STATE,
		                      "%s: t = %.17g s is past the time processed, %.17g s: run the shot there first", what, t,
		                      sim->processed);
	return POOL_OK;
}

pool_result pool_sim_state_at(const pool_sim *sim, double t, pool_ball_state *out) {
	if (!sim || !out)
		return POOL_ERR_INVALID_ARGUMENT;
	const pool_result r = readable(sim, "state_at", t);
	if (r)
		return r;
	read_error(sim)->message[0] = '\0';
	pool_history_state_at(&sim->history, &sim->def.params, sim->n, t, out);
	return POOL_OK;
}

pool_result pool_sim_states_at(const pool_sim *sim, const double *times, int count, pool_ball_state *out,
                               int *bad_index) {
	if (!sim || count < 0 || (count > 0 && (!times || !out)))
		return POOL_ERR_INVALID_ARGUMENT;
	// Every time is checked before any state is written, so a failed call leaves out alone.
	for (int k = 0; k < count; ++k) {
		char what[32];
		snprintf(what, sizeof what, "states_at[%d]", k);
		const pool_result r = readable(sim, what, times[k]);
		if (r != POOL_OK) {
			if (bad_index)
				*bad_index = k;
			return r;
		}
	}
	read_error(sim)->message[0] = '\0';
	for (int k = 0; k < count; ++k)
		pool_history_state_at(&sim->history, &sim->def.params, sim->n, times[k], out + (size_t)k * (size_t)sim->n);
	return POOL_OK;
}

const pool_event *pool_sim_events(const pool_sim *sim, int *count) {
	if (count)
		*count = sim ? sim->history.n_events : 0;
	return sim ? sim->history.events : NULL;
}

const pool_ball_state *pool_sim_event_states(const pool_sim *sim, const pool_event *event) {
	if (!sim || !event || event->first_state < 0 || event->first_state >= sim->history.n_states)
		return NULL;
	return &sim->history.states[event->first_state];
}


const char *pool_sim_last_error(const pool_sim *sim) { return sim ? sim->last_error.message : "sim: missing"; }

pool_result pool_sim_link_stats(const pool_sim *sim, pool_link_stats *out) {
	if (!sim || !out)
		return POOL_ERR_INVALID_ARGUMENT;
	*out = sim->link.stats;
	return POOL_OK;
}
