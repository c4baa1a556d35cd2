// The schedule: each body's next event in the heap (docs/physics.md "Event list"). After an event
// only the bodies it involved, and those whose pending event involved them, are re-predicted.
#ifndef POOL_SCHEDULE_H
#define POOL_SCHEDULE_H

#include <math.h>

#include "world.h"

/// Starts body i's new motion segment at time t in state s and predicts its own next event
/// (state change, cushion, pocket), which needs no other body.
void pool_schedule_begin_segment(pool_sim *sim, int i, const pool_ball_state *s, double t);

/// Predicts every body's next event at sim->time and builds the heap.
void pool_schedule_predict_all(pool_sim *sim);

/// After an event of the bodies inv[0..m) at time now: re-predicts them and every body whose
/// pending event involved one of them.
void pool_schedule_after_event(pool_sim *sim, const int *inv, int m, double now);

/// The bodies inv[0..m) keep their segments but their own next events moved (a LINK cluster's
/// step): predicted again, then as pool_schedule_after_event.
void pool_schedule_refresh(pool_sim *sim, const int *inv, int m, double now);

/// s, the first instant after max_time: the time of a body's next event when a prediction cut
/// at max_time found none although one must come (a flight's landing).
static inline double pool_schedule_beyond(const pool_sim *sim) { return nextafter(sim->def.max_time, INFINITY); }

/// Sets the pair search (broadphase.h) from the next run on: every body is predicted again then.
/// For tests and benchmarks; the default, POOL_BROADPHASE_AUTO, chooses by ball count.
void pool_schedule_set_broadphase(pool_sim *sim, pool_broadphase_mode mode);

/// Slot of the earliest pending event (sim->n > 0).
static inline int pool_schedule_next(const pool_sim *sim) { return pool_event_queue_top(&sim->queue); }

#endif
