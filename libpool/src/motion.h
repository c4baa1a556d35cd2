// Closed-form ball motion on the cloth between events (docs/physics.md, "Motion between events").
#ifndef POOL_MOTION_H
#define POOL_MOTION_H

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/table.h"

/// Slip speed (m/s) at or below which a ball counts as rolling, not sliding. Rounding of a
/// rolling ball's velocities is ~1e-16 m/s; 1e-9 m/s is far below anything measurable.
#define POOL_SLIP_EPS 1e-9
/// Speed (m/s) and spin (rad/s) at or below which a component counts as zero when a state is
/// derived (a ball with less would stop within a nanosecond anyway).
#define POOL_REST_EPS 1e-12

/// Classifies an on-cloth state from its velocities and cleans it: sliding if the slip exceeds
/// POOL_SLIP_EPS, else rolling, spinning or stationary; tiny components of a ball at rest are
/// zeroed. Pocketed / off-table / airborne states are left alone.
void pool_motion_derive(const pool_params *p, pool_ball_state *s);

/// Acceleration of the centre in the given state (constant over the segment): its segment model.
pool_vec3 pool_motion_accel(const pool_params *p, const pool_ball_state *s);

/// State dt >= 0 after the segment start s0, in closed form (never incremental); components
/// are clamped at their own end times so any dt is safe.
void pool_motion_evolve(const pool_params *p, const pool_ball_state *s0, double dt,
                        pool_ball_state *out);

/// Duration from s until its next state change (slide_roll, roll_stop or spin_stop, whichever
/// comes first, ties in that order); INFINITY and no kind when none.
double pool_motion_next_change(const pool_params *p, const pool_ball_state *s,
                               pool_event_type *kind);

/// Applies a state change to a state already evolved to the change's time: snaps it exactly
/// onto the new motion (rolling exactly at slide_roll, v = 0 at roll_stop, wz = 0 at spin_stop).
void pool_motion_apply_change(const pool_params *p, pool_ball_state *s, pool_event_type kind);

/// Kinetic energy (translational + rotational), J, of a ball of mass m and radius R.
double pool_motion_energy(const pool_params *p, const pool_ball_state *s);

#endif
