// The world: storage of a simulation (bodies, their segments, the schedule, the shot's history),
// shared by the modules that work on it, after Box2D v3's world / solver split:
//   world.c      storage, history and the public API (pool/sim.h);
//   schedule.c   the event heap over bodies and the predictions that fill it;
//   segment.c    the closed-form motion of each state (one polynomial per segment);
//   handlers.c   one small function per event kind, each in the file of its physics
//                (motion.c, ball_ball.c, cushion.c; the planar stand-in contact_floor.c);
//   geometry.c   the table: contact lines, pocket mouths, nose normals.
// A body is one ball today; a LINK cluster will be one body of several balls.
#ifndef POOL_WORLD_H
#define POOL_WORLD_H

#include "event_queue.h"
#include "pool/sim.h"
#include "segment.h"

/// A ball's runtime record: its current segment, its own next event and its place in history.
typedef struct pool_body {
	pool_segment seg;         ///< current motion segment (start state, start time, path)
	int hist;                 ///< index of the segment's start state in the history
	int active;               ///< still on the table
	double own_time;          ///< s, next own event (state change, cushion, pocket); absolute
	pool_event_type own_kind; ///< its kind
	pool_rail own_rail;       ///< for a cushion or pocket event
	pool_pocket own_pocket;   ///< for a pocket event
	int partner;              ///< other body of the pending event in the queue slot, or -1
} pool_body;

struct pool_sim {
	pool_sim_def def;
	pool_allocator alloc;
	double dc; // m, horizontal centre distance from a nose line at contact

	int n, cap_balls;
	pool_ball_state *cur; // segment start states (pool_sim_balls)
	pool_body *body;
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
	int predicted; // the queue holds predictions for every body
	int started;   // an event was recorded: balls can no longer be added
	int noop_streak; // contacts found to be grazes (no impulse) in a row, not recorded
};

/// Planar mode (airborne off): every ball stays on the cloth, v_z is dropped after each impulse.
static inline int pool_world_planar(const pool_sim *sim) { return !sim->def.airborne; }

#endif
