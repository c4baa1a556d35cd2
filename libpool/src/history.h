// The shot's history: the events in order, the states they leave each ball in, and for each ball
// the chain of its states back in time, from which the state of every ball at any processed
// instant is evaluated in closed form (pool_sim_state_at). The world records into it; nothing in
// it knows how an event was computed.
#ifndef POOL_HISTORY_H
#define POOL_HISTORY_H

#include "pool/sim.h"

/// Events and states of one shot, in the def's allocator's memory (kept by pool_sim_reset).
typedef struct pool_history {
	pool_event *events;       ///< in processing order
	int n_events, cap_events;
	pool_ball_state *states;  ///< the balls' initial states, then every event's after-states
	double *state_time;       ///< s, the instant each state begins
	int *state_prev;          ///< the same ball's previous state, or -1
	int n_states, cap_states;
	int *last;                ///< each ball's latest state (by ball index), or -1
	int cap_balls;
	int checked_events, checked_states; ///< those pool_history_valid has checked already
} pool_history;

/// Forgets the shot, keeping the memory.
void pool_history_clear(pool_history *h);

/// Frees the memory (with the allocator that made it).
void pool_history_free(pool_history *h, const pool_allocator *a);

/// Room for `balls` balls (`used` of them placed); POOL_ERR_OUT_OF_MEMORY leaves h as it was.
pool_result pool_history_reserve_balls(pool_history *h, const pool_allocator *a, int balls, int used);

/// pool_history_reserve when the arrays must grow.
pool_result pool_history_grow(pool_history *h, const pool_allocator *a, int events, int states);

/// Room for `events` more events with `states` more states; POOL_ERR_OUT_OF_MEMORY leaves h as
/// it was. Inline: asked at every step and every ball added, the room is nearly always there.
static inline pool_result pool_history_reserve(pool_history *h, const pool_allocator *a, int events, int states) {
	if (h->n_events + events <= h->cap_events && h->n_states + states <= h->cap_states)
		return POOL_OK;
	return pool_history_grow(h, a, events, states);
}

/// Ball i's first state, at its placement at time t (room reserved).
void pool_history_place(pool_history *h, int i, const pool_ball_state *s, double t);

/// Records an event at t of the balls balls[0..m), whose after-states are cur[balls[k]], where
/// (rail, pocket, part) says (pool_event), growing the history when the room reserved falls
/// short; POOL_ERR_OUT_OF_MEMORY records nothing.
pool_result pool_history_record(pool_history *h, const pool_allocator *a, double t, pool_event_type type, pool_rail rail,
                                pool_pocket pocket, pool_cushion_part part, const int *balls, int m,
                                const pool_ball_state *cur);

/// The state of each of the n balls at t, from its latest state begun at or before t (its
/// first state when t precedes them all), evolved in closed form.
void pool_history_state_at(const pool_history *h, const pool_params *p, int n, double t, pool_ball_state *out);

/// 1 when every event since the last call is no earlier than the one before and its states lie
/// in the history, and every state recorded since follows its ball's previous one in time; so
/// every ball's chain runs back in time order (n balls). Checks each entry once.
int pool_history_valid(pool_history *h, int n);

#endif
