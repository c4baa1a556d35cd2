// An independent recount of what the rules read from a shot, written from the raw event list and
// docs/games.md "What the rules read" alone (not from games/src): the oracle of the rule tests and
// of the 10,000-shot comparison. Deliberately written another way: one question, one pass.
#ifndef POOL_TEST_RECOUNT_H
#define POOL_TEST_RECOUNT_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "pool/pool.h"

#define RECOUNT_NONE INT32_MIN

/// The after-state of ball `id` in event k, or NULL when the event does not involve it.
static inline const pool_ball_state *recount_state(const pool_sim *sim, const pool_event *ev, int32_t id) {
	const pool_ball_state *after = pool_sim_event_states(sim, ev);
	for (int j = 0; j < ev->ball_count; ++j)
		if (after[j].id == id)
			return &after[j];
	return NULL;
}

/// The id of the ball the strike hit (the shot's first event).
static inline int32_t recount_struck(const pool_sim *sim) {
	int n = 0;
	const pool_event *ev = pool_sim_events(sim, &n);
	return n > 0 && ev[0].type == POOL_EVENT_STRIKE ? pool_sim_event_states(sim, &ev[0])[0].id : RECOUNT_NONE;
}

/// The balls the struck ball touches in event k, in the order docs/games.md gives: a ball_ball
/// event's other ball; in a LINK event holding it, every ball whose centre is within 2R + 1 um.
static inline int recount_touches(const pool_sim *sim, const pool_event *ev, int32_t cue, double radius,
                                  int32_t out[], int capacity) {
	const pool_ball_state *me = recount_state(sim, ev, cue);
	if (!me)
		return 0;
	const pool_ball_state *after = pool_sim_event_states(sim, ev);
	int n = 0;
	if (ev->type == POOL_EVENT_BALL_BALL) {
		out[n++] = after[0].id == cue ? after[1].id : after[0].id;
		return n;
	}
	if (ev->type != POOL_EVENT_LINK_BEGIN && ev->type != POOL_EVENT_LINK_STEP)
		return 0;
	// Nearest first: selection by repeated minimum.
	bool taken[64] = {false};
	for (;;) {
		int best = -1;
		double best_d = 0.0;
		for (int j = 0; j < ev->ball_count && j < 64; ++j) {
			if (after[j].id == cue || taken[j])
				continue;
			const double d = hypot(hypot(after[j].pos.x - me->pos.x, after[j].pos.y - me->pos.y),
			                       after[j].pos.z - me->pos.z);
			if (d <= 2.0 * radius + 1e-6 && (best < 0 || d < best_d))
				best = j, best_d = d;
		}
		if (best < 0 || n == capacity)
			return n;
		taken[best] = true;
		out[n++] = after[best].id;
	}
}

/// The first ball the struck ball touches, and the event where it does (-1: none).
static inline int32_t recount_first_hit(const pool_sim *sim, int *at) {
	int n = 0;
	const pool_event *ev = pool_sim_events(sim, &n);
	const int32_t cue = recount_struck(sim);
	const double radius = pool_sim_event_states(sim, &ev[0])[0].pos.z;
	for (int k = 1; k < n; ++k) {
		int32_t met[16];
		if (recount_touches(sim, &ev[k], cue, radius, met, 16) > 0) {
			if (at)
				*at = k;
			return met[0];
		}
	}
	if (at)
		*at = -1;
	return RECOUNT_NONE;
}

/// ball_cushion events of any ball after the struck ball's first contact.
static inline int recount_rails_after_contact(const pool_sim *sim) {
	int at, n = 0, rails = 0;
	recount_first_hit(sim, &at);
	const pool_event *ev = pool_sim_events(sim, &n);
	if (at < 0)
		return 0;
	for (int k = at + 1; k < n; ++k)
		rails += ev[k].type == POOL_EVENT_BALL_CUSHION;
	return rails;
}

/// The ids with a `type` event (pocket or off_table), in event order; returns how many.
static inline int recount_gone(const pool_sim *sim, pool_event_type type, int32_t *ids, pool_pocket *pockets,
                               int capacity) {
	int n = 0, count = 0;
	const pool_event *ev = pool_sim_events(sim, &n);
	for (int k = 0; k < n && count < capacity; ++k)
		if (ev[k].type == type) {
			if (pockets)
				pockets[count] = ev[k].pocket;
			ids[count++] = pool_sim_event_states(sim, &ev[k])[0].id;
		}
	return count;
}

/// Whether ball id has a ball_cushion event in the shot.
static inline bool recount_railed(const pool_sim *sim, int32_t id) {
	int n = 0;
	const pool_event *ev = pool_sim_events(sim, &n);
	for (int k = 0; k < n; ++k)
		if (ev[k].type == POOL_EVENT_BALL_CUSHION && pool_sim_event_states(sim, &ev[k])[0].id == id)
			return true;
	return false;
}

/// The second ball the struck ball touches (the first other than the first ball), and the
/// struck ball's ball_cushion events before the event where it does (all of them without one).
static inline int32_t recount_second_hit(const pool_sim *sim, int *cushions_before) {
	int n = 0;
	const pool_event *ev = pool_sim_events(sim, &n);
	const int32_t cue = recount_struck(sim);
	const double radius = pool_sim_event_states(sim, &ev[0])[0].pos.z;
	int32_t first = RECOUNT_NONE;
	int cushions = 0;
	for (int k = 1; k < n; ++k) {
		if (ev[k].type == POOL_EVENT_BALL_CUSHION && pool_sim_event_states(sim, &ev[k])[0].id == cue)
			cushions++;
		int32_t met[16];
		const int m = recount_touches(sim, &ev[k], cue, radius, met, 16);
		for (int j = 0; j < m; ++j) {
			if (first == RECOUNT_NONE)
				first = met[j];
			else if (met[j] != first) {
				*cushions_before = cushions;
				return met[j];
			}
		}
	}
	*cushions_before = cushions;
	return RECOUNT_NONE;
}

#endif
