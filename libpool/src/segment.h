// Motion segments: between two of its events a ball follows one closed-form motion (docs/physics.md
// "Motion between events"). One model per motion state gives the segment's acceleration, its
// own end (the state change it leads to) and its spin; the centre follows one polynomial,
//     r(tau) = r0 + v0 tau + a tau^2 / 2,   v(tau) = v0 + a tau,
// which is used both to predict contacts and to evaluate states, so the two can never round
// differently.
#ifndef POOL_SEGMENT_H
#define POOL_SEGMENT_H

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/table.h"
#include "vec3.h"

/// One motion state's closed forms.
typedef struct pool_segment_model {
	int translating; ///< the centre moves (sliding, rolling, airborne)
	int on_cloth;    ///< cloth friction acts: z-spin decays, the state can change by itself
	/// m/s^2, acceleration of the centre, constant over the segment.
	pool_vec3 (*accel)(const pool_params *p, const pool_ball_state *s);
	/// s, duration of the translation until its own state change (slide_roll, roll_stop), and
	/// its kind; INFINITY when none.
	double (*move_end)(const pool_params *p, const pool_ball_state *s, pool_event_type *kind);
	/// Spin perpendicular to z at tau into the segment, velocity vel then (z-spin aside).
	void (*spin)(const pool_params *p, const pool_ball_state *s0, double tau, pool_vec3 vel, pool_vec3 *omega);
} pool_segment_model;

/// The model of a motion state (stationary, spinning, sliding, rolling, airborne, linked: uniform
/// motion over a link step; a pocketed or off-table ball gets a model where nothing moves).
const pool_segment_model *pool_segment_model_of(pool_motion motion);

/// A segment: its start state and time and what its model makes of them.
typedef struct pool_segment {
	pool_ball_state start;      ///< state at the start
	double t0;                  ///< s, absolute start time
	pool_vec3 acc;              ///< m/s^2, centre acceleration over the segment
	double move_end;            ///< s after t0 of the translation's own change (INFINITY: none)
	pool_event_type move_kind;  ///< slide_roll or roll_stop
	double spin_end;            ///< s after t0 when the z-spin stops (INFINITY: none)
	const pool_segment_model *model;
} pool_segment;

/// Starts a segment in state s at absolute time t0.
void pool_segment_begin(pool_segment *seg, const pool_params *p, const pool_ball_state *s, double t0);

/// The earlier of two times as fmin gives it (a NaN b gives a), without fmin's library call: the
/// schedule's pair loop and every state evaluation take it.
static inline double pool_earlier(double a, double b) { return b < a ? b : a; }

/// Duration until the segment's own next state change (slide_roll, roll_stop or spin_stop,
/// whichever comes first, ties in that order) and its kind; INFINITY and no kind when none.
/// Inline: every segment start asks it.
static inline double pool_segment_next_change(const pool_segment *seg, pool_event_type *kind) {
	double best = seg->move_end;
	pool_event_type k = seg->move_kind;
	if (seg->spin_end < best) {
		best = seg->spin_end;
		k = POOL_EVENT_SPIN_STOP;
	}
	if (kind)
		*kind = k;
	return best;
}

/// Centre position and velocity tau >= 0 after the start: the segment's one polynomial (tau is
/// clamped at the translation's own end, where the motion stops changing that way). Inline: the
/// schedule evaluates it for every pair it predicts.
static inline void pool_segment_path(const pool_segment *seg, double tau, pool_vec3 *pos, pool_vec3 *vel) {
	const pool_ball_state *s = &seg->start;
	if (!(tau > 0.0) || !seg->model->translating) {
		*pos = s->pos;
		*vel = s->vel;
		return;
	}
	const double t = tau < seg->move_end ? tau : seg->move_end;
	*pos = pool_v3_madd(pool_v3_madd(s->pos, t, s->vel), 0.5 * t * t, seg->acc);
	*vel = pool_v3_madd(s->vel, t, seg->acc);
}

/// The range [*lo, *hi] of one coordinate x0 + v t + a t^2 / 2 of a path over t in [t_lo, t_hi]
/// (times from the segment's start): its ends and, when it turns inside (its speed changes sign
/// there), its vertex. For the searches' boxes, which a margin widens beyond rounding: a vertex
/// within rounding of an end is that end.
static inline void pool_segment_range_1d(double x0, double v, double a, double t_lo, double t_hi, double *lo,
                                         double *hi) {
	const double e0 = x0 + t_lo * v + 0.5 * t_lo * t_lo * a, e1 = x0 + t_hi * v + 0.5 * t_hi * t_hi * a;
	*lo = e0 < e1 ? e0 : e1;
	*hi = e0 < e1 ? e1 : e0;
	const double v0 = v + a * t_lo, v1 = v + a * t_hi;
	if ((v0 < 0.0 && v1 > 0.0) || (v0 > 0.0 && v1 < 0.0)) { // a division only then
		const double t = -v / a;
		if (t > t_lo && t < t_hi) {
			const double e = x0 + t * v + 0.5 * t * t * a;
			*lo = e < *lo ? e : *lo;
			*hi = e > *hi ? e : *hi;
		}
	}
}

/// The whole state tau >= 0 after the start, in closed form (every component clamped at its
/// own end time, so any tau is safe).
void pool_segment_state(const pool_segment *seg, const pool_params *p, double tau, pool_ball_state *out);

#endif
