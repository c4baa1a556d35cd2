// LINK, persistent contact (docs/physics.md "LINK", docs/library.md "Persistent contact"), as a
// solver with one owner: this module keeps every piece of its state (the clusters, each ball's
// cluster, the collision streaks of the trigger, the steps' tails, the LCP workspace, the
// statistics) and the world calls it in four places:
//   pool_link_cut          before an event from outside acts on balls it holds: their clusters'
//                          steps end there, at the length they actually lasted;
//   pool_link_take_pressed a contact the impulses cannot hold (pressed, no impulse): a cluster forms;
//   pool_link_after_event  after an event was applied and recorded: the trigger, adopting a hitter,
//                          a cluster touched or left by the event;
//   pool_link_step_event   the schedule's step event of a cluster: one LCP step (link_step.c).
// It asks the world for nothing but what pool_link_world offers (a ball's state at t, starting a
// segment, recording an event, re-predicting), so it includes no world internals, and the world
// finds no cluster logic of its own: calls go one way, as Box2D v3's world calls its solver and
// the solver keeps its state.
//
// A cluster is one body of the schedule: its balls share one step event and, over a step, move
// uniformly with the step's mean velocities (link_step.h), so the exact state at any instant stays
// known and the balls outside keep predicting contacts against them. A step ends early when an
// event from outside reaches one of its balls (the cluster steps again at that instant); steps
// grow from 1 to 16 ms while the contacts barely act. A ball that nothing presses leaves the
// cluster and resumes its closed-form state; the cluster dissolves when all of them have.
#ifndef POOL_LINK_INTERNAL_H
#define POOL_LINK_INTERNAL_H

#include "link_step.h"
#include "pool/link.h"
#include "pool/sim.h"

/// What LINK may ask of the world it serves; ctx is passed back to every call.
typedef struct pool_link_world {
	void *ctx;
	/// Ball i's state at t (closed form from its current segment; pocketed and off-table balls too).
	void (*state_at)(void *ctx, int i, double t, pool_ball_state *out);
	/// Ball i's motion starts over at t in state s (its own next event predicted from there).
	void (*begin_segment)(void *ctx, int i, const pool_ball_state *s, double t);
	/// Balls balls[0..m) keep their segments, but their own next events (a cluster's step)
	/// moved: predicted again, with the contacts of everything they changed.
	void (*refresh)(void *ctx, const int *balls, int m, double t);
	/// Balls balls[0..m) started new segments at t: their contacts are predicted again.
	void (*changed)(void *ctx, const int *balls, int m, double t);
	/// Records an event at t of balls[0..m) in their current segment-start states.
	pool_result (*record)(void *ctx, double t, pool_event_type type, pool_pocket pocket, const int *balls, int m);
	/// Room for `events` more events with `states` more states (POOL_ERR_OUT_OF_MEMORY: none).
	pool_result (*reserve)(void *ctx, int events, int states);
	/// Events that may still be recorded before max_events.
	int (*room)(void *ctx);
} pool_link_world;

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

/// A cluster: its balls are those whose cluster_of is its index; they share one step event.
/// A step is an object: it starts at t_start from the velocities v0 its balls had then, is
/// planned to last step_dt (its end, t_next), and lasts what it actually lasts: an event from
/// outside can end it earlier, and whatever it changed (the gravity kick, the contact impulses,
/// the cloth wrenches) then follows from the time it lasted (pool_link_cut).
typedef struct pool_cluster {
	int active;     ///< in use
	double t_next;  ///< s, the cluster's next step (INFINITY while it sleeps)
	double dt;      ///< s, the length of its next step (POOL_LINK_STEP_TIME ... POOL_LINK_STEP_MAX)
	int in_step;    ///< a step is in progress (solved at t_start, to end at t_next)
	double t_start; ///< s, the step's start
	double step_dt; ///< s, its planned length
	int steps;      ///< steps taken
	int quiet;      ///< the last step found every ball loose: the cluster dissolves at its next
	                ///< step instead of solving again
} pool_cluster;

/// LINK's whole state, owned by it (the world holds it and passes it to every call).
typedef struct pool_link {
	const pool_sim_def *def;   ///< the simulation's (table, parameters, planar or airborne)
	double dc;                 ///< m, a ball's centre from a nose line at contact on the cloth
	pool_link_world world;
	const pool_allocator *alloc;
	int n, cap;                ///< balls, and the room of the per-ball arrays
	// Per ball (cap of each):
	int *cluster_of;           ///< the ball's cluster, or -1
	int *loose;                ///< the cluster's last step found nothing pressing it: it leaves
	                           ///< at the next step
	double *tail;              ///< 6 per ball: velocity (v, w) at the step's end less the
	                           ///< segment's mean (link_step.h ball_tail); zero outside a step
	double *v0;                ///< 6 per ball: velocity (v, w) at the step's start
	pool_contact_streak *streak; ///< POOL_LINK_PARTNERS per ball: recent collisions, for the trigger
	pool_cluster *clusters;    ///< at most one per ball
	// Scratch of a step (cap of each):
	pool_ball_state *states;
	pool_ball_state *now;      ///< every ball's state at a gathering's instant
	int *members;
	int *mark;                 ///< a gathering's balls
	int *group;
	pool_ball_state *leaving;  ///< the states loose balls would leave with
	pool_vec3 *accel;          ///< each ball's acceleration over the step
	pool_link_workspace ws;    ///< the steps' LCP memory, reused
	pool_link_stats stats;     ///< this shot's
	pool_link_step_stats failed_step; ///< the last failed solve (pool_link_failure)
	int failed_size;           ///< its cluster's balls
	int starved;               ///< an event LINK needed found no room under max_events: it did
	                           ///< nothing, and the shot stops (POOL_STOP_MAX_EVENTS)
} pool_link;

/// Binds LINK to its simulation's def and table shape (kept by address: the world's; the
/// shape's parts are the steps' cushion contacts with pockets "jaws"), allocator and world.
void pool_link_init(pool_link *link, const pool_sim_def *def, const struct pool_table_shape *shape, double dc,
                    const pool_allocator *alloc, const pool_link_world *world);

/// A new shot: no ball, no cluster, no warm start (the same input gives the same bits).
void pool_link_clear(pool_link *link);

/// Frees LINK's memory.
void pool_link_free(pool_link *link);

/// Room for `balls` balls; POOL_ERR_OUT_OF_MEMORY leaves LINK as it was.
pool_result pool_link_reserve(pool_link *link, int balls);

/// Ball i (the next index) is placed: in no cluster, no collision remembered.
void pool_link_add_ball(pool_link *link, int i);

/// Ball i's cluster, or -1 (inline: the schedule asks it for every pair it predicts).
static inline int pool_link_cluster_of(const pool_link *link, int i) { return link->cluster_of[i]; }

/// s, the next step of ball i's cluster (i linked).
double pool_link_next_step(const pool_link *link, int i);

/// Before an event from outside acts on the balls inv[0..m) at t: the step in progress of each
/// of their clusters ends at t, its velocities those of the time it lasted (pool_cluster), and
/// a link_step records the cluster's states at the cut; the cluster steps again at t.
pool_result pool_link_cut(pool_link *link, const int *inv, int m, double t);

/// 1 when LINK found no room for an event it needed under max_events (it then did nothing):
/// the shot stops there.
static inline int pool_link_starved(const pool_link *link) { return link->starved; }

/// An event of the balls inv[0..m) (evolved to t, in s[0..m)) found them touching and pressed,
/// and Petit's law gave no impulse: resting contact the impulses cannot hold. Returns 1 when
/// LINK takes it (forms a cluster at t, *result its outcome), 0 when it is not LINK's (the
/// balls are in one cluster already, or a ball pair is not pressed).
int pool_link_take_pressed(pool_link *link, pool_event_type type, const int *inv, const pool_ball_state *s, int m,
                           double t, pool_result *result);

/// Marks the after-states s[0..m) of an event of the balls inv[0..m): a ball LINK holds stays
/// linked (its state's motion is POOL_MOTION_LINKED).
void pool_link_keep_linked(const pool_link *link, const int *inv, pool_ball_state *s, int m);

/// After an event of type `type` (rail: a cushion's) at t changed the balls inv[0..m) (their
/// after-states s[0..m), recorded): a hitter that does not part from a cluster's ball joins it,
/// a cluster touched or left steps at t, and the trigger may form a cluster.
pool_result pool_link_after_event(pool_link *link, pool_event_type type, pool_rail rail, const int *inv,
                                  const pool_ball_state *s, int m, double t);

/// The step event of ball i's cluster at t: one LCP step of the whole cluster, then link_step
/// (or link_end when it dissolves). POOL_ERR_INTERNAL when the LCP cannot be solved
/// (pool_link_failure says how), POOL_ERR_OUT_OF_MEMORY when the workspace cannot grow.
pool_result pool_link_step_event(pool_link *link, int i, double t);

/// What the last failed step was: its solve's residual and contacts, and its cluster's balls.
void pool_link_failure(const pool_link *link, double *residual, int *balls, int *contacts);

#endif
