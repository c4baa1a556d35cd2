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

/// Earliest tau in [0, T] at which two balls of radius R come into contact while approaching,
/// with relative motion p(tau) = dp + dv tau + da tau^2 (da = half the difference of the
/// accelerations); INFINITY when none. Touching balls (gap <= POOL_TOUCH_TOLERANCE) follow the
/// rules of contact.h: 0 when they collide now, else their next meeting.
double pool_predict_ball_ball(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T);

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

#endif
