// LINK clusters (link.h): the trigger, forming and merging clusters, their steps and their
// lengths, balls leaving them, and their dissolution. Everything it knows of the world comes
// through link->world (link.h).
#include "link.h"

#include <math.h>
#include <string.h>

#include "assert.h"
#include "contact.h"
#include "geometry.h"
#include "handlers.h"
#include "memory.h"
#include "motion.h"
#include "predict.h"
#include "table_shape.h"
#include "vec3.h"

// ---- the world, as LINK may ask it

static void state_at(const pool_link *link, int i, double t, pool_ball_state *out) {
	link->world.state_at(link->world.ctx, i, t, out);
}
static void begin_segment(const pool_link *link, int i, const pool_ball_state *s, double t) {
	link->world.begin_segment(link->world.ctx, i, s, t);
}
static pool_result record(const pool_link *link, double t, pool_event_type type, pool_pocket pocket, const int *balls,
                          int m) {
	return link->world.record(link->world.ctx, t, type, pocket, balls, m);
}
// Records an event at t of balls[0..m), which started new segments there, and has their
// contacts predicted again (whatever the record's outcome: the segments have changed).
static pool_result record_changed(const pool_link *link, double t, pool_event_type type, pool_pocket pocket,
                                  const int *balls, int m) {
	const pool_result r = record(link, t, type, pocket, balls, m);
	link->world.changed(link->world.ctx, balls, m, t);
	return r;
}

static int in_play(pool_motion motion) { return motion != POOL_MOTION_POCKETED && motion != POOL_MOTION_OFF_TABLE; }

static int planar(const pool_link *link) { return !link->def->airborne; }

// ---- lifetime

void pool_link_init(pool_link *link, const pool_sim_def *def, const struct pool_table_shape *shape, double dc,
                    const pool_allocator *alloc, const pool_link_world *world) {
	link->def = def;
	link->ws.shape = shape;
	link->dc = dc;
	link->alloc = alloc;
	link->world = *world;
}

void pool_link_clear(pool_link *link) {
	link->n = 0;
	link->starved = 0;
	memset(&link->stats, 0, sizeof link->stats);
	memset(&link->failed_step, 0, sizeof link->failed_step);
	link->failed_size = 0;
	pool_link_bases_clear(&link->ws.bases); // no warm start from another shot: the same input, the same bits
}

void pool_link_free(pool_link *link) {
	void *arrays[] = {link->cluster_of, link->loose,   link->tail,  link->v0,      link->streak, link->clusters,
	                  link->states,     link->now,     link->members, link->mark, link->group, link->leaving,
	                  link->accel};
	pool_link_workspace_free(&link->ws, link->alloc);
	for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i)
		pool_mem_free(link->alloc, arrays[i]);
	link->cluster_of = link->loose = link->members = link->mark = link->group = NULL;
	link->tail = link->v0 = NULL;
	link->streak = NULL;
	link->clusters = NULL;
	link->states = link->now = link->leaving = NULL;
	link->accel = NULL;
	link->cap = link->n = 0;
}

pool_result pool_link_reserve(pool_link *link, int balls) {
	if (balls <= link->cap)
		return POOL_OK;
	const int cap = pool_mem_next_cap(link->cap, balls);
	void **arrays[] = {(void **)&link->cluster_of, (void **)&link->loose,   (void **)&link->tail,
	                   (void **)&link->v0,         (void **)&link->streak,  (void **)&link->clusters,
	                   (void **)&link->states,     (void **)&link->now,     (void **)&link->members,
	                   (void **)&link->mark,       (void **)&link->group,   (void **)&link->leaving,
	                   (void **)&link->accel};
	const size_t elems[] = {sizeof(int),
	                        sizeof(int),
	                        6 * sizeof(double),
	                        6 * sizeof(double),
	                        POOL_LINK_PARTNERS * sizeof(pool_contact_streak),
	                        sizeof(pool_cluster),
	                        sizeof(pool_ball_state),
	                        sizeof(pool_ball_state),
	                        sizeof(int),
	                        sizeof(int),
	                        sizeof(int),
	                        sizeof(pool_ball_state),
	                        sizeof(pool_vec3)};
	if (pool_mem_grow(link->alloc, arrays, elems, (int)(sizeof elems / sizeof elems[0]), link->n, cap))
		return POOL_ERR_OUT_OF_MEMORY;
	link->cap = cap;
	return POOL_OK;
}

void pool_link_add_ball(pool_link *link, int i) {
	link->cluster_of[i] = -1;
	link->loose[i] = 0;
	for (int e = 0; e < 6; ++e)
		link->tail[6 * i + e] = link->v0[6 * i + e] = 0.0;
	for (int k = 0; k < POOL_LINK_PARTNERS; ++k) {
		memset(&link->streak[POOL_LINK_PARTNERS * i + k], 0, sizeof link->streak[0]);
		link->streak[POOL_LINK_PARTNERS * i + k].partner = -1;
	}
	memset(&link->clusters[i], 0, sizeof link->clusters[i]);
	link->n = i + 1;
}

double pool_link_next_step(const pool_link *link, int i) { return link->clusters[link->cluster_of[i]].t_next; }

void pool_link_failure(const pool_link *link, double *residual, int *balls, int *contacts) {
	if (residual)
		*residual = link->failed_step.residual;
	if (balls)
		*balls = link->failed_size;
	if (contacts)
		*contacts = link->failed_step.contacts;
}

// 1 when `events` more LINK events fit under max_events. When they do not, LINK does nothing and
// the shot stops there (POOL_STOP_MAX_EVENTS): a LINK event never takes the count past the limit.
static int has_room(pool_link *link, int events) {
	if (events <= 0 || link->world.room(link->world.ctx) >= events)
		return 1;
	link->starved = 1;
	return 0;
}

// ---- the trigger

// Notes a recorded collision of ball i with `partner` (a ball index, or -2 - rail) at t and
// returns 1 when it completes the trigger (POOL_LINK_TRIGGER_COLLISIONS within the window, or
// POOL_LINK_TRIGGER_SAME_INSTANT at one instant).
static int note_collision(pool_link *link, int i, int partner, double t) {
	pool_contact_streak *streak = link->streak + POOL_LINK_PARTNERS * i;
	int slot = -1, oldest = 0;
	for (int k = 0; k < POOL_LINK_PARTNERS; ++k) {
		if (streak[k].partner == partner)
			slot = k;
		// The slot to reuse: an unused one, else the one whose streak began first.
		if (streak[oldest].partner == -1)
			continue;
		if (streak[k].partner == -1 || streak[k].t0 < streak[oldest].t0)
			oldest = k;
	}
	pool_contact_streak *k = NULL;
	if (slot >= 0 && t - streak[slot].t0 <= POOL_LINK_TRIGGER_WINDOW) {
		k = &streak[slot];
		if (t == k->t_last) {
			k->same++;
		} else {
			k->count++;
			k->same = 1;
		}
	} else {
		k = &streak[slot < 0 ? oldest : slot];
		k->partner = partner;
		k->count = k->same = 1;
		k->t0 = t;
	}
	k->t_last = t;
	return k->count >= POOL_LINK_TRIGGER_COLLISIONS || k->same >= POOL_LINK_TRIGGER_SAME_INSTANT;
}

// ---- clusters

// The cluster's balls, ascending by index (so every step reads them in the same order).
static int members(const pool_link *link, int c, int *out) {
	int m = 0;
	for (int i = 0; i < link->n; ++i)
		if (link->cluster_of[i] == c)
			out[m++] = i;
	return m;
}

// Adds a step's tail (link_step.h: v, then w) to s's velocities.
static void add_tail(pool_ball_state *s, const double *tail) {
	s->vel = pool_v3_add(s->vel, pool_v3(tail[0], tail[1], tail[2]));
	s->omega = pool_v3_add(s->omega, pool_v3(tail[3], tail[4], tail[5]));
}

// Ball i keeps its linked segment's mean velocities (the tail is dropped, or not yet known).
static void drop_tail(pool_link *link, int i) {
	for (int e = 0; e < 6; ++e)
		link->tail[6 * i + e] = 0.0;
}

// Linked ball i's state at t, the end of its step: the segment's mean velocity plus the step's
// tail (zero after an interruption).
static void step_end_state(const pool_link *link, int i, double t, pool_ball_state *s) {
	state_at(link, i, t, s);
	add_tail(s, link->tail + 6 * i);
}

// Ball i joins cluster c at t: it (or the whole cluster it is in) starts linked segments there.
static void end_step_early(pool_link *link, int c, double t);

static void join(pool_link *link, int i, int c, double t) {
	POOL_ASSERT(i >= 0 && i < link->n && c >= 0 && c < link->n && link->clusters[c].active);
	if (link->cluster_of[i] == c)
		return;
	if (link->cluster_of[i] >= 0) {
		const int other = link->cluster_of[i];
		end_step_early(link, other, t); // (absorb recorded it: nothing left to do here)
		link->clusters[other].active = 0;
		for (int k = 0; k < link->n; ++k)
			if (link->cluster_of[k] == other)
				link->cluster_of[k] = -1, join(link, k, c, t);
		return;
	}
	pool_ball_state s;
	state_at(link, i, t, &s);
	s.motion = POOL_MOTION_LINKED;
	link->cluster_of[i] = c;
	link->loose[i] = 0;
	drop_tail(link, i);
	begin_segment(link, i, &s, t);
}

// pressed_pair with the two balls' accelerations given.
static int pressed_with(const pool_ball_state *s, pool_vec3 a0, pool_vec3 a1) {
	const pool_vec3 d = pool_v3_sub(s[0].pos, s[1].pos);
	const double dist = pool_v3_len(d);
	const pool_vec3 n = pool_v3_scale(d, 1.0 / dist);
	const pool_vec3 dv = pool_v3_sub(s[0].vel, s[1].vel);
	const pool_vec3 da = pool_v3_sub(a0, a1);
	// (the curvature of the relative path from dv's part across n itself: pool_v3_across2)
	const double approach_accel = -pool_v3_dot(n, da) - pool_v3_across2(dv, d) / dist;
	return approach_accel > 0.0;
}

// A ball's acceleration without contacts: its closed-form motion's, or for a linked ball (whose
// segment is uniform over a step) that of the state it would resume if released (gravity above
// the cloth, the cloth's friction on it).
static pool_vec3 free_accel(const pool_link *link, const pool_ball_state *s) {
	pool_ball_state f = *s;
	if (f.motion == POOL_MOTION_LINKED) {
		f.motion = POOL_MOTION_SLIDING;
		pool_motion_after_impulse(link->def, &f);
	}
	return pool_motion_accel(&link->def->params, &f);
}

// 1 when two touching balls s[0..2) (closed-form states at the contact) are pressed together:
// their normal approach acceleration, the difference of their free accelerations (a linked
// ball's: as if released, gravity above the cloth) along the normal less the curvature of their
// relative path (|v_t|^2 / 2R parts them), is positive.
static int pressed_pair(const pool_link *link, const pool_ball_state *s) {
	return pressed_with(s, free_accel(link, &s[0]), free_accel(link, &s[1]));
}

// The contact of ball k (state sk, outside the cluster) with cluster ball i (si) presses at
// this instant: they touch (within POOL_LINK_TOUCH_GAP), it is no hit (closing at most
// POOL_LINK_IMPACT_SPEED: faster is a collision, an event), and k closes faster than
// POOL_LINK_REST_SPEED or, closing within the rounding of a speed (POOL_APPROACH_EPS, the
// contact rule's), their free accelerations press them together (gravity on a ball resting on
// others, the cloth's friction driving a spinning ball into its neighbour). Balls that merely
// touch stay out: the balls of a frozen rack touch one another, and a step that linked them all
// would solve the whole rack's contacts.
static int pressing(const pool_link *link, const pool_ball_state *si, const pool_ball_state *sk) {
	const double reach = 2.0 * link->def->params.ball_radius + POOL_LINK_TOUCH_GAP;
	const double dist = pool_v3_len(pool_v3_sub(sk->pos, si->pos));
	if (!(dist <= reach) || !(dist > 0.0))
		return 0;
	const double closing = pool_closing_speed(sk->pos, sk->vel, si->pos, si->vel);
	if (!(closing <= POOL_LINK_IMPACT_SPEED))
		return 0;
	if (closing > POOL_LINK_REST_SPEED)
		return 1;
	if (closing < -POOL_APPROACH_EPS)
		return 0;
	const pool_ball_state pair[2] = {*sk, *si};
	return pressed_with(pair, free_accel(link, sk), free_accel(link, si));
}

// Gathers into link->mark the balls of cluster c at t, the seeds seed[0..m) with the clusters
// they are in, and every ball in play whose contact with one of them presses (pressing),
// transitively: one pass over the contacts of every gathered ball, each ball's state at t taken
// once (link->now). A ball of another cluster brings its whole cluster. Returns how many of
// the clusters it brings have a step in progress (absorb ends each there, recorded).
static int gather(pool_link *link, int c, const int *seed, int m, double t) {
	const int n = link->n;
	int *queue = link->members, count = 0, cuts = 0;
	for (int k = 0; k < n; ++k) {
		state_at(link, k, t, &link->now[k]);
		link->mark[k] = c >= 0 && link->cluster_of[k] == c;
	}
	for (int j = 0; j < m; ++j) {
		const int other = link->cluster_of[seed[j]];
		if (other >= 0 && other != c && !link->mark[seed[j]])
			cuts += link->clusters[other].in_step;
		for (int k = 0; k < n; ++k)
			link->mark[k] |= k == seed[j] || (other >= 0 && link->cluster_of[k] == other);
	}
	for (int k = 0; k < n; ++k)
		if (link->mark[k])
			queue[count++] = k;
	for (int head = 0; head < count; ++head) {
		const pool_ball_state *si = &link->now[queue[head]];
		for (int k = 0; k < n; ++k) {
			if (link->mark[k] || !in_play(link->now[k].motion) || !pressing(link, si, &link->now[k]))
				continue;
			const int other = link->cluster_of[k];
			if (other >= 0)
				cuts += link->clusters[other].in_step;
			for (int q = 0; q < n; ++q)
				if (!link->mark[q] && (q == k || (other >= 0 && link->cluster_of[q] == other))) {
					link->mark[q] = 1;
					queue[count++] = q;
				}
		}
	}
	return cuts;
}

static pool_result cut_cluster(pool_link *link, int c, double t);

// Joins into cluster c at t the balls gather() marked: the steps in progress of the clusters
// they bring end there first, each recorded (link_step), so every velocity a step changed is
// in the history before the balls move on in c.
static pool_result absorb(pool_link *link, int c, double t) {
	for (int k = 0; k < link->n; ++k) {
		const int other = link->cluster_of[k];
		if (link->mark[k] && other >= 0 && other != c && link->clusters[other].in_step) {
			const pool_result r = cut_cluster(link, other, t);
			if (r)
				return r;
		}
	}
	for (int k = 0; k < link->n; ++k)
		if (link->mark[k])
			join(link, k, c, t);
	return POOL_OK;
}

// Every member's next event becomes the cluster's step at t_next.
static void reschedule(pool_link *link, int c, double now) {
	int *idx = link->members;
	const int m = members(link, c, idx);
	link->world.refresh(link->world.ctx, idx, m, now);
}

// Something from outside changed cluster c: what its last step decided about who leaves no
// longer holds, and the next step, POOL_LINK_STEP_TIME long again, decides afresh.
static void unsettle(pool_link *link, int c) {
	link->clusters[c].quiet = 0;
	link->clusters[c].dt = POOL_LINK_STEP_TIME;
	for (int k = 0; k < link->n; ++k)
		if (link->cluster_of[k] == c) {
			link->loose[k] = 0;
			drop_tail(link, k);
		}
}

// Cluster c's step in progress ends at t, before its planned end: every velocity it changed (the
// gravity kick, the contact impulses, the cloth wrenches, all applied for the whole step at its
// start) is taken for the share of the step that passed, v = v0 + (h / dt) (v_end - v0), with h
// = t - t_start the time it lasted and dt its planned length; the positions are those its mean
// velocities brought (the history's). Kept whole, a step cut after 0.3 of its 7.5 ms kept a
// falling ball's whole gravity kick, energy from nowhere (issue 21). The new velocities are a
// mean of the step's start and end ones, so by convexity the cluster's energy at the cut is at
// most that same mean of its energies at the step's start and planned end.
static void end_step_early(pool_link *link, int c, double t) {
	pool_cluster *cl = &link->clusters[c];
	if (!cl->in_step)
		return;
	const double lasted = t - cl->t_start;
	POOL_ASSERT(lasted >= 0.0 && t <= cl->t_next); // a step is cut inside itself
	const double share = cl->step_dt > 0.0 ? fmin(fmax(lasted / cl->step_dt, 0.0), 1.0) : 1.0;
	for (int k = 0; k < link->n; ++k) {
		if (link->cluster_of[k] != c)
			continue;
		pool_ball_state s;
		step_end_state(link, k, t, &s);
		const double *v0 = link->v0 + 6 * k;
		s.vel = pool_v3_add(pool_v3(v0[0], v0[1], v0[2]),
		                    pool_v3_scale(pool_v3_sub(s.vel, pool_v3(v0[0], v0[1], v0[2])), share));
		s.omega = pool_v3_add(pool_v3(v0[3], v0[4], v0[5]),
		                      pool_v3_scale(pool_v3_sub(s.omega, pool_v3(v0[3], v0[4], v0[5])), share));
		s.motion = POOL_MOTION_LINKED;
		drop_tail(link, k);
		begin_segment(link, k, &s, t);
	}
	cl->in_step = 0;
}

// Cluster c's step ends at t (end_step_early) and a link_step records its balls' states there;
// the cluster steps again at t, from POOL_LINK_STEP_TIME.
static pool_result cut_cluster(pool_link *link, int c, double t) {
	link->clusters[c].t_next = t; // (before the segments restart: their next event is that step)
	end_step_early(link, c, t);
	unsettle(link, c);
	int *idx = link->members;
	const int m = members(link, c, idx);
	return record_changed(link, t, POOL_EVENT_LINK_STEP, POOL_POCKET_NONE, idx, m);
}

pool_result pool_link_cut(pool_link *link, const int *inv, int m, double t) {
	// Room for every cut and for the event that cuts them, recorded right after: at the event
	// limit the shot stops before the event, not after its cuts with the event one too many.
	int cuts = 0;
	for (int k = 0; k < m; ++k) {
		const int c = link->cluster_of[inv[k]];
		cuts += c >= 0 && link->clusters[c].in_step && !(k == 1 && c == link->cluster_of[inv[0]]);
	}
	if (cuts > 0 && !has_room(link, cuts + 1))
		return POOL_OK;
	for (int k = 0; k < m; ++k) {
		const int c = link->cluster_of[inv[k]];
		if (c < 0 || !link->clusters[c].in_step)
			continue;
		const pool_result r = cut_cluster(link, c, t);
		if (r)
			return r;
	}
	return POOL_OK;
}

// Forms a cluster at t around the balls seed[0..m) (merging every cluster they touch) and
// records link_begin; its first step is at t.
static pool_result link_begin(pool_link *link, const int *seed, int m, double t) {
	int c = -1;
	for (int k = 0; k < m; ++k) {
		const int in = link->cluster_of[seed[k]];
		if (in >= 0 && (c < 0 || in < c))
			c = in;
	}
	// Its balls first, and the room for link_begin and the cuts of the steps it ends.
	const int cuts = gather(link, c, seed, m, t) + (c >= 0 && link->clusters[c].in_step);
	if (!has_room(link, 1 + cuts))
		return POOL_OK;
	if (c >= 0 && link->clusters[c].in_step) {
		const pool_result rc = cut_cluster(link, c, t);
		if (rc)
			return rc;
	}
	if (c < 0) {
		for (c = 0; c < link->n && link->clusters[c].active; ++c) {
		}
		POOL_ASSERT(c < link->n); // a cluster has a ball: there are never more than balls
		memset(&link->clusters[c], 0, sizeof link->clusters[c]);
		link->stats.clusters++;
	}
	link->clusters[c].active = 1;
	link->clusters[c].t_next = t;
	unsettle(link, c);
	const pool_result ra = absorb(link, c, t);
	if (ra)
		return ra;
	int *idx = link->members;
	const int count = members(link, c, idx);
	// Every ball restarts its segment here, so link_begin records every ball's state at t (the
	// history evolves each recorded state from its event's time); for a ball whose segment began
	// at t that is the same segment.
	for (int k = 0; k < count; ++k) {
		pool_ball_state s;
		state_at(link, idx[k], t, &s);
		begin_segment(link, idx[k], &s, t);
	}
	const pool_result r = record(link, t, POOL_EVENT_LINK_BEGIN, POOL_POCKET_NONE, idx, count);
	reschedule(link, c, t);
	return r;
}

// Every ball of the cluster still (a heap resting on itself: nothing to step until hit).
static int all_still(const pool_link *link, const pool_ball_state *s, int m) {
	const double R = link->def->params.ball_radius;
	for (int k = 0; k < m; ++k)
		if (pool_v3_len(s[k].vel) > POOL_LINK_REST_SPEED || pool_v3_len(s[k].omega) * R > POOL_LINK_REST_SPEED)
			return 0;
	return 1;
}

// Groups (in group[0..m)) the balls of s[0..m) that touch and whose velocities, and with
// `spin_too` their spins' surface speeds, agree to within POOL_APPROACH_EPS.
static void group_common(const pool_link *link, const pool_ball_state *s, int m, int spin_too, int *group) {
	const double R = link->def->params.ball_radius, reach = 2.0 * R + POOL_LINK_TOUCH_GAP;
	for (int k = 0; k < m; ++k)
		group[k] = k;
	for (int a = 0; a < m; ++a)
		for (int b = a + 1; b < m; ++b) {
			const double dv = pool_v3_len(pool_v3_sub(s[a].vel, s[b].vel));
			const double dw = spin_too ? pool_v3_len(pool_v3_sub(s[a].omega, s[b].omega)) * R : 0.0;
			if (pool_v3_len(pool_v3_sub(s[a].pos, s[b].pos)) > reach || dv > POOL_APPROACH_EPS || dw > POOL_APPROACH_EPS)
				continue;
			const int ga = group[a], gb = group[b];
			for (int k = 0; k < m; ++k)
				if (group[k] == gb)
					group[k] = ga;
		}
}

// Balls of s[0..m) that touch and move together to within POOL_APPROACH_EPS get their group's
// mean velocity, exactly the same doubles, and those whose spins agree too the group's mean
// spin: two balls rolling (or sliding) together in contact then decelerate identically in
// closed form and never meet again, where the rounding of the LCP's solution (1e-14 m/s)
// would make them "collide" by nothing at every event. The means keep momentum and never add
// energy.
static void merge_common_motion(const pool_link *link, pool_ball_state *s, int m, int *group) {
	for (int pass = 0; pass < 2; ++pass) {
		group_common(link, s, m, pass, group);
		for (int g = 0; g < m; ++g) {
			pool_vec3 mean = {0.0, 0.0, 0.0};
			int count = 0;
			for (int k = 0; k < m; ++k)
				if (group[k] == g) {
					mean = pool_v3_add(mean, pass ? s[k].omega : s[k].vel);
					count++;
				}
			if (count < 2)
				continue;
			mean = pool_v3_scale(mean, 1.0 / count);
			for (int k = 0; k < m; ++k)
				if (group[k] == g)
					*(pass ? &s[k].omega : &s[k].vel) = mean;
		}
	}
}

/// m/s: a ball leaving a cluster on the cloth slower than this (velocity, and spin's surface
/// speed) leaves at rest. The LCP's rounding leaves touching balls drifting at up to ~1e-10 m/s,
/// which the closed forms would take for balls rolling into their neighbours, "colliding" again
/// and again at one instant; stopping a ball 100 times faster than that moves it from the path
/// the step gave it by 1e-11 m per millisecond, far inside POOL_TOUCH_TOLERANCE. (Inside a step
/// the velocities stay exactly the LCP's, whose contacts they keep apart.)
#define POOL_LINK_SETTLE_SPEED 1e-8

/// Relative residual above which a step longer than POOL_LINK_STEP_TIME is taken again at
/// that length. A solve's velocities are off by at most its residual times 1 + the cluster's
/// speeds (link_step.h), and the positions by that times dt: the steps' own limit,
/// POOL_LINK_RESIDUAL_MAX, over 16 ms would let balls into each other by 1.6e-8 m; 1e-9 keeps
/// a long step's error below 1e-10 m, a tenth of POOL_TOUCH_TOLERANCE. (Lemke's residuals are
/// 1e-16 to 1e-12 on most solves.)
#define POOL_LINK_LONG_STEP_RESIDUAL 1e-9

static void settle(const pool_link *link, pool_ball_state *s) {
	const double R = link->def->params.ball_radius;
	const pool_vec3 w_perp = pool_v3(s->omega.x, s->omega.y, 0.0);
	if (s->pos.z > R + POOL_TOUCH_TOLERANCE || pool_v3_len(s->vel) > POOL_LINK_SETTLE_SPEED ||
	    pool_v3_len(w_perp) * R > POOL_LINK_SETTLE_SPEED)
		return;
	s->vel = pool_v3(0.0, 0.0, 0.0);
	s->omega.x = s->omega.y = 0.0;
	if (fabs(s->omega.z) * R <= POOL_LINK_SETTLE_SPEED)
		s->omega.z = 0.0;
}

// Turns the end-of-step states s[0..m) of balls leaving a cluster together into the closed-form
// states they resume: balls moving together share their motion, a crawling ball on the cloth
// settles, and the on-cloth state of the velocities is derived (airborne above the cloth).
static void leaving_states(pool_link *link, pool_ball_state *s, int m) {
	merge_common_motion(link, s, m, link->group);
	for (int k = 0; k < m; ++k) {
		settle(link, &s[k]);
		s[k].motion = POOL_MOTION_SLIDING;
		pool_motion_after_impulse(link->def, &s[k]);
	}
}

// Balls idx[0..m) of a cluster leave it at t and resume their closed-form states, with the
// velocities of the last step (its motion up to t): airborne above the cloth, else the on-cloth
// state of the velocities (pool_motion_after_impulse derives it); link_end records them.
static pool_result release(pool_link *link, const int *idx, int m, double t) {
	pool_ball_state *s = link->states;
	for (int k = 0; k < m; ++k)
		step_end_state(link, idx[k], t, &s[k]);
	leaving_states(link, s, m);
	for (int k = 0; k < m; ++k) {
		link->cluster_of[idx[k]] = -1;
		link->loose[idx[k]] = 0;
		begin_segment(link, idx[k], &s[k], t);
	}
	return record_changed(link, t, POOL_EVENT_LINK_END, POOL_POCKET_NONE, idx, m);
}

// The pocket a member at pos has strayed into: past a rail's contact line inside a pocket mouth
// (pockets "jaws": over a hole) and below the nose, as in flight. Above the nose a ball over a
// pocket is not in it: it rides a nose from above (soak seed 21, mouth shot 184749 and
// extreme_params shot 12377: a ball landing on a facing from above was linked at once and
// dropped into the hole 2R above the cloth).
static pool_pocket stray_pocket(const pool_link *link, pool_vec3 pos) {
	if (!(pos.z < link->def->table.cushion_height))
		return POOL_POCKET_NONE;
	return pool_table_pocket_past(&link->def->table, link->dc, pos);
}

// Members past a rail's contact line inside a pocket mouth at t (the step's LCP has no rail
// there; the crossing's own pocket event is predicted, this catches a ball that was already
// past the line when its segment began) fall into that pocket now.
static pool_result pocket_strays(pool_link *link, int c, double t) {
	for (int k = 0; k < link->n; ++k) {
		if (link->cluster_of[k] != c)
			continue;
		pool_ball_state s;
		state_at(link, k, t, &s);
		const pool_pocket pocket = stray_pocket(link, s.pos);
		if (pocket == POOL_POCKET_NONE)
			continue;
		if (link->world.reserve(link->world.ctx, 1, 1))
			return POOL_ERR_OUT_OF_MEMORY;
		pool_take_out_of_play(&s, POOL_MOTION_POCKETED);
		link->cluster_of[k] = -1;
		begin_segment(link, k, &s, t);
		const pool_result r = record_changed(link, t, POOL_EVENT_POCKET, pocket, &k, 1);
		if (r)
			return r;
	}
	return POOL_OK;
}

// Loose balls (states s[0..m) after the step, the cluster's idx[0..m)) that the closed forms
// would press together again at once stay linked: leaving, they would collide at once with
// nothing to part them and the trigger would link them again, one cluster per step where one
// cluster holds them.
static void hold_pressed(pool_link *link, const int *idx, const pool_ball_state *s, int m, double dt) {
	pool_ball_state *free_state = link->leaving;
	for (int k = 0; k < m; ++k) {
		free_state[k] = s[k];
		add_tail(&free_state[k], link->ws.ball_tail + 6 * k);
		// accel held the velocity at the step's start (pool_link_step_event)
		link->accel[k] = pool_v3_scale(pool_v3_sub(free_state[k].vel, link->accel[k]), 1.0 / dt);
	}
	leaving_states(link, free_state, m); // as release() would make them
	// A loose ball touching one that stays is held too when that one closes on it or presses
	// it (the staying ball moving uniformly, as linked balls do): it would be hit at once.
	const double reach = 2.0 * link->def->params.ball_radius + POOL_LINK_TOUCH_GAP;
	for (int changed = 1; changed;) {
		changed = 0;
		for (int a = 0; a < m; ++a)
			for (int b = a + 1; b < m; ++b) {
				int *la = &link->loose[idx[a]], *lb = &link->loose[idx[b]];
				if ((!*la && !*lb) || !(pool_v3_len(pool_v3_sub(s[a].pos, s[b].pos)) <= reach))
					continue;
				// A staying ball goes on as its last step did (its acceleration over it).
				const pool_ball_state pair[2] = {free_state[a], free_state[b]};
				const pool_vec3 aa = *la ? pool_motion_accel(&link->def->params, &pair[0]) : link->accel[a];
				const pool_vec3 ab = *lb ? pool_motion_accel(&link->def->params, &pair[1]) : link->accel[b];
				const double closing = pool_closing_speed(pair[0].pos, pair[0].vel, pair[1].pos, pair[1].vel);
				if (closing > POOL_APPROACH_EPS || pressed_with(pair, aa, ab)) {
					changed |= *la | *lb;
					*la = *lb = 0;
				}
			}
	}
}

// The length of the step after one of length dt whose contacts accelerated a ball by at most
// accel (POOL_LINK_STEP_MAX says why).
static double next_step_length(double dt, double accel) {
	const double bound = accel > 0.0 ? sqrt(2.0 * POOL_LINK_STEP_ERROR / accel) : INFINITY;
	return fmax(POOL_LINK_STEP_TIME, fmin(fmin(2.0 * dt, POOL_LINK_STEP_MAX), bound));
}

// Ball i's velocities entering the step: those of s.
static void set_v0(pool_link *link, int i, const pool_ball_state *s) {
	double *v0 = link->v0 + 6 * i;
	v0[0] = s->vel.x, v0[1] = s->vel.y, v0[2] = s->vel.z;
	v0[3] = s->omega.x, v0[4] = s->omega.y, v0[5] = s->omega.z;
}

// The step of cluster c's balls idx[0..m) from their positions in s and their velocities v0: on
// return s holds the step's mean velocities. A step longer than POOL_LINK_STEP_TIME whose solve
// left a residual above POOL_LINK_LONG_STEP_RESIDUAL is taken again at that length (its velocity
// error moves the balls by that times dt).
static pool_result solve(pool_link *link, pool_cluster *cl, const int *idx, pool_ball_state *s, int m,
                         pool_link_step_stats *st) {
	for (int pass = 0; pass < 2; ++pass) {
		for (int k = 0; k < m; ++k) {
			const double *v0 = link->v0 + 6 * idx[k];
			s[k].vel = pool_v3(v0[0], v0[1], v0[2]);
			s[k].omega = pool_v3(v0[3], v0[4], v0[5]);
			link->accel[k] = s[k].vel;
		}
		const pool_result r = pool_link_step(link->def, s, m, cl->dt, &link->ws, link->alloc, st);
		if (r) {
			link->failed_step = *st;
			link->failed_size = m;
			return r;
		}
		if (pass > 0 || !(cl->dt > POOL_LINK_STEP_TIME && st->residual > POOL_LINK_LONG_STEP_RESIDUAL))
			return POOL_OK;
		link->stats.pivots += st->pivots;
		cl->dt = POOL_LINK_STEP_TIME;
	}
	return POOL_OK;
}

// Ball k (state sk, outside) would collide now with cluster ball i moving at the step's mean
// velocity (si): the schedule's own prediction (predict.h, the contact rule of contact.h), with
// the step's ball moving uniformly, has them meet at once. At whatever speed: this contact is
// the step's own doing, not a hit from outside (where faster than POOL_LINK_IMPACT_SPEED is a
// collision), and it can only be taken inside the step: as an event at the step's start it would
// cut the step after no time, undoing what drove it, and the cluster would step again for ever.
static int driven_into(const pool_link *link, const pool_ball_state *si, const pool_ball_state *sk) {
	const double R = link->def->params.ball_radius;
	const pool_vec3 dp = pool_v3_sub(sk->pos, si->pos);
	if (!(pool_v3_len(dp) - 2.0 * R <= POOL_TOUCH_TOLERANCE))
		return 0;
	const pool_vec3 da = pool_v3_scale(pool_motion_accel(&link->def->params, sk), 0.5);
	return pool_predict_ball_ball(dp, pool_v3_sub(sk->vel, si->vel), da, R, POOL_LINK_STEP_TIME) <= 0.0;
}

// Joins into cluster c the balls in play outside it that the step's mean velocities s[0..m)
// drive into (driven_into), each entering the next solve with its own velocities (a ball of
// another cluster brings that cluster, whose step in progress ends there, recorded: two
// clusters pressing each other are one); returns how many joined. (The link_step of this step
// is still to be recorded: a cut needs room for itself and that.)
static int drive_in(pool_link *link, int c, const pool_ball_state *s, int m, double t) {
	int joined = 0;
	for (int k = 0; k < link->n; ++k) {
		const int other = link->cluster_of[k];
		if (other == c)
			continue;
		const int cut = other >= 0 && link->clusters[other].in_step;
		if (cut && link->world.room(link->world.ctx) < 2)
			continue; // (left to the collision's events, which stop the shot at the limit)
		// (Positions do not change at t: gather's are good for the cheap test of distance.)
		int near = 0;
		for (int q = 0; q < m && !near; ++q)
			near = pool_v3_len(pool_v3_sub(link->now[k].pos, s[q].pos)) - 2.0 * link->def->params.ball_radius <=
			       POOL_TOUCH_TOLERANCE;
		if (!near)
			continue;
		pool_ball_state sk;
		state_at(link, k, t, &sk);
		if (!in_play(sk.motion))
			continue;
		for (int q = 0; q < m; ++q)
			if (driven_into(link, &s[q], &sk)) {
				if (cut && cut_cluster(link, other, t))
					return joined; // (out of memory: the failed record has failed the shot)
				for (int j = 0; j < link->n; ++j) // it, or the cluster it is in
					if (j == k || (other >= 0 && link->cluster_of[j] == other)) {
						pool_ball_state sj;
						state_at(link, j, t, &sj);
						set_v0(link, j, &sj);
					}
				join(link, k, c, t);
				++joined;
				break;
			}
	}
	return joined;
}

pool_result pool_link_step_event(pool_link *link, int i, double t) {
	const int c = link->cluster_of[i];
	POOL_ASSERT(c >= 0 && link->clusters[c].active); // a step event is a linked ball's
	pool_cluster *cl = &link->clusters[c];
	// The balls of the next step (gathered afresh at every step), and the room for the events
	// this one records: the cuts of the clusters it takes in, the pocketed strays, the loose
	// balls' link_end and the link_step.
	const int cuts = gather(link, c, NULL, 0, t);
	int gathered = 0, strays = 0, loose_now = 0;
	for (int k = 0; k < link->n; ++k) {
		if (!link->mark[k])
			continue;
		++gathered;
		if (stray_pocket(link, link->now[k].pos) != POOL_POCKET_NONE)
			++strays;
		else
			loose_now += link->cluster_of[k] == c && link->loose[k];
	}
	const int rest = gathered - strays;
	const int need = cuts + strays + (rest == 0 ? 0 : cl->quiet ? 1 : (loose_now > 0) + (rest > loose_now));
	if (!has_room(link, need))
		return POOL_OK;
	cl->in_step = 0; // the step ends as planned: its balls leave it with its end's velocities
	const pool_result ra = absorb(link, c, t);
	if (ra)
		return ra;
	const pool_result rp = pocket_strays(link, c, t);
	if (rp)
		return rp;
	int *idx = link->members;
	pool_ball_state *s = link->states;
	int m = members(link, c, idx);
	if (m == 0) {
		cl->active = 0;
		return POOL_OK;
	}
	// Leaving is decided by the last step, so every cluster takes at least one step (a Zeno
	// pair is merged by it) and a leaving ball keeps the motion it had.
	if (cl->quiet) {
		cl->active = 0;
		return release(link, idx, m, t);
	}
	// The loose balls first (members keep ascending order within each part), then they leave:
	// one link_end with them (pool_sim_step reserved the history for it and the step).
	int loose = 0;
	for (int k = 0; k < m; ++k)
		if (link->loose[idx[k]]) {
			const int ball = idx[k];
			for (int j = k; j > loose; --j)
				idx[j] = idx[j - 1];
			idx[loose++] = ball;
		}
	if (loose > 0) {
		const pool_result rr = release(link, idx, loose, t);
		if (rr)
			return rr;
		m = members(link, c, idx);
		if (m == 0) {
			cl->active = 0;
			return POOL_OK;
		}
	}
	for (int k = 0; k < m; ++k) {
		step_end_state(link, idx[k], t, &s[k]);
		drop_tail(link, idx[k]);
		set_v0(link, idx[k], &s[k]);
	}
	pool_link_step_stats st;
	for (int round = 0;; ++round) {
		const pool_result r = solve(link, cl, idx, s, m, &st);
		if (r)
			return r;
		// Touching balls the step's velocities drive into (the contact rule would have them
		// collide at this very instant) are pressed by the cluster: they join it and the step
		// is solved again with them. Left out, each would be hit at once, and that hit would cut
		// the step after no time, restoring the velocities under which nothing closes: the
		// cluster would step, be cut and step again at one instant for ever.
		if (round == link->n || !drive_in(link, c, s, m, t))
			break;
		link->stats.pivots += st.pivots;
		m = members(link, c, idx);
		for (int k = 0; k < m; ++k)
			state_at(link, idx[k], t, &s[k]);
	}
	pool_link_stats *total = &link->stats;
	total->steps++;
	total->pivots += st.pivots;
	total->warm_solves += st.warm;
	total->max_balls = m > total->max_balls ? m : total->max_balls;
	total->max_contacts = st.contacts > total->max_contacts ? st.contacts : total->max_contacts;
	total->max_residual = fmax(total->max_residual, st.residual);
	cl->steps++;
	const int still = all_still(link, s, m);
	const double this_dt = cl->dt;
	// A ball nothing presses leaves at the next step: on the cloth the closed forms take over
	// its contacts (two balls rolling together in contact stay so by themselves; if friction
	// presses them again, the trigger links them again), above it only once it touches
	// nothing. The cluster dissolves when every ball leaves; a heap at rest above the cloth
	// sleeps instead.
	for (int k = 0; k < m; ++k) {
		const int on_cloth = s[k].pos.z <= link->def->params.ball_radius + POOL_TOUCH_TOLERANCE;
		// (the push of a step of dt: POOL_LINK_PUSH_MIN per POOL_LINK_STEP_TIME)
		const int unpressed = link->ws.ball_push[k] <= POOL_LINK_PUSH_MIN * (this_dt / POOL_LINK_STEP_TIME);
		link->loose[idx[k]] = (on_cloth && (unpressed || still)) || (unpressed && link->ws.ball_touching[k] == 0);
	}
	hold_pressed(link, idx, s, m, cl->dt);
	int leaving = 0;
	for (int k = 0; k < m; ++k)
		leaving += link->loose[idx[k]];
	cl->quiet = leaving == m;
	// A cluster whose balls are all still and all held sleeps until something hits it: its
	// balls are then at rest (slower than POOL_LINK_REST_SPEED, they would otherwise creep on
	// for ever without another step: a ball held to a rail at 1e-7 m/s, the soak's rail_drift).
	const int sleeps = still && leaving == 0;
	cl->t_next = sleeps ? INFINITY : t + this_dt;
	cl->dt = next_step_length(this_dt, st.max_contact_accel);
	// The step in progress: from t, planned for this_dt (a sleeping heap has none: it is at rest).
	cl->in_step = !sleeps;
	cl->t_start = t;
	cl->step_dt = this_dt;
	for (int k = 0; k < m; ++k) {
		if (sleeps) {
			s[k].vel = s[k].omega = pool_v3(0.0, 0.0, 0.0);
			for (int e = 0; e < 6; ++e)
				link->ws.ball_tail[6 * k + e] = 0.0;
		}
		memcpy(link->tail + 6 * idx[k], link->ws.ball_tail + 6 * k, 6 * sizeof(double));
		s[k].motion = POOL_MOTION_LINKED;
		// The LCP's rounding (down to 1e-36 m/s) is no motion: a linked ball drifting at it
		// would "collide" with every touching ball outside. Below POOL_REST_EPS, as in the
		// closed-form states' own clean-up, a velocity or spin is zero (1e-15 m per step).
		if (pool_v3_len(s[k].vel) <= POOL_REST_EPS)
			s[k].vel = pool_v3(0.0, 0.0, 0.0);
		if (pool_v3_len(s[k].omega) * link->def->params.ball_radius <= POOL_REST_EPS)
			s[k].omega = pool_v3(0.0, 0.0, 0.0);
		if (planar(link)) {
			s[k].pos.z = link->def->params.ball_radius;
			s[k].vel.z = 0.0;
		}
		begin_segment(link, idx[k], &s[k], t);
	}
	return record_changed(link, t, POOL_EVENT_LINK_STEP, POOL_POCKET_NONE, idx, m);
}

// A ball within touch of the cushion and driven into it faster than the cluster's own forces close
// a contact. With pockets "jaws" the cushion is the nose curve, each part whose span the centre
// faces (the parts the step's contacts are, link_step.c): a ball over a mouth has no rail to be
// driven into, and one against a facing or jaw is driven along that part's normal. The other
// models keep the four rails' contact lines.
static int driven_into_cushion(const pool_link *link, const pool_ball_state *s) {
	const pool_table_shape *shape = link->ws.shape;
	if (shape && shape->table.pockets == POOL_POCKETS_JAWS) {
		const double R = link->def->params.ball_radius;
		for (int k = 0; k < shape->n_parts; ++k) {
			if (!pool_shape_in_span(shape, k, s->pos))
				continue;
			const double gap = pool_v3_len(pool_v3_sub(s->pos, pool_shape_nearest(shape, k, s->pos))) - R;
			if (gap <= POOL_LINK_TOUCH_GAP &&
			    -pool_v3_dot(s->vel, pool_shape_normal(shape, k, s->pos)) > POOL_LINK_IMPACT_SPEED)
				return 1;
		}
		return 0;
	}
	pool_rail rails[4];
	pool_vec3 into[4];
	const int near = pool_table_cushions_near(&link->def->table, link->dc, s->pos, POOL_LINK_TOUCH_GAP, rails, into);
	for (int k = 0; k < near; ++k)
		if (pool_v3_dot(s->vel, into[k]) > POOL_LINK_IMPACT_SPEED)
			return 1;
	return 0;
}

// A contact inside cluster c (two of its balls, or one and the cushion, touching) closing
// faster than POOL_LINK_IMPACT_SPEED at t: a hit from outside passed on into the cluster.
static int hit_inside(pool_link *link, int c, double t) {
	const double reach = 2.0 * link->def->params.ball_radius + POOL_LINK_TOUCH_GAP;
	int *idx = link->members;
	pool_ball_state *s = link->states;
	const int m = members(link, c, idx);
	for (int k = 0; k < m; ++k)
		state_at(link, idx[k], t, &s[k]);
	for (int a = 0; a < m; ++a) {
		for (int b = a + 1; b < m; ++b) {
			const pool_vec3 d = pool_v3_sub(s[b].pos, s[a].pos);
			const double dist = pool_v3_len(d);
			if (dist <= reach && dist > 0.0 &&
			    pool_closing_speed(s[a].pos, s[a].vel, s[b].pos, s[b].vel) > POOL_LINK_IMPACT_SPEED)
				return 1;
		}
		if (driven_into_cushion(link, &s[a]))
			return 1;
	}
	return 0;
}

// After an event from outside changed member i's state at t (already its new segment start):
// keeps it linked and makes its cluster step at t, so no event inside a step is skipped.
static pool_result touched(pool_link *link, int i, double t) {
	const int c = link->cluster_of[i];
	link->clusters[c].t_next = t;
	unsettle(link, c);
	// A hit passed on into the cluster (a ball hit into its neighbour or into the rail faster
	// than the cluster's own forces close a contact): the cluster dissolves and the impulses of
	// events pass it on, with restitution, where the inelastic step would absorb the bounce; if
	// the balls press one another again, the trigger links them again. (pool_sim_step reserved
	// the history for the link_end.)
	if (hit_inside(link, c, t) && has_room(link, 1)) {
		int *idx = link->members;
		const int m = members(link, c, idx);
		link->clusters[c].active = 0;
		return release(link, idx, m, t);
	}
	reschedule(link, c, t);
	return POOL_OK;
}

// Member i left play (pocketed, off the table) at t: it leaves its cluster, which steps at t.
static void left(pool_link *link, int i, double t) {
	const int c = link->cluster_of[i];
	link->cluster_of[i] = -1;
	int any = 0;
	for (int k = 0; k < link->n; ++k)
		any |= link->cluster_of[k] == c;
	if (!any) {
		link->clusters[c].active = 0;
		return;
	}
	link->clusters[c].t_next = t;
	unsettle(link, c);
	reschedule(link, c, t);
}

/// m/s: a pair whose centres separate faster than this after a collision parts (the hitter of a
/// cluster's ball then stays out of the cluster). The contact rule's own threshold for a pair
/// closing (contact.h), so a pair that does not part is one the rule would see touching or closing.
#define POOL_PARTING_SPEED POOL_APPROACH_EPS

// The two balls of s[0..1] (just after their collision) separate faster than POOL_PARTING_SPEED.
static int parting(const pool_ball_state *s) {
	const pool_vec3 d = pool_v3_sub(s[1].pos, s[0].pos);
	const double dist = pool_v3_len(d);
	return dist > 0.0 && -pool_closing_speed(s[0].pos, s[0].vel, s[1].pos, s[1].vel) > POOL_PARTING_SPEED;
}

int pool_link_take_pressed(pool_link *link, pool_event_type type, const int *inv, const pool_ball_state *s, int m,
                           double t, pool_result *result) {
	if (!(type == POOL_EVENT_BALL_CUSHION || (type == POOL_EVENT_BALL_BALL && pressed_pair(link, s))))
		return 0;
	const int c0 = link->cluster_of[inv[0]];
	if (c0 >= 0 && (m == 1 || c0 == link->cluster_of[inv[1]]))
		return 0;
	*result = link_begin(link, inv, m, t);
	return 1;
}

void pool_link_keep_linked(const pool_link *link, const int *inv, pool_ball_state *s, int m) {
	for (int k = 0; k < m; ++k)
		if (link->cluster_of[inv[k]] >= 0 && in_play(s[k].motion))
			s[k].motion = POOL_MOTION_LINKED;
}

pool_result pool_link_after_event(pool_link *link, pool_event_type type, pool_rail rail, const int *inv,
                                  const pool_ball_state *s, int m, double t) {
	// A ball that hit a cluster's ball and does not part from it joins the cluster: if the
	// cluster presses it, the next step holds it (rather than impulses at one instant, each
	// after a whole step's forces); if not, the step finds it loose and it leaves. One that
	// parts (Petit's law sends it off at e times its approach) stays out: the cluster's next
	// step would only find it loose, at the price of an LCP with all its contacts (a break's
	// balls running into a cluster in the rack: 8 balls, 21 contacts), and should the cluster
	// catch it again, the trigger links the pair.
	if (type == POOL_EVENT_BALL_BALL && in_play(s[0].motion) && in_play(s[1].motion) &&
	    (link->cluster_of[inv[0]] >= 0) != (link->cluster_of[inv[1]] >= 0) && !parting(s)) {
		const int member = link->cluster_of[inv[0]] >= 0 ? 0 : 1;
		join(link, inv[1 - member], link->cluster_of[inv[member]], t);
	}
	// The cluster of a ball the event changed steps now: no event inside a step is skipped.
	for (int k = 0; k < m; ++k) {
		if (link->cluster_of[inv[k]] < 0)
			continue;
		if (in_play(s[k].motion)) {
			const pool_result r = touched(link, inv[k], t);
			if (r)
				return r;
		} else {
			left(link, inv[k], t);
		}
	}
	// The trigger: a pair colliding again and again forms a cluster at t.
	if (type == POOL_EVENT_BALL_BALL) {
		const int a = note_collision(link, inv[0], inv[1], t);
		const int b = note_collision(link, inv[1], inv[0], t);
		return a || b ? link_begin(link, inv, 2, t) : POOL_OK;
	}
	if (type == POOL_EVENT_BALL_CUSHION && note_collision(link, inv[0], -2 - (int)rail, t))
		return link_begin(link, inv, 1, t);
	return POOL_OK;
}
