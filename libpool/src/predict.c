// Event prediction (docs/physics.md "Predicting events"): each contact's gap polynomial, handed to
// the one rule for touching and approaching bodies (contact.c).
#include "predict.h"

#include <math.h>

#include "contact.h"
#include "geometry.h"
#include "pool/quartic.h"
#include "pool/sim.h"
#include "vec3.h"

// Squared distance from the origin to the segment [a, b].
static double segment_dist2(pool_vec3 a, pool_vec3 b) {
	const pool_vec3 e = pool_v3_sub(b, a);
	const double ee = pool_v3_dot(e, e);
	double t = ee > 0.0 ? -pool_v3_dot(a, e) / ee : 0.0;
	t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
	const pool_vec3 x = pool_v3_madd(a, t, e);
	return pool_v3_dot(x, x);
}

// Squared distance from the origin to the triangle (a, b, c), in 3D: the nearest of its edges,
// or its plane when the origin projects inside it. Degenerate triangles (collinear control points:
// a straight path) have no plane and are their edges.
static double triangle_dist2(pool_vec3 a, pool_vec3 b, pool_vec3 c) {
	double d = fmin(segment_dist2(a, b), fmin(segment_dist2(b, c), segment_dist2(c, a)));
	const pool_vec3 nrm = pool_v3_cross(pool_v3_sub(b, a), pool_v3_sub(c, a));
	const double nn = pool_v3_dot(nrm, nrm);
	if (nn > 0.0) {
		const double h = pool_v3_dot(a, nrm); // origin's plane offset times |nrm|
		const pool_vec3 q = pool_v3_scale(nrm, h / nn); // the origin projected onto the plane
		const double s0 = pool_v3_dot(pool_v3_cross(pool_v3_sub(b, a), pool_v3_sub(q, a)), nrm);
		const double s1 = pool_v3_dot(pool_v3_cross(pool_v3_sub(c, b), pool_v3_sub(q, b)), nrm);
		const double s2 = pool_v3_dot(pool_v3_cross(pool_v3_sub(a, c), pool_v3_sub(q, c)), nrm);
		if ((s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) || (s0 <= 0.0 && s1 <= 0.0 && s2 <= 0.0))
			d = fmin(d, h * h / nn);
	}
	return d;
}

// The least and the greatest of three numbers (no NaN here: the caller's T is finite).
static inline double fmin3(double a, double b, double c) {
	const double m = a < b ? a : b;
	return m < c ? m : c;
}
static inline double fmax3(double a, double b, double c) {
	const double m = a > b ? a : b;
	return m > c ? m : c;
}

// Cheap rejection: over [0, T] the quadratic path p(tau) = dp + dv tau + da tau^2 is a Bezier
// curve inside the triangle of its control points P0, P0 + dv T / 2, P0 + dv T + da T^2 (in 3D:
// airborne balls too); if that triangle stays farther than 2R from the origin, the balls
// cannot touch. The margin 1e-9 (relative) covers the rounding of the control points.
// reach_tested: the caller found the pair within reach (pool_predict_pair_out_of_reach) already.
static inline int may_touch(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T, int reach_tested) {
	if (!isfinite(T))
		return 1;
	if (!reach_tested && pool_predict_pair_out_of_reach(dp, dv, da, R, T)) // cheaper still, enough for most pairs
		return 0;
	const pool_vec3 p1 = pool_v3_madd(dp, 0.5 * T, dv);
	const pool_vec3 p2 = pool_v3_madd(pool_v3_madd(dp, T, dv), T * T, da);
	const double d2 = 4.0 * R * R * (1.0 + 1e-9);
	if (dp.z == 0.0 && p1.z == 0.0 && p2.z == 0.0) {
		// In the plane (both balls on the cloth: the hot path). The triangle's bounding box
		// farther than 2R from the origin: apart, without the edges (most pairs that get here).
		const double x_lo = fmin3(dp.x, p1.x, p2.x), x_hi = fmax3(dp.x, p1.x, p2.x);
		const double y_lo = fmin3(dp.y, p1.y, p2.y), y_hi = fmax3(dp.y, p1.y, p2.y);
		const double gx = x_lo > 0.0 ? x_lo : x_hi < 0.0 ? -x_hi : 0.0, gy = y_lo > 0.0 ? y_lo : y_hi < 0.0 ? -y_hi : 0.0;
		if (gx * gx + gy * gy > d2)
			return 0;
		// Origin inside the triangle when the three edge cross products agree in sign, else the
		// nearest edge.
		const double c0 = dp.x * p1.y - dp.y * p1.x, c1 = p1.x * p2.y - p1.y * p2.x, c2 = p2.x * dp.y - p2.y * dp.x;
		if ((c0 >= 0 && c1 >= 0 && c2 >= 0) || (c0 <= 0 && c1 <= 0 && c2 <= 0))
			return 1;
		return segment_dist2(dp, p1) <= d2 || segment_dist2(p1, p2) <= d2 || segment_dist2(p2, dp) <= d2;
	}
	return triangle_dist2(dp, p1, p2) <= d2;
}

static inline double ball_ball(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T, int reach_tested) {
	const double d0 = 2.0 * R, touch = d0 + POOL_TOUCH_TOLERANCE;
	const double dd = pool_v3_dot(dp, dp);
	if (!(T >= 0.0))
		return INFINITY;
	// Apart (the hot path, no square root): most pairs are out of reach over the window.
	const int apart = dd > touch * touch;
	if (apart && !(T > 0.0 && may_touch(dp, dv, da, R, T, reach_tested)))
		return INFINITY;
	// f = |p|^2 - (2R)^2 with p(tau) = dp + dv tau + da tau^2.
	const double pv = pool_v3_dot(dp, dv), vv = pool_v3_dot(dv, dv);
	pool_contact_gap g;
	g.f[0] = dd - d0 * d0;
	g.f[1] = 2.0 * pv;
	g.f[2] = vv + 2.0 * pool_v3_dot(da, dp);
	g.f[3] = 2.0 * pool_v3_dot(da, dv);
	g.f[4] = pool_v3_dot(da, da);
	if (apart)
		return pool_contact_first_falling_root(g.f, 4, T);
	const double dist = sqrt(dd);
	if (!(dist > 0.0))
		return INFINITY; // coincident centres have no normal (placement refuses them)
	g.gap = dist - d0;
	// Rate and curvature of the distance |p|: |p|' = p.p'/|p|, |p|'' = (p'.p' + p.p'')/|p| - (p.p')^2/|p|^3
	// = (|dv across dp|^2 + 2 dp.da)/|p| (the tangential part of dv curves a touching pair apart;
	// taken as that part's own square, never negative, pool_v3_across2 says why).
	g.speed = -pv / dist;
	// The curvature decides only when rounding cannot tell the speed's sign (pool_contact_now):
	// its two divisions are left out for the touching pairs that clearly approach or part.
	const int speed_decides = g.speed > POOL_APPROACH_EPS || g.speed < -POOL_APPROACH_EPS;
	g.accel = speed_decides ? 0.0 : -(pool_v3_across2(dv, dp) + 2.0 * pool_v3_dot(dp, da)) / dist;
	return pool_contact_next(&g, T);
}

double pool_predict_ball_ball(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T) {
	return ball_ball(dp, dv, da, R, T, 0);
}

double pool_predict_ball_ball_in_reach(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T) {
	return ball_ball(dp, dv, da, R, T, 1);
}

// Earliest tau in [0, T] at which a gap side (line - x), now `gap` and not out of reach
// (pool_line_reach), closes along x0 + v tau + a/2 tau^2 (side +1: x increasing towards the line);
// INFINITY when never.
static double gap_contact(double gap, double v, double a, double side, double T) {
	pool_contact_gap g;
	g.gap = gap;
	g.speed = side * v;
	g.accel = side * a;
	g.f[0] = g.gap;
	g.f[1] = -g.speed;
	g.f[2] = -0.5 * g.accel;
	// Apart and staying apart (the least of the gap over the window well above zero): most rails
	// a ball does not reach before its segment ends, without the root finder either.
	if (g.gap > POOL_TOUCH_TOLERANCE && pool_contact_quadratic_apart(g.f[0], g.f[1], g.f[2], T))
		return INFINITY;
	g.f[3] = g.f[4] = 0.0;
	return pool_contact_next(&g, T);
}

// Earliest tau in [0, T] where x0 + v tau + a/2 tau^2 meets `line` coming from the side where
// side (line - x) > 0 (side +1: increasing towards it); INFINITY when never.
static double line_contact(double x0, double v, double a, double line, double side, double T) {
	const double gap = side * (line - x0);
	// Apart and out of reach over the window: no contact, without the root finder.
	if (gap > POOL_TOUCH_TOLERANCE && pool_line_reach(v, a, T) < gap)
		return INFINITY;
	return gap_contact(gap, v, a, side, T);
}

// One rail of cushion_lines: its contact line and side, the centre's coordinate q0, speed v and
// acceleration a across it, that axis' reach; *best and *best_rail become its contact if earlier.
static inline void rail_line(double line, double side, double q0, double v, double a, double reach, double T,
                             pool_rail rail, double *best, pool_rail *best_rail) {
	const double gap = side * (line - q0);
	// Apart and out of reach over the window: no contact, without the root finder.
	if (gap > POOL_TOUCH_TOLERANCE && reach < gap)
		return;
	const double t = gap_contact(gap, v, a, side, T);
	if (t < *best) {
		*best = t;
		*best_rail = rail;
	}
}

// pool_predict_cushion with the contact distance dc of the table and ball radius.
static double cushion_lines(const pool_table_def *table, double dc, const pool_ball_state *s, pool_vec3 acc, double T,
                            pool_rail *rail, pool_pocket *pocket) {
	double best = INFINITY;
	pool_rail best_rail = POOL_RAIL_NONE;
	// The reach of each axis, the same for its two rails; the rails in their order (the first of
	// two contacts at one instant wins), south and north across y.
	const double reach_x = pool_line_reach(s->vel.x, acc.x, T), reach_y = pool_line_reach(s->vel.y, acc.y, T);
	rail_line(pool_rail_contact_line(table, dc, POOL_RAIL_SOUTH), -1.0, s->pos.y, s->vel.y, acc.y, reach_y, T,
	          POOL_RAIL_SOUTH, &best, &best_rail);
	rail_line(pool_rail_contact_line(table, dc, POOL_RAIL_NORTH), 1.0, s->pos.y, s->vel.y, acc.y, reach_y, T,
	          POOL_RAIL_NORTH, &best, &best_rail);
	rail_line(pool_rail_contact_line(table, dc, POOL_RAIL_WEST), -1.0, s->pos.x, s->vel.x, acc.x, reach_x, T,
	          POOL_RAIL_WEST, &best, &best_rail);
	rail_line(pool_rail_contact_line(table, dc, POOL_RAIL_EAST), 1.0, s->pos.x, s->vel.x, acc.x, reach_x, T,
	          POOL_RAIL_EAST, &best, &best_rail);
	*rail = best_rail;
	*pocket = POOL_POCKET_NONE;
	if (best_rail != POOL_RAIL_NONE) {
		const double along = pool_rail_along_x(best_rail) ? s->pos.x + best * s->vel.x + 0.5 * acc.x * best * best
		                                                  : s->pos.y + best * s->vel.y + 0.5 * acc.y * best * best;
		*pocket = pool_pocket_at(table, best_rail, along);
	}
	return best;
}

double pool_predict_cushion(const pool_table_def *table, double R, const pool_ball_state *s,
                            pool_vec3 acc, double T, pool_rail *rail, pool_pocket *pocket) {
	return cushion_lines(table, pool_table_contact_distance(table, R), s, acc, T, rail, pocket);
}

double pool_predict_cushion_shape(const pool_table_shape *sh, const pool_ball_state *s, pool_vec3 acc, double T,
                                  pool_event_type *kind, pool_site *site) {
	if (sh->table.pockets != POOL_POCKETS_MOUTH_LINES)
		return pool_predict_cushion_jaws(sh, s, acc, T, kind, site);
	// The thesis model's lines, with the shape's contact distance (computed once).
	site->part = -1;
	const double t = cushion_lines(&sh->table, sh->dc, s, acc, T, &site->rail, &site->pocket);
	*kind = site->pocket != POOL_POCKET_NONE ? POOL_EVENT_POCKET : POOL_EVENT_BALL_CUSHION;
	return t;
}

/// m: how far past a rail's contact line a flight may land and stay on the table: as far as a
/// ball may be placed past it (POOL_TOUCH_TOLERANCE, falling straight down from there) and the
/// landing point's rounding (a few ulps of the table's size, 1e-15 m). It was 2
/// POOL_TOUCH_TOLERANCE: a flight over a mouth's line landing 1 to 2 nm past it stayed on the
/// cloth there, further out than any ball may be (test_flight: test_landing_past_a_mouth_line).
#define LANDING_PAST_LINE (POOL_TOUCH_TOLERANCE + 1e-12)

// The first instant in (after, window] at which a flying ball's distance to a nose line
// (relative path dp + dv tau + da tau^2 in the rail's normal plane) falls to R while closing,
// with the ball's coordinate along the rail (a0 + va tau + aa tau^2 / 2) outside the pocket
// mouths: a contact with the nose found after one that fell over a mouth (a ball rising through
// the line over a mouth comes down onto the nose further along); INFINITY when none.
static double later_nose_contact(const pool_table_def *table, pool_rail rail, pool_vec3 dp, pool_vec3 dv, pool_vec3 da,
                                 double R, double a0, double va, double aa, double after, double window) {
	const double c[5] = {pool_v3_dot(da, da), 2.0 * pool_v3_dot(da, dv), pool_v3_dot(dv, dv) + 2.0 * pool_v3_dot(da, dp),
	                     2.0 * pool_v3_dot(dv, dp), pool_v3_dot(dp, dp) - R * R};
	double roots[4];
	const int n = pool_quartic_real_roots(c, roots);
	for (int k = 0; k < n; ++k) {
		const double r = roots[k];
		if (!(r > after && r <= window))
			continue;
		const double slope = ((4.0 * c[0] * r + 3.0 * c[1]) * r + 2.0 * c[2]) * r + c[3];
		if (slope < 0.0 && pool_pocket_at(table, rail, a0 + r * va + 0.5 * aa * r * r) == POOL_POCKET_NONE)
			return r;
	}
	return INFINITY;
}

double pool_predict_flight(const pool_table_def *table, double R, const pool_ball_state *s, pool_vec3 acc, double T,
                           pool_event_type *kind, pool_rail *rail, pool_pocket *pocket) {
	const double dc = pool_table_contact_distance(table, R), h = table->cushion_height;
	*kind = POOL_EVENT_BALL_TABLE;
	*rail = POOL_RAIL_NONE;
	*pocket = POOL_POCKET_NONE;
	// Landing: the height above the cloth z - R reaches 0 (gravity presses it down).
	pool_contact_gap land;
	land.gap = s->pos.z - R;
	land.speed = -s->vel.z;
	land.accel = -acc.z;
	land.f[0] = land.gap;
	land.f[1] = s->vel.z;
	land.f[2] = 0.5 * acc.z;
	land.f[3] = land.f[4] = 0.0;
	double best = pool_contact_next(&land, T);
	for (int r = 0; r < 4; ++r) {
		const pool_rail rr = (pool_rail)r;
		const int along_x = pool_rail_along_x(rr);
		const double side = pool_rail_side(rr);
		const double q0 = along_x ? s->pos.y : s->pos.x, vq = along_x ? s->vel.y : s->vel.x, aq = along_x ? acc.y : acc.x;
		const double a0 = along_x ? s->pos.x : s->pos.y, va = along_x ? s->vel.x : s->vel.y, aa = along_x ? acc.x : acc.y;
		const double window = fmin(best, T);
		// The nose line in the rail's normal plane: distance from it (u inwards, w up) equal to R,
		// the ball-ball quartic with one "ball" of radius 0 (radius R/2 for the pair).
		const double n = pool_rail_nose_line(table, rr);
		const pool_vec3 dp = pool_v3(side * (n - q0), s->pos.z - h, 0.0);
		const pool_vec3 dv = pool_v3(-side * vq, s->vel.z, 0.0), da = pool_v3(-0.5 * side * aq, 0.5 * acc.z, 0.0);
		// A ball over a mouth already within R of the line (no nose there): the contact rule, made
		// for touching bodies, does not apply to that depth; where it comes out of the mouth into
		// the nose is a root of the distance itself.
		const int inside = pool_v3_len(dp) < R - POOL_TOUCH_TOLERANCE && pool_pocket_at(table, rr, a0) != POOL_POCKET_NONE;
		double t = inside ? later_nose_contact(table, rr, dp, dv, da, R, a0, va, aa, 0.0, window)
		                  : pool_predict_ball_ball(dp, dv, da, 0.5 * R, window);
		if (t <= window && pool_pocket_at(table, rr, a0 + t * va + 0.5 * aa * t * t) != POOL_POCKET_NONE)
			t = later_nose_contact(table, rr, dp, dv, da, R, a0, va, aa, t, window);
		int nose = t <= window && pool_pocket_at(table, rr, a0 + t * va + 0.5 * aa * t * t) == POOL_POCKET_NONE;
		if (nose) {
			best = t;
			*kind = POOL_EVENT_BALL_CUSHION;
			*rail = rr;
			*pocket = POOL_POCKET_NONE;
			// A ball coming down onto the nose from above touches it with its centre already past
			// the table's edge: the edge, crossed first, still ends the flight (below).
		}
		// The nose ends at the mouths' edges: over a mouth, a ball within R of the nose's line
		// meets its end (a point), or it would come out of the mouth inside the cushion.
		// (Ends are on the line: a ball that cannot come within R of the line in the window,
		// most flights, meets none of them; nor one that cannot reach the end itself.)
		double ends[4];
		const double w_ends = best < T ? best : T;
		const double reach = (pool_v3_len(s->vel) + 0.5 * pool_v3_len(acc) * w_ends) * w_ends;
		const int n_ends = pool_v3_len(dp) - R > reach ? 0 : pool_nose_ends(table, rr, ends);
		for (int k = 0; k < n_ends; ++k) {
			const pool_vec3 end = along_x ? pool_v3(ends[k], n, h) : pool_v3(n, ends[k], h);
			const double w = fmin(best, T);
			if (pool_v3_len(pool_v3_sub(s->pos, end)) - R > reach)
				continue;
			t = pool_predict_ball_ball(pool_v3_sub(s->pos, end), s->vel, pool_v3_scale(acc, 0.5), 0.5 * R, w);
			if (t <= w && pool_pocket_at(table, rr, a0 + t * va + 0.5 * aa * t * t) != POOL_POCKET_NONE) {
				best = t;
				nose = 1;
				*kind = POOL_EVENT_BALL_CUSHION;
				*rail = rr;
				*pocket = POOL_POCKET_NONE;
			}
		}
		const double before_nose = fmin(best, T);
		// Over a pocket mouth there is no nose: crossing the contact line below the nose height
		// is a pocket; above it the ball flies on.
		t = line_contact(q0, vq, aq, pool_rail_contact_line(table, dc, rr), side, before_nose);
		if (t <= before_nose) {
			const pool_pocket pk = pool_pocket_at(table, rr, a0 + t * va + 0.5 * aa * t * t);
			if (pk != POOL_POCKET_NONE && s->pos.z + t * s->vel.z + 0.5 * acc.z * t * t < h) {
				best = t;
				*kind = POOL_EVENT_POCKET;
				*rail = rr;
				*pocket = pk;
				continue;
			}
		}
		// Crossing the table's edge (the nose line's vertical plane) without touching the nose:
		// it leaves the table.
		t = line_contact(q0, vq, aq, n, side, before_nose);
		if (t <= before_nose && (!nose || t < best)) {
			best = t;
			*kind = POOL_EVENT_OFF_TABLE;
			*rail = rr;
			*pocket = POOL_POCKET_NONE;
		}
	}
	if (*kind == POOL_EVENT_BALL_TABLE && isfinite(best)) {
		// Landing beyond a contact line (over a pocket mouth it had crossed above the nose, or on
		// the rail top, which is not modelled): into that pocket, or off the table.
		const pool_vec3 at = pool_v3_madd(pool_v3_madd(s->pos, best, s->vel), 0.5 * best * best, acc);
		for (int r = 0; r < 4; ++r) {
			const pool_rail rr = (pool_rail)r;
			const double q = pool_rail_along_x(rr) ? at.y : at.x;
			if (pool_rail_side(rr) * (pool_rail_contact_line(table, dc, rr) - q) < -LANDING_PAST_LINE) {
				*pocket = pool_pocket_at(table, rr, pool_rail_along_x(rr) ? at.x : at.y);
				*kind = *pocket != POOL_POCKET_NONE ? POOL_EVENT_POCKET : POOL_EVENT_OFF_TABLE;
				*rail = rr;
				break;
			}
		}
	}
	return best;
}
