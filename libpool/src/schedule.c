// The schedule (schedule.h). Every body owns one slot of an indexed min-heap holding its next
// predicted event: the earliest of its own events, computed once when its segment starts, and
// its earliest contact with another body. A contact is searched only up to the earlier of the
// two bodies' own next events, since either changes trajectory there and is re-predicted then.
#include "schedule.h"

#include <math.h>
#ifdef POOL_BROADPHASE_VERIFY
#include <stdlib.h>
#include <string.h>
#endif

#include "assert.h"
#include "broadphase.h"
#include "geometry.h"
#include "predict.h"
#include "vec3.h"

// When a linked ball (moving uniformly over its step: its segment has no acceleration) leaves
// play within `window`: crossing a rail's contact line over a pocket mouth below the nose's
// height (the step's LCP holds it off the noses, but there is no nose there: it falls in), or,
// above the noses, the table's edge (thrown off the table); INFINITY when neither. The step's
// LCP keeps it inside the contact lines elsewhere.
static double linked_exit(const pool_sim *sim, const pool_ball_state *s, double window, pool_event_type *kind,
                          pool_rail *rail, pool_pocket *pocket) {
	const pool_table_def *table = &sim->def.table;
	double best = INFINITY;
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_EAST; ++r) {
		const pool_rail rr = (pool_rail)r;
		const int along_x = pool_rail_along_x(rr);
		const double side = pool_rail_side(rr);
		const double q0 = along_x ? s->pos.y : s->pos.x, vq = along_x ? s->vel.y : s->vel.x;
		const double a0 = along_x ? s->pos.x : s->pos.y, va = along_x ? s->vel.x : s->vel.y;
		if (!(side * vq > 0.0))
			continue; // not moving out across this rail
		// The contact line, over a mouth and below the nose: a pocket.
		const double tl = fmax((pool_rail_contact_line(table, sim->dc, rr) - q0) / vq, 0.0);
		const pool_pocket pk = pool_pocket_at(table, rr, a0 + va * tl);
		if (tl < best && tl <= window && pk != POOL_POCKET_NONE && s->pos.z + s->vel.z * tl < table->cushion_height) {
			best = tl;
			*kind = POOL_EVENT_POCKET;
			*rail = rr;
			*pocket = pk;
		}
		// The table's edge, the nose line's plane: off the table.
		const double te = fmax((pool_rail_nose_line(table, rr) - q0) / vq, 0.0);
		if (te < best && te <= window) {
			best = te;
			*kind = POOL_EVENT_OFF_TABLE;
			*rail = rr;
			*pocket = POOL_POCKET_NONE;
		}
	}
	return best;
}

// Starts body i's segment and finds its own next event (pool_schedule_begin_segment).
static void begin_own(pool_sim *sim, int i, const pool_ball_state *s, double t) {
	const pool_params *p = &sim->def.params;
	pool_body *b = &sim->body[i];
	sim->cur[i] = *s;
	// A pocketed or off-table ball is out of play for good: no event of its own, no contact.
	b->active = s->motion != POOL_MOTION_POCKETED && s->motion != POOL_MOTION_OFF_TABLE;
	pool_segment_begin(&b->seg, p, s, t);
	b->own_time = INFINITY;
	b->own_kind = POOL_EVENT_SPIN_STOP;
	b->own_rail = POOL_RAIL_NONE;
	b->own_pocket = POOL_POCKET_NONE;
	b->own_part = -1;
	if (!b->active)
		return;
	const pool_table_shape *shape = &sim->shape;
	pool_event_type kind;
	pool_site site;
	if (s->motion == POOL_MOTION_LINKED) {
		// The cluster's step, or leaving play first: the step's LCP holds a linked ball off the
		// cushions, but not over a hole (pockets "jaws") or past a mouth's contact line and off the
		// table's edge (the thesis model's lines: linked_exit).
		b->own_time = pool_link_next_step(&sim->link, i);
		b->own_kind = POOL_EVENT_LINK_STEP;
		const double window = fmin(b->own_time, sim->def.max_time) - t;
		if (!(window > 0.0))
			return;
		if (shape->table.pockets == POOL_POCKETS_MOUTH_LINES) {
			kind = POOL_EVENT_POCKET;
			site.rail = POOL_RAIL_NONE;
			site.pocket = POOL_POCKET_NONE;
			const double tc = linked_exit(sim, s, window, &kind, &site.rail, &site.pocket);
			if (tc < window) {
				b->own_time = t + tc;
				b->own_kind = kind;
				b->own_rail = site.rail;
				b->own_pocket = site.pocket;
			}
			return;
		}
		// Only the holes: a part of the nose curve the ball touches or will touch within the
		// window is the LCP's (no event), and taken as the earliest it would hide a hole the
		// ball slides into during the step (pool_predict_hole_jaws).
		pool_pocket pocket;
		const double tc = pool_predict_hole_jaws(shape, s, b->seg.acc, window, &pocket);
		if (tc < window) {
			b->own_time = t + tc;
			b->own_kind = POOL_EVENT_POCKET;
			b->own_rail = POOL_RAIL_NONE;
			b->own_pocket = pocket;
		}
		return;
	}
	if (s->motion == POOL_MOTION_AIRBORNE) {
		// In flight: landing, a nose, a pocket or the table's edge; nothing changes by itself.
		const double window = fmax(sim->def.max_time - t, 0.0);
		const double dt = pool_predict_flight_shape(shape, s, b->seg.acc, window, &b->own_kind, &site);
		// Gravity ends every flight (params.g > 0), so nothing within the window means the
		// flight's next event lies after max_time, not that none comes: the shot then stops at
		// max_time (POOL_STOP_MAX_TIME), never "at rest" with a ball in the air.
		b->own_time = isfinite(dt) ? t + dt : pool_schedule_beyond(sim);
		b->own_rail = site.rail;
		b->own_pocket = site.pocket;
		b->own_part = site.part;
		return;
	}
	if (!b->seg.model->on_cloth)
		return;
	double dt = pool_segment_next_change(&b->seg, &kind);
	if (b->seg.model->translating) {
		pool_event_type contact;
		const double tc = pool_predict_cushion_shape(shape, s, b->seg.acc, dt, &contact, &site);
		// A state change at the same instant goes first (its kind orders first).
		if (tc < dt) {
			dt = tc;
			kind = contact;
			b->own_rail = site.rail;
			b->own_pocket = site.pocket;
			b->own_part = site.part;
		}
	}
	b->own_time = t + dt;
	b->own_kind = kind;
}

// Body i's reach (pool_reach): its flags, and its box over its segment up to its own next event
// or max_time. Every contact search of it asks about a window inside that stretch (it ends at the
// earlier of the two bodies' own events and at max_time), so a pair whose boxes are apart is one
// the pair loop's narrow phase would reject: the box test leaves the events the same to the bit.
// The margin covers the touching band and the rounding of the paths, as the broadphase's pieces.
// While the grid is on only the flags are kept: its pieces' boxes already leave out every pair the
// reach boxes would (and finer), and should it turn off mid-shot every box is filed again at once
// (boxes_again).
static void reach_box(pool_sim *sim, int i) {
	const pool_body *b = &sim->body[i];
	const pool_segment *seg = &b->seg;
	const pool_ball_state *s = &seg->start;
	pool_reach *r = &sim->reach[i];
	const uint64_t bit = pool_body_bit(i);
	sim->in_play[i >> 6] = b->active ? sim->in_play[i >> 6] | bit : sim->in_play[i >> 6] & ~bit;
	sim->moving[i >> 6] = seg->model->translating ? sim->moving[i >> 6] | bit : sim->moving[i >> 6] & ~bit;
	if (sim->broad.on)
		return;
	const double widen = sim->def.params.ball_radius + POOL_BROADPHASE_MARGIN;
	// The window's end as the pair loop takes it (max_time were own_time NaN), and the path's.
	const double end = b->own_time < sim->def.max_time ? b->own_time : sim->def.max_time;
	double span = end - seg->t0;
	span = seg->move_end < span ? seg->move_end : span;
	double *box = r->box;
	if (seg->model->translating && !(span < INFINITY)) {
		box[0] = box[2] = -INFINITY; // an endless window (or a NaN): every pair
		box[1] = box[3] = INFINITY;
		return;
	}
	if (!seg->model->translating || !(span > 0.0)) {
		box[0] = box[1] = s->pos.x;
		box[2] = box[3] = s->pos.y;
	} else {
		pool_segment_range_1d(s->pos.x, s->vel.x, seg->acc.x, 0.0, span, &box[0], &box[1]);
		pool_segment_range_1d(s->pos.y, s->vel.y, seg->acc.y, 0.0, span, &box[2], &box[3]);
	}
	box[0] -= widen;
	box[1] += widen;
	box[2] -= widen;
	box[3] += widen;
}

// The grid has just turned off (out of memory, an endless window): every body's reach box, which
// the all-pairs loop now reads and reach_box left alone while the grid was on.
static void boxes_again(pool_sim *sim) {
	for (int j = 0; j < sim->n; ++j)
		reach_box(sim, j);
}

// 1 when two reach boxes are apart (the balls cannot meet: reach_box).
static inline int reach_apart(const double *a, const double *b) {
	return a[0] > b[1] || b[0] > a[1] || a[2] > b[3] || b[2] > a[3];
}

void pool_schedule_begin_segment(pool_sim *sim, int i, const pool_ball_state *s, double t) {
	begin_own(sim, i, s, t);
	// Before the shot's first prediction (balls being added, the strike) no search reads the reach,
	// and the first prediction files every body's (pool_schedule_predict_all).
	if (!sim->predicted)
		return;
	reach_box(sim, i);
	// The broadphase files the segment's reach up to its own next event: no pair search looks
	// further (a window ends at the earlier of the two bodies' own events, and at max_time).
	const pool_body *b = &sim->body[i];
	if (sim->broad.on) {
		pool_broadphase_place(&sim->broad, &sim->alloc, i, &b->seg, b->active, t, fmin(b->own_time, sim->def.max_time));
		if (!sim->broad.on)
			boxes_again(sim);
	}
}

// What a contact search of body i knows before it looks at other bodies (search_of).
typedef struct search {
	pool_sim *sim;
	int i;
	double now;
	pool_vec3 pi, vi, ai;  // body i's path as a polynomial in (t - now)
	double horizon_i;      // its own next event, or max_time
	int cluster_i;         // its LINK cluster (-1: none)
	const double *box_i;   // its reach box
	int boxes;             // leave out bodies whose reach boxes are apart from body i's
	pool_event_key *best;  // the earliest event so far
	int partner;           // the other body of *best (-1: none)
} search;

// Body j, a ball in play (moving when body i is not), against body i: *best becomes their
// contact if it comes first.
static inline void try_pair(search *q, int j) {
	pool_sim *sim = q->sim;
	const int i = q->i;
	if (q->boxes && reach_apart(q->box_i, sim->reach[j].box))
		return;
	const pool_body *bj = &sim->body[j];
	// Contacts inside a cluster are its LCP's (link.c), not events.
	if (q->cluster_i >= 0 && q->cluster_i == pool_link_cluster_of(&sim->link, j))
		return;
	// A contact after the best event so far cannot be the earliest: shrink the window.
	const double now = q->now;
	const double T = pool_earlier(pool_earlier(q->horizon_i, bj->own_time), q->best->time) - now;
	if (!(T >= 0.0))
		return;
	pool_vec3 pj, vj;
	pool_segment_path(&bj->seg, now - bj->seg.t0, &pj, &vj);
	// Same operand order whichever body predicts, so both get the same time.
	pool_vec3 dp = pool_v3_sub(q->pi, pj), dv = pool_v3_sub(q->vi, vj), da = pool_v3_scale(pool_v3_sub(q->ai, bj->seg.acc), 0.5);
	if (j < i) {
		dp = pool_v3_scale(dp, -1.0);
		dv = pool_v3_scale(dv, -1.0);
		da = pool_v3_scale(da, -1.0);
	}
	const double R = sim->def.params.ball_radius;
	if (pool_predict_pair_out_of_reach(dp, dv, da, R, T))
		return;
	const double tau = pool_predict_ball_ball_in_reach(dp, dv, da, R, T);
	if (!(tau <= T))
		return;
	const int32_t a = sim->cur[i].id, b = sim->cur[j].id;
	const pool_event_key k = {now + tau, POOL_EVENT_BALL_BALL, a < b ? a : b, a < b ? b : a, i};
	if (pool_event_key_cmp(&k, q->best) < 0) {
		*q->best = k;
		q->partner = j;
		POOL_ASSERT(bj->active && j != i); // a partner is a ball in play, another one
	}
}

// A contact search of body i at `now` whose earliest event so far is *best (search).
static inline search search_of(pool_sim *sim, int i, double now, int boxes, pool_event_key *best) {
	const pool_body *bi = &sim->body[i];
	search q = {.sim = sim, .i = i, .now = now, .boxes = boxes, .best = best, .partner = -1};
	// Both paths as polynomials in (t - now), from the segments' own polynomial.
	pool_segment_path(&bi->seg, now - bi->seg.t0, &q.pi, &q.vi);
	q.ai = bi->seg.acc;
	q.horizon_i = pool_earlier(sim->def.max_time, bi->own_time); // as fmin, were own_time NaN
	q.cluster_i = pool_link_cluster_of(&sim->link, i);
	q.box_i = sim->reach[i].box;
	return q;
}

// Body i's earliest contact at `now` with another body, if it comes before *best (its own
// event): *best becomes it, and the other body is returned (-1: none). Every body in play
// (moving ones when body i does not move), taken a word of the bit sets at a time, in index
// order; boxes: bodies whose reach boxes are apart left out at once (they cannot come within
// reach over the window: reach_box), the same pairs otherwise in the same order.
static int contact_all_pairs(pool_sim *sim, int i, double now, int boxes, pool_event_key *best) {
	search q = search_of(sim, i, now, boxes, best);
	const int mi = sim->body[i].seg.model->translating;
	const int n = sim->n, words = (n + 63) >> 6;
	for (int w = 0; w < words; ++w) {
		// A body in play other than i; when body i does not move, one that does.
		uint64_t m = sim->in_play[w] & (mi ? ~(uint64_t)0 : sim->moving[w]);
		if (w == words - 1 && (n & 63))
			m &= pool_body_bit(n) - 1; // bits past the last body are stale
		if (w == i >> 6)
			m &= ~pool_body_bit(i);
		for (; m; m &= m - 1)
			try_pair(&q, 64 * w + __builtin_ctzll(m));
	}
	return q.partner;
}

// contact_all_pairs over the broadphase's candidates only, in index order, without the reach
// boxes (the grid's pieces leave out every pair they would, and finer): it leaves out only bodies
// that cannot come within reach over the window (broadphase.h), the same pairs otherwise.
static int contact_grid(pool_sim *sim, int i, double now, pool_event_key *best) {
	search q = search_of(sim, i, now, 0, best);
	const pool_body *bi = &sim->body[i];
	const int mi = bi->seg.model->translating;
	const int found = pool_broadphase_query(&sim->broad, i, &bi->seg, now, q.horizon_i);
	for (int k = 0; k < found; ++k) {
		const int j = sim->broad.found[k];
		if ((sim->in_play[j >> 6] & pool_body_bit(j)) && (mi || (sim->moving[j >> 6] & pool_body_bit(j))))
			try_pair(&q, j);
	}
	return q.partner;
}

// Body i's next event at time `now`, its own event or its earliest contact with another, in
// *best (the partner lists follow its partner); the caller puts it in the queue.
static void predict(pool_sim *sim, int i, double now, pool_event_key *out) {
	POOL_ASSERT(i >= 0 && i < sim->n);
	pool_body *bi = &sim->body[i];
	pool_event_key best = {INFINITY, POOL_EVENT_SPIN_STOP, sim->cur[i].id, sim->cur[i].id, i};
	int partner = -1;
	if (bi->active) {
		best.time = bi->own_time;
		best.kind = (int)bi->own_kind;
		const int grid = sim->broad.on;
#ifdef POOL_BROADPHASE_VERIFY
		// The verification build: the answer of the grid and the boxes must be that of every
		// pair without them, to the bit.
		pool_event_key all = best;
		const int all_partner = contact_all_pairs(sim, i, now, 0, &all);
		partner = grid ? contact_grid(sim, i, now, &best) : contact_all_pairs(sim, i, now, 1, &best);
		if (memcmp(&all, &best, sizeof best) != 0 || all_partner != partner)
			abort();
#else
		partner = grid ? contact_grid(sim, i, now, &best) : contact_all_pairs(sim, i, now, 1, &best);
#endif
	}
	if (sim->broad.watching && partner != bi->partner)
		pool_broadphase_repartner(&sim->broad, i, bi->partner, partner);
	bi->partner = partner;
	*out = best;
}

// Recomputes body i's slot at time `now`.
static void repredict(pool_sim *sim, int i, double now) {
	pool_event_key best;
	predict(sim, i, now, &best);
	pool_event_queue_update(&sim->queue, i, &best);
}

void pool_schedule_predict_all(pool_sim *sim) {
	sim->queue.keys = sim->keys;
	sim->queue.heap = sim->heap;
	sim->queue.pos = sim->hpos;
	const int grid = pool_broadphase_begin(&sim->broad, &sim->alloc, &sim->def.table, sim->def.params.ball_radius, sim->n);
	for (int i = 0; i < sim->n; ++i) {
		sim->body[i].partner = -1;
		reach_box(sim, i); // max_time as this run has it
	}
	if (grid) {
		for (int i = 0; i < sim->n && sim->broad.on; ++i) {
			const pool_body *b = &sim->body[i];
			pool_broadphase_place(&sim->broad, &sim->alloc, i, &b->seg, b->active, b->seg.t0,
			                      fmin(b->own_time, sim->def.max_time));
		}
		if (!sim->broad.on)
			boxes_again(sim);
	}
	// Every slot's key, then the heap built over them at once (linear), rather than each key
	// sifted in: the keys are the same, so is the order events come out in.
	for (int i = 0; i < sim->n; ++i)
		predict(sim, i, sim->time, &sim->keys[i]);
	pool_event_queue_build(&sim->queue, sim->n);
	sim->predicted = 1;
}

void pool_schedule_set_broadphase(pool_sim *sim, pool_broadphase_mode mode) {
	pool_broadphase_set_mode(&sim->broad, mode);
	sim->predicted = 0; // the next run predicts every body again, with this search
}

void pool_schedule_refresh(pool_sim *sim, const int *inv, int m, double now) {
	for (int k = 0; k < m; ++k) {
		const int i = inv[k];
		const pool_ball_state s = sim->cur[i];
		pool_schedule_begin_segment(sim, i, &s, sim->body[i].seg.t0);
	}
	pool_schedule_after_event(sim, inv, m, now);
}

// Adds body x to the sorted list sim->work[0..*count) unless it is there (marked changed).
static void enlist(pool_sim *sim, int x, int *count) {
	if (sim->body[x].changed)
		return;
	sim->body[x].changed = 1;
	int at = (*count)++; // insertion: a handful of bodies
	for (; at > 0 && sim->work[at - 1] > x; --at)
		sim->work[at] = sim->work[at - 1];
	sim->work[at] = x;
}

// The bodies to predict again after an event of inv[0..m), from the partner lists: those bodies
// and the ones whose pending contact is with one of them, in index order; their count.
static int watchers(pool_sim *sim, const int *inv, int m) {
	int count = 0;
	for (int k = 0; k < m; ++k) {
		enlist(sim, inv[k], &count);
		for (int x = pool_broadphase_watcher(&sim->broad, inv[k]); x >= 0; x = pool_broadphase_next_watcher(&sim->broad, x))
			enlist(sim, x, &count);
	}
	for (int k = 0; k < count; ++k)
		sim->body[sim->work[k]].changed = 0;
	return count;
}

void pool_schedule_after_event(pool_sim *sim, const int *inv, int m, double now) {
	// The changed bodies and those whose pending contact was with one of them, in index order.
	int count = 0;
	if (sim->broad.watching) {
		count = watchers(sim, inv, m);
	} else {
		for (int k = 0; k < m; ++k)
			sim->body[inv[k]].changed = 1;
		for (int x = 0; x < sim->n; ++x) {
			const int partner = sim->body[x].partner;
			if (sim->body[x].changed || (partner >= 0 && sim->body[partner].changed))
				sim->work[count++] = x;
		}
		for (int k = 0; k < m; ++k)
			sim->body[inv[k]].changed = 0;
	}
	for (int k = 0; k < count; ++k)
		repredict(sim, sim->work[k], now);
}
