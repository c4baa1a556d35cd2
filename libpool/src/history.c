// The shot's history (history.h).
#include "history.h"

#include <string.h>

#include "assert.h"
#include "memory.h"
#include "motion.h"

void pool_history_clear(pool_history *h) {
	h->n_events = 0;
	h->n_states = 0;
	h->checked_events = 0;
	h->checked_states = 0;
}

void pool_history_free(pool_history *h, const pool_allocator *a) {
	pool_mem_free(a, h->events);
	pool_mem_free(a, h->states);
	pool_mem_free(a, h->state_time);
	pool_mem_free(a, h->state_prev);
	pool_mem_free(a, h->last);
	memset(h, 0, sizeof *h);
}

pool_result pool_history_reserve_balls(pool_history *h, const pool_allocator *a, int balls, int used) {
	if (balls <= h->cap_balls)
		return POOL_OK;
	const int cap = pool_mem_next_cap(h->cap_balls, balls);
	void **arrays[] = {(void **)&h->last};
	const size_t elems[] = {sizeof(int)};
	if (pool_mem_grow(a, arrays, elems, 1, used, cap))
		return POOL_ERR_OUT_OF_MEMORY;
	h->cap_balls = cap;
	return POOL_OK;
}

pool_result pool_history_grow(pool_history *h, const pool_allocator *a, int events, int states) {
	if (h->n_events + events > h->cap_events) {
		const int cap = pool_mem_next_cap(h->cap_events, h->n_events + events);
		void **arrays[] = {(void **)&h->events};
		const size_t elems[] = {sizeof(pool_event)};
		if (pool_mem_grow(a, arrays, elems, 1, h->n_events, cap))
			return POOL_ERR_OUT_OF_MEMORY;
		h->cap_events = cap;
	}
	if (h->n_states + states > h->cap_states) {
		const int cap = pool_mem_next_cap(h->cap_states, h->n_states + states);
		void **arrays[] = {(void **)&h->states, (void **)&h->state_time, (void **)&h->state_prev};
		const size_t elems[] = {sizeof(pool_ball_state), sizeof(double), sizeof(int)};
		if (pool_mem_grow(a, arrays, elems, 3, h->n_states, cap))
			return POOL_ERR_OUT_OF_MEMORY;
		h->cap_states = cap;
	}
	return POOL_OK;
}

// Appends ball i's state s from t on (room reserved).
static void push_state(pool_history *h, int i, const pool_ball_state *s, double t) {
	const int k = h->n_states++;
	h->states[k] = *s;
	h->state_time[k] = t;
	h->state_prev[k] = h->last[i];
	h->last[i] = k;
}

void pool_history_place(pool_history *h, int i, const pool_ball_state *s, double t) {
	h->last[i] = -1;
	push_state(h, i, s, t);
}

pool_result pool_history_record(pool_history *h, const pool_allocator *a, double t, pool_event_type type, pool_rail rail,
                                pool_pocket pocket, pool_cushion_part part, const int *balls, int m,
                                const pool_ball_state *cur) {
	// The callers reserve the room first (pool_sim_step for an event and the LINK events it
	// brings); should that count ever fall short, the history grows here, and if it cannot, the
	// caller fails the shot rather than write past the arrays.
	if (pool_history_reserve(h, a, 1, m))
		return POOL_ERR_OUT_OF_MEMORY;
	POOL_ASSERT(h->n_events == 0 || t >= h->events[h->n_events - 1].time); // events in time order
	pool_event *e = &h->events[h->n_events++];
	memset(e, 0, sizeof *e); // padding too: event lists compare bit for bit
	e->time = t;
	e->type = type;
	e->rail = rail;
	e->pocket = pocket;
	e->part = part;
	e->ball_count = m;
	e->first_state = h->n_states;
	for (int k = 0; k < m; ++k)
		push_state(h, balls[k], &cur[balls[k]], t);
	return POOL_OK;
}

void pool_history_state_at(const pool_history *h, const pool_params *p, int n, double t, pool_ball_state *out) {
	for (int i = 0; i < n; ++i) {
		int k = h->last[i];
		while (h->state_time[k] > t && h->state_prev[k] >= 0)
			k = h->state_prev[k];
		pool_motion_evolve(p, &h->states[k], t - h->state_time[k], &out[i]);
	}
}

int pool_history_valid(pool_history *h, int n) {
	for (int e = h->checked_events; e < h->n_events; ++e) {
		const pool_event *ev = &h->events[e];
		if (ev->first_state < 0 || ev->first_state + ev->ball_count > h->n_states)
			return 0;
		if (e > 0 && !(ev->time >= h->events[e - 1].time))
			return 0;
	}
	for (int k = h->checked_states; k < h->n_states; ++k) {
		const int prev = h->state_prev[k];
		if (prev >= k || (prev >= 0 && (h->state_time[prev] > h->state_time[k] || h->states[prev].id != h->states[k].id)))
			return 0;
	}
	for (int i = 0; i < n; ++i)
		if (h->last[i] < 0 || h->last[i] >= h->n_states)
			return 0;
	h->checked_events = h->n_events;
	h->checked_states = h->n_states;
	return 1;
}
