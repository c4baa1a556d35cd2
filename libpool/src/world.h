// The world: storage of a simulation (bodies and their segments, the schedule, the history, the
// LINK solver), shared by the modules that work on it, after Box2D v3's world / solver split:
//   world.c      the public API (pool/sim.h) and the event loop: each event is applied by its
//                kind's handler and recorded, and its bodies start new segments;
//   history.c    the events, their states and each ball's chain of states (pool_sim_state_at);
//   schedule.c   the event heap over bodies and the predictions that fill it;
//   broadphase.c which bodies a prediction looks at (a grid of the paths' reach, many balls);
//   segment.c    the closed-form motion of each state (one polynomial per segment);
//   handlers.c   one small function per event kind, each in the file of its physics
//                (motion.c, ball_ball.c, cushion.c, cloth.c);
//   link.c       LINK, persistent contact: the world calls it around events and for its steps,
//                and it keeps its own state (link.h); each step one LCP (link_step.c, lemke.c);
//   geometry.c   the table: contact lines, pocket mouths, nose normals.
#ifndef POOL_WORLD_H
#define POOL_WORLD_H

#include <stdint.h>

#include "broadphase.h"
#include "event_queue.h"
#include "history.h"
#include "link.h"
#include "pool/sim.h"
#include "segment.h"
#include "table_shape.h"

/// A ball's runtime record: its current segment and its own next event.
typedef struct pool_body {
	pool_segment seg;         ///< current motion segment (start state, start time, path)
	int active;               ///< still on the table (not pocketed, not off it)
	double own_time;          ///< s, next own event (state change, cushion, pocket); absolute
	pool_event_type own_kind; ///< its kind
	pool_rail own_rail;       ///< for a cushion or pocket event
	pool_pocket own_pocket;   ///< for a pocket event; for a cushion event, the pocket of its facing or jaw
	int own_part;             ///< for a cushion event with pockets "jaws": the part of the nose curve
	int partner;              ///< other body of the pending event in the queue slot, or -1
	int changed;              ///< scratch of pool_schedule_after_event: among the changed bodies
} pool_body;

/// What a contact search reads of every other body before anything else (schedule.c), kept
/// apart from pool_body so that a search over every body reads a few cache lines.
typedef struct pool_reach {
	/// m, box in the plane (x_lo, x_hi, y_lo, y_hi) the centre stays in from the segment's start
	/// to its own next event (or max_time), widened by R + POOL_BROADPHASE_MARGIN: two balls whose
	/// boxes do not overlap cannot meet before either's own event
	double box[4];
} pool_reach;

/// Bit of body i in a set of bodies kept as words of 64 bits (pool_sim's in_play and moving).
static inline uint64_t pool_body_bit(int i) { return (uint64_t)1 << (i & 63); }

struct pool_sim {
	pool_sim_def def;
	pool_allocator alloc;
	double dc; // m, horizontal centre distance from a nose line at contact
	pool_table_shape shape; // the table's nose curve for this ball radius (table_shape.h)

	int n, cap_balls;
	pool_ball_state *cur; // segment start states (pool_sim_balls)
	pool_body *body;
	pool_reach *reach;    // by body, as the schedule keeps them
	// The bodies in play (pool_body.active) and those whose segment translates (the segment model's
	// `translating`), body i in bit i % 64 of word i / 64, as the schedule files the reach boxes:
	// a search over every body takes those it must look at a word at a time (schedule.c).
	uint64_t *in_play, *moving;
	pool_event_key *keys;
	int *heap, *hpos, *work;
	pool_event_queue queue;
	pool_broadphase broad;  // which bodies each contact search looks at (broadphase.h)

	pool_link link;         // LINK's own state (link.h)
	pool_history history;   // the shot so far (history.h)
	pool_result failed;     // a link step's solve failed: the shot cannot go on
	pool_error last_error;  // what the last failed run call met (pool_sim_last_error)

	double time;      // s, last processed event
	double processed; // s, events up to here are processed (INFINITY at rest)
	pool_stop_reason stop;
	int predicted; // the queue holds predictions for every body
	int started;   // an event was recorded: balls can no longer be added
	int noop_streak; // contacts found to be grazes (no impulse) in a row at one instant, not recorded
	double noop_time; // s, that instant
};

/// Ball i's state at time t, within its current segment (closed form from the segment start).
void pool_world_state_now(const pool_sim *sim, int i, double t, pool_ball_state *out);

/// Planar mode (airborne off): every ball stays on the cloth, v_z is dropped after each impulse.
static inline int pool_world_planar(const pool_sim *sim) { return !sim->def.airborne; }

#endif
