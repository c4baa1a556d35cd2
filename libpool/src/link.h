// LINK clusters in the world (docs/physics.md "LINK"). Where pairwise impulses break down (a ball
// pushing another, resting on two, pinned to a rail), the pair's collision history triggers a
// cluster: the linker and every ball touching and closing on it, transitively; a ball that hits
// a cluster's ball joins it. The cluster is one body of the schedule: its balls share one step
// event and, over a step, move uniformly with the step's mean velocities (link_step.h), so the
// exact state at any instant stays known and the balls outside keep predicting contacts against
// them. A step ends early when an event from outside reaches one of its balls (the cluster
// steps again at that instant); steps grow from 1 to 16 ms while the contacts barely act. A ball
// that nothing presses leaves the cluster and resumes its closed-form state; the cluster
// dissolves when all of them have.
#ifndef POOL_LINK_INTERNAL_H
#define POOL_LINK_INTERNAL_H

#include "world.h"

/// Notes a recorded collision of ball i with `partner` (a ball index, or -2 - rail) at t and
/// returns 1 when it completes the trigger (POOL_LINK_TRIGGER_COLLISIONS within the window).
int pool_link_note_collision(pool_sim *sim, int i, int partner, double t);

/// Forms a cluster at t around the balls seed[0..m) (merging every cluster they touch) and
/// records link_begin; its first step is at t.
pool_result pool_link_begin(pool_sim *sim, const int *seed, int m, double t);

/// Processes the step event of ball i's cluster at t: one LCP step of the whole cluster, then
/// link_step (or link_end when it dissolves).
pool_result pool_link_step_event(pool_sim *sim, int i, double t);

/// After an event from outside changed member i's state at t (already its new segment start):
/// keeps it linked and makes its cluster step at t, so no event inside a step is skipped.
void pool_link_touched(pool_sim *sim, int i, double t);

/// Ball i (in play, in no cluster) joins cluster c at t, its state then a linked segment's start.
void pool_link_adopt(pool_sim *sim, int i, int c, double t);

/// 1 when two touching balls s[0..2) (closed-form states at the contact) are pressed together:
/// their normal approach acceleration, the difference of their accelerations along the normal
/// less the curvature of their relative path (|v_t|^2 / 2R parts them), is positive.
int pool_link_pressed_pair(const pool_sim *sim, const pool_ball_state *s);

/// Member i left play (pocketed, off the table) at t: it leaves its cluster, which steps at t.
void pool_link_left(pool_sim *sim, int i, double t);

#endif
