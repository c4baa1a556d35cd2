// The whole world checked (invariants.h).
#include "invariants.h"

#ifdef POOL_ASSERTS
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "motion.h"
#include "vec3.h"

/// m: a ball's recorded state, evolved to the start of its current segment, is where the segment
/// starts (positions are continuous), to the rounding of positions evaluated from two polynomials.
#define POOL_CHECK_POSITION 1e-9

static char detail[256];

// The heap: every slot at its position, no child's key before its parent's (slots with no event
// in any order among themselves: pool_event_queue_before).
static void check_heap(const pool_sim *sim) {
	const pool_event_queue *q = &sim->queue;
	POOL_ASSERT(q->count == sim->n);
	for (int i = 0; i < q->count; ++i) {
		const bool placed = q->heap[i] >= 0 && q->heap[i] < q->count && q->pos[q->heap[i]] == i;
		const bool ordered = placed && (i == 0 || !pool_event_queue_before(&q->keys[q->heap[i]], &q->keys[q->heap[(i - 1) / 2]]));
		if (!ordered) {
			snprintf(detail, sizeof detail, "heap position %d", i);
			pool_assert_failed(placed ? "parent's key at most its child's" : "slot at its heap position", detail, __FILE__,
			                   __LINE__);
		}
	}
}

// The bodies: each one's slot, partner and own event, and the segment it is in. These checks run
// after every step of the sanitizer build, on up to thousands of balls: the description of a ball
// is formatted only once one of its checks has failed.
#define CHECK_BODY(condition)                                                                    \
	((condition) ? (void)0 : (describe_body(sim, i), pool_assert_failed(#condition, detail, __FILE__, __LINE__)))

static void describe_body(const pool_sim *sim, int i) {
	snprintf(detail, sizeof detail, "ball %d (index %d, %s) at t = %.17g s", (int)sim->cur[i].id, i,
	         pool_motion_name(sim->cur[i].motion), sim->time);
}

static void check_bodies(const pool_sim *sim) {
	for (int i = 0; i < sim->n; ++i) {
		const pool_body *b = &sim->body[i];
		const pool_event_key *k = &sim->keys[i];
		CHECK_BODY(k->slot == i);
		CHECK_BODY(memcmp(&sim->cur[i], &b->seg.start, sizeof sim->cur[i]) == 0);
		CHECK_BODY(b->active == (sim->cur[i].motion != POOL_MOTION_POCKETED && sim->cur[i].motion != POOL_MOTION_OFF_TABLE));
		// What the pair loop reads first mirrors the body (schedule.c).
		CHECK_BODY(((sim->in_play[i >> 6] & pool_body_bit(i)) != 0) == (b->active != 0));
		CHECK_BODY(((sim->moving[i >> 6] & pool_body_bit(i)) != 0) == (b->seg.model->translating != 0));
		CHECK_BODY(b->partner >= -1 && b->partner < sim->n && b->partner != i);
		CHECK_BODY(b->partner < 0 || (b->active && sim->body[b->partner].active));
		CHECK_BODY(!(b->seg.t0 > sim->time) || sim->time == 0.0);
		CHECK_BODY(!isnan(k->time) && (!(k->time < sim->time) || sim->stop != POOL_STOP_NONE));
		// A ball is linked when, and only when, LINK holds it, and its next event is no later than
		// its cluster's step.
		const int c = pool_link_cluster_of(&sim->link, i);
		CHECK_BODY((c >= 0) == (sim->cur[i].motion == POOL_MOTION_LINKED));
		CHECK_BODY(c < 0 || (b->active && b->own_time <= pool_link_next_step(&sim->link, i)));
	}
}

// LINK's clusters: every ball's cluster in use, every cluster in use with balls, its steps sound.
// A cluster in use is looked for among the balls only until its first member turns up, so the
// check costs the number of balls times that of clusters in use at most, not the square of n.
static bool has_member(const pool_link *link, int c) {
	for (int i = 0; i < link->n; ++i)
		if (link->cluster_of[i] == c)
			return true;
	return false;
}

static void check_link(const pool_sim *sim) {
	const pool_link *link = &sim->link;
	POOL_ASSERT(link->n == sim->n);
	for (int i = 0; i < sim->n; ++i) {
		const int c = link->cluster_of[i];
		POOL_ASSERT_MSG(c >= -1 && c < sim->n && (c < 0 || link->clusters[c].active), "a ball's cluster");
	}
	for (int c = 0; c < sim->n; ++c) {
		const pool_cluster *cl = &link->clusters[c];
		if (!cl->active)
			continue; // (a cluster out of use has no balls: every ball's cluster is in use, above)
		const bool ok = (has_member(link, c) || sim->stop != POOL_STOP_NONE) && !isnan(cl->t_next) &&
		                !(cl->t_next < sim->time) && cl->dt >= POOL_LINK_STEP_TIME && cl->dt <= POOL_LINK_STEP_MAX &&
		                (!cl->in_step ||
		                 (cl->t_start <= sim->time && cl->step_dt > 0.0 && cl->t_start + cl->step_dt == cl->t_next));
		if (!ok) {
			int members = 0;
			for (int i = 0; i < sim->n; ++i)
				members += link->cluster_of[i] == c;
			snprintf(detail, sizeof detail, "cluster %d (%d balls, step %.17g s from %.17g s, next %.17g s) at t = %.17g s",
			         c, members, cl->step_dt, cl->t_start, cl->t_next, sim->time);
			pool_assert_failed("cluster in use: members, next step and step sound", detail, __FILE__, __LINE__);
		}
	}
}

// The history: the events in time order, each ball's chain back in time, and each ball's
// current segment starting where its last recorded state has brought it.
static void check_history(pool_sim *sim) {
	pool_history *h = &sim->history;
	POOL_ASSERT(h->n_events <= sim->def.max_events);
	POOL_ASSERT(pool_history_valid(h, sim->n));
	if (h->n_events > 0)
		POOL_ASSERT(h->events[h->n_events - 1].time <= sim->time);
	for (int i = 0; i < sim->n; ++i) {
		const int k = h->last[i];
		const pool_segment *seg = &sim->body[i].seg;
		pool_ball_state s;
		const bool in_order = h->state_time[k] <= seg->t0;
		if (in_order)
			pool_motion_evolve(&sim->def.params, &h->states[k], seg->t0 - h->state_time[k], &s);
		if (!in_order || !(pool_v3_len(pool_v3_sub(s.pos, seg->start.pos)) <= POOL_CHECK_POSITION)) {
			snprintf(detail, sizeof detail, "ball %d's history at t = %.17g s", (int)sim->cur[i].id, sim->time);
			pool_assert_failed(in_order ? "segment starts where the recorded state has brought the ball"
			                            : "recorded state no later than the segment", detail, __FILE__, __LINE__);
		}
	}
}

void pool_world_check(pool_sim *sim) {
	if (!sim->predicted)
		return;
	check_heap(sim);
	check_bodies(sim);
	check_link(sim);
	check_history(sim);
}
#else
typedef int pool_invariants_unused; // (ISO C wants a translation unit to declare something)
#endif
