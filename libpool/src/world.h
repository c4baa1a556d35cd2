// The world: storage of a simulation (bodies, their segments, the schedule, the shot's history),
// shared by the modules that work on it, after Box2D v3's world / solver split:
//   world.c      storage, history and the public API (pool/sim.h);
//   schedule.c   the event heap over bodies and the predictions that fill it;
//   segment.c    the closed-form motion of each state (one polynomial per segment);
//   handlers.c   one small function per event kind, each in the file of its physics
//                (motion.c, ball_ball.c, cushion.c, cloth.c);
//   link.c       LINK clusters: the trigger, forming, stepping and dissolving a cluster, whose
//                balls are one body of the schedule (one step event, uniform motion over the
//                step), each step one LCP (link_step.c, lemke.c);
//   geometry.c   the table: contact lines, pocket mouths, nose normals.
#ifndef POOL_WORLD_H
#define POOL_WORLD_H

#include "event_queue.h"
#include "link_step.h"
#include "pool/link.h"
#include "pool/sim.h"
#include "segment.h"
#include "table_shape.h"

/// Partners a ball remembers for the LINK trigger: a collision streak per recent partner.
#define POOL_LINK_PARTNERS 4

/// Collisions of a ball with one partner (a ball index, or -2 - rail for a cushion) since t0.
typedef struct pool_contact_streak {
	int partner;   ///< -1: unused
	int count;     ///< at distinct instants since t0
	int same;      ///< at the instant t_last
	double t0;     ///< s, the first collision counted
	double t_last; ///< s, the last one
} pool_contact_streak;

/// A ball's runtime record: its current segment, its own next event and its place in history.
typedef struct pool_body {
	pool_segment seg;         ///< current motion segment (start state, start time, path)
	int hist;                 ///< index of the segment's start state in the history
	int active;               ///< still on the table
	double own_time;          ///< s, next own event (state change, cushion, pocket); absolute
	pool_event_type own_kind; ///< its kind
	pool_rail own_rail;       ///< for a cushion or pocket event
	pool_pocket own_pocket;   ///< for a pocket event; for a cushion event, the pocket of its facing or jaw
	int own_part;             ///< for a cushion event with pockets "jaws": the part of the nose curve
	int partner;              ///< other body of the pending event in the queue slot, or -1
	int cluster;              ///< LINK cluster the ball belongs to, or -1
	int changed;              ///< scratch of pool_schedule_after_event: among the changed bodies
	int loose;                ///< the cluster's last step found nothing pressing it: it leaves
	                          ///< the cluster at the next step
	double tail[6];           ///< linked: velocity (v, w) at the step's end less the segment's mean
	                          ///< (link_step.h ball_tail); zero after an interruption
	pool_contact_streak streak[POOL_LINK_PARTNERS]; ///< recent collisions, for the LINK trigger
} pool_body;

/// A LINK cluster: its balls are the bodies whose `cluster` is its index; they share one step
/// event, at t_next.
typedef struct pool_cluster {
	int active;    ///< in use
	double t_next; ///< s, the cluster's next step (INFINITY while it sleeps)
	double dt;     ///< s, the length of its current step (POOL_LINK_STEP_TIME ... POOL_LINK_STEP_MAX)
	int steps;     ///< steps taken
	int quiet;     ///< the last step found every ball loose (pool_body.loose): the cluster
	               ///< dissolves at its next step instead of solving again
} pool_cluster;

struct pool_sim {
	pool_sim_def def;
	pool_allocator alloc;
	double dc; // m, horizontal centre distance from a nose line at contact
	pool_table_shape shape; // the table's nose curve for this ball radius (table_shape.h)

	int n, cap_balls;
	pool_ball_state *cur; // segment start states (pool_sim_balls)
	pool_body *body;
	pool_event_key *keys;
	int *heap, *hpos, *work;
	pool_event_queue queue;

	pool_cluster *clusters;         // cap_balls of them: at most one per ball
	pool_ball_state *link_states;   // scratch of a link step, cap_balls
	int *link_members;              // scratch of a link step, cap_balls
	pool_ball_state *link_leaving;  // scratch of a link step: the states leaving balls would get
	pool_vec3 *link_accel;          // scratch of a link step: each ball's acceleration over it
	pool_link_workspace link_ws;    // the steps' LCP memory, reused
	pool_link_stats link_stats;     // this shot's
	pool_result failed;             // a link step's solve failed: the shot cannot go on

	pool_event *events;
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

/// Ball i's state at time t, within its current segment (closed form from the segment start).
void pool_world_state_now(const pool_sim *sim, int i, double t, pool_ball_state *out);

/// Makes room for `events` more events with `states` more states in the history.
pool_result pool_world_reserve_history(pool_sim *sim, int events, int states);

/// Records an event at t of the balls inv[0..m) with their current segment-start states.
void pool_world_record_event(pool_sim *sim, double t, pool_event_type type, pool_rail rail, pool_pocket pocket,
                             const int *inv, int m);

/// Planar mode (airborne off): every ball stays on the cloth, v_z is dropped after each impulse.
static inline int pool_world_planar(const pool_sim *sim) { return !sim->def.airborne; }

#endif
