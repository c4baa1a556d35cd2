// Event prediction: ball-ball contact (quartic), cushion and pocket contact (quadratics); the
// pocket mouths and contact lines are in geometry.h.
#ifndef POOL_PREDICT_H
#define POOL_PREDICT_H

#include <math.h>

#include "contact.h"
#include "pool/ball.h"
#include "pool/sim.h"
#include "pool/event.h"
#include "pool/table.h"
#include "table_shape.h"

/// Earliest tau in [0, T] at which two balls of radius R come into contact while approaching,
/// with relative motion p(tau) = dp + dv tau + da tau^2 (da = half the difference of the
/// accelerations); INFINITY when none. Touching balls (gap <= POOL_TOUCH_TOLERANCE) follow the
/// rules of contact.h: 0 when they collide now, else their next meeting.
double pool_predict_ball_ball(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T);

/// pool_predict_ball_ball for a pair that pool_predict_pair_out_of_reach, with the same operands,
/// found within reach (the schedule's pair loop): the same answer without that test again.
double pool_predict_ball_ball_in_reach(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T);

/// 1 when two balls of radius R with relative motion dp + dv tau + da tau^2 are apart beyond
/// the touching band and cannot meet over [0, T] (T finite): the path moves at most
/// (|dv| + |da| T) T from dp, each |.| bounded by the 1-norm (no square root). The cheap test
/// pool_predict_ball_ball starts with, inline for the schedule's loop over pairs, where most
/// pairs end here.
static inline int pool_predict_pair_out_of_reach(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T) {
	if (!(T >= 0.0 && T < INFINITY))
		return 0;
	const double reach = (fabs(dv.x) + fabs(dv.y) + fabs(dv.z) + (fabs(da.x) + fabs(da.y) + fabs(da.z)) * T) * T;
	const double clear = 2.0 * R + POOL_TOUCH_TOLERANCE + reach;
	return dp.x * dp.x + dp.y * dp.y + dp.z * dp.z > clear * clear;
}

/// How far a coordinate x0 + v tau + a tau^2 / 2 moves over [0, T] at most, (|v| + |a| T / 2) T,
/// with a margin for that bound's rounding: a line farther away is out of reach. It never falls
/// as T grows, so a line out of reach over a window is out of reach over any shorter one.
static inline double pool_line_reach(double v, double a, double T) {
	return (fabs(v) + 0.5 * fabs(a) * T) * T * (1.0 + 1e-12);
}

/// Earliest tau in [0, T] at which a ball on the cloth (state s, centre acceleration acc)
/// touches a cushion nose; *rail receives the rail, and *pocket the pocket when the contact
/// falls inside a pocket mouth (else POOL_POCKET_NONE). INFINITY when none.
double pool_predict_cushion(const pool_table_def *table, double R, const pool_ball_state *s,
                            pool_vec3 acc, double T, pool_rail *rail, pool_pocket *pocket);

/// Earliest tau in [0, T] of an airborne ball's own next event (state s, acceleration acc):
/// landing (ball_table), a cushion nose met in flight (ball_cushion: distance to the nose line
/// in the rail's normal plane equal to R, a quartic), a pocket (crossing a contact line inside a
/// mouth below the nose height, or landing beyond a contact line inside a mouth) or leaving the
/// table (off_table: crossing the table's edge without touching the nose, or landing beyond a
/// contact line outside the mouths, on the rail top, which is not modelled). *kind, *rail and
/// *pocket describe it; INFINITY when none within T.
double pool_predict_flight(const pool_table_def *table, double R, const pool_ball_state *s, pool_vec3 acc, double T,
                           pool_event_type *kind, pool_rail *rail, pool_pocket *pocket);

/// Where a cushion, pocket or off-table event happens: the rail, the pocket (of a pocket event,
/// or of the facing or jaw hit) and the part of the nose curve (an index into the shape's parts,
/// -1 for the thesis model's lines and for pocket and off-table events).
typedef struct pool_site {
	pool_rail rail;
	pool_pocket pocket;
	int part;
} pool_site;

/// A ball on the cloth against the table's cushions and pockets, whatever its pocket model:
/// earliest tau in [0, T], *kind POOL_EVENT_BALL_CUSHION or POOL_EVENT_POCKET, *site where.
double pool_predict_cushion_shape(const pool_table_shape *shape, const pool_ball_state *s, pool_vec3 acc, double T,
                                  pool_event_type *kind, pool_site *site);

/// An airborne ball's own next event, whatever the pocket model (pool_predict_flight's kinds).
double pool_predict_flight_shape(const pool_table_shape *shape, const pool_ball_state *s, pool_vec3 acc, double T,
                                 pool_event_type *kind, pool_site *site);

/// Pockets "jaws" on the cloth (predict_jaws.c): a crossing of a rail's contact line within a
/// nose segment's span, a pocket's facing at dc or jaw at its radius + dc, its hole's edge.
double pool_predict_cushion_jaws(const pool_table_shape *shape, const pool_ball_state *s, pool_vec3 acc, double T,
                                 pool_event_type *kind, pool_site *site);

/// Pockets "jaws", a linked ball on the cloth: earliest tau in [0, T] at which its centre enters
/// a hole (*pocket which; INFINITY, POOL_POCKET_NONE: none), the nose curve's parts ignored.
double pool_predict_hole_jaws(const pool_table_shape *shape, const pool_ball_state *s, pool_vec3 acc, double T,
                              pool_pocket *pocket);

/// Pockets "jaws" in flight: landing (a pocket when over a hole), a part of the nose curve at
/// distance R (a jaw: degree 8), crossing the nose curve over the cushion (off_table), entering a
/// hole below the nose height (pocket).
double pool_predict_flight_jaws(const pool_table_shape *shape, const pool_ball_state *s, pool_vec3 acc, double T,
                                pool_event_type *kind, pool_site *site);

#endif
