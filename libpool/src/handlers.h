// Event handlers: one small function per event kind, each in the file of its physics (world.h
// lists them). A handler turns the involved balls' states at the event instant into their
// after-states; the world records them and the schedule re-predicts.
#ifndef POOL_HANDLERS_H
#define POOL_HANDLERS_H

#include "pool/sim.h"
#include "table_shape.h"

/// What a handler knows of the event besides the states.
typedef struct pool_event_context {
	const pool_sim_def *def; ///< table, parameters, planar or airborne
	pool_rail rail;          ///< the rail of a cushion event
	pool_pocket pocket;      ///< the pocket of a pocket event (of the facing or jaw of a cushion event)
	const pool_table_shape *shape; ///< the table's nose curve
	int part;                ///< the part of the nose curve a cushion event touches (-1: the rail's nose line)
} pool_event_context;

/// Applies event `type` to the states s[0..count) of its balls, evolved to its instant (for two
/// balls, s[0] has the smaller id). Returns 0 (the slot is kept for event flags; none is defined).
typedef int (*pool_event_handler)(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s,
                                  int count);

/// The handler of an event kind handled by the schedule (not the strike, which is an API call),
/// or NULL.
pool_event_handler pool_event_handler_for(pool_event_type type);

/// slide_roll, roll_stop, spin_stop (motion.c).
int pool_handle_state_change(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count);
/// Two balls (ball_ball.c).
int pool_handle_ball_ball(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count);
/// A ball and a cushion nose (cushion.c).
int pool_handle_ball_cushion(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count);
/// A ball into a pocket (cushion.c: a cushion contact inside a mouth).
int pool_handle_pocket(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count);

/// A ball on the cloth (airborne mode) settles instead of bouncing when its rebound would fly
/// for less than this (s): a rebound at v_z flies 2 v_z / g, so the bounces of a dropped ball
/// (flight times shrinking by e_table each) end after log(T_first / this) / log(1 / e_table)
/// events, never a Zeno series; settling drops at most m (g this / 2)^2 / 2 = 2e-6 J (defaults).
#define POOL_SETTLE_FLIGHT_TIME 1e-3

/// A landing (ball_table): Petit's law with the cloth (n = k, e_table, mu_table), then settle or
/// fly (cloth.c).
int pool_handle_ball_table(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count);
/// A ball clears a rail and leaves the table (cloth.c): final, like a pocket.
int pool_handle_off_table(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count);

/// A ball leaves play (pocketed, off the table): at rest where it left, final.
static inline void pool_take_out_of_play(pool_ball_state *s, pool_motion motion) {
	const pool_vec3 zero = {0.0, 0.0, 0.0};
	s->vel = zero;
	s->omega = zero;
	s->motion = motion;
}

/// The motion state after an impulse or at placement (motion.c). Planar mode drops v_z and
/// derives the on-cloth state (docs/physics.md "Collisions"); airborne mode makes the ball airborne
/// when it is above the cloth or moves vertically faster than POOL_APPROACH_EPS (into the cloth:
/// the ball_table contact follows at once, by the contact rule), else puts it on the cloth.
void pool_motion_after_impulse(const pool_sim_def *def, pool_ball_state *s);

#endif
