// Event prediction (PHYSICS.md "Predicting events").
#include "predict.h"

#include <math.h>

#include "pool/quartic.h"
#include "pool/sim.h"
#include "vec3.h"

// Squared distance from the origin to the segment [a, b] in the plane.
static double seg_dist2(double ax, double ay, double bx, double by) {
	double ex = bx - ax, ey = by - ay;
	double ee = ex * ex + ey * ey;
	double t = ee > 0.0 ? -(ax * ex + ay * ey) / ee : 0.0;
	t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
	double x = ax + t * ex, y = ay + t * ey;
	return x * x + y * y;
}

// Cheap rejection: over [0, T] the quadratic path p(tau) is a Bezier curve inside the triangle
// of its control points P0, P0 + V T / 2, P0 + V T + A T^2; if that triangle stays farther
// than 2R from the origin, the balls cannot touch.
static int may_touch(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T) {
	if (!isfinite(T) || dp.z != 0.0 || dv.z != 0.0 || da.z != 0.0)
		return 1;
	double x0 = dp.x, y0 = dp.y;
	double x1 = dp.x + 0.5 * T * dv.x, y1 = dp.y + 0.5 * T * dv.y;
	double x2 = dp.x + T * dv.x + T * T * da.x, y2 = dp.y + T * dv.y + T * T * da.y;
	double d2 = 4.0 * R * R * (1.0 + 1e-9);
	// Origin inside the triangle: same sign of the three edge cross products.
	double c0 = x0 * y1 - y0 * x1, c1 = x1 * y2 - y1 * x2, c2 = x2 * y0 - y2 * x0;
	if ((c0 >= 0 && c1 >= 0 && c2 >= 0) || (c0 <= 0 && c1 <= 0 && c2 <= 0))
		return 1;
	return seg_dist2(x0, y0, x1, y1) <= d2 || seg_dist2(x1, y1, x2, y2) <= d2 ||
	       seg_dist2(x2, y2, x0, y0) <= d2;
}

double pool_predict_ball_ball(pool_vec3 dp, pool_vec3 dv, pool_vec3 da, double R, double T) {
	const double d0 = 2.0 * R;
	const double dd = pool_v3_dot(dp, dp);
	if (!(T >= 0.0))
		return INFINITY;
	if (dd <= (d0 + POOL_TOUCH_TOLERANCE) * (d0 + POOL_TOUCH_TOLERANCE)) {
		// Touching (a frozen rack, or just after an event): collide now only if approaching.
		const double dpdv = pool_v3_dot(dp, dv);
		if (dpdv < -POOL_APPROACH_EPS * sqrt(dd))
			return 0.0;
		// ... or if not separating while cloth friction pushes them together (|p|^2 has a negative
		// second-order term, a2 = dv.dv + 2 da.dp = |dv_t|^2 + 2R a_n): the root at 0 has no
		// approach speed, and when rounding left them overlapping by a hair there is no later
		// approaching root either, so they would pass through each other. The threshold keeps
		// a_n below -1e-9 m/s^2, enough for the event's separation floor (sim.c) to show in the
		// velocities.
		if (dpdv <= 0.0 && pool_v3_dot(dv, dv) + 2.0 * pool_v3_dot(da, dp) < -d0 * POOL_APPROACH_EPS)
			return 0.0;
	}
	if (T == 0.0 || !may_touch(dp, dv, da, R, T))
		return INFINITY;
	const double c[5] = {
		pool_v3_dot(da, da),
		2.0 * pool_v3_dot(da, dv),
		pool_v3_dot(dv, dv) + 2.0 * pool_v3_dot(da, dp),
		2.0 * pool_v3_dot(dv, dp),
		pool_v3_dot(dp, dp) - d0 * d0,
	};
	// Roots in ascending order from the window solver; a root where the balls separate (a touching
	// pair moving apart, or a graze) is stepped over.
	const double hi = isfinite(T) ? T : 1e12;
	double lo = 0.0, t;
	for (int it = 0; it < 4 && pool_quartic_smallest_root_in(c, lo, hi, &t) == 0; ++it) {
		// Approaching at the root: p . p' < 0 with |p| = 2R.
		pool_vec3 p = pool_v3_madd(pool_v3_madd(dp, t, dv), t * t, da);
		pool_vec3 dpdt = pool_v3_madd(dv, 2.0 * t, da);
		if (pool_v3_dot(p, dpdt) < -POOL_APPROACH_EPS * d0)
			return t;
		lo = t + 1e-13 * (1.0 + t);
		if (!(lo <= hi))
			break;
	}
	// Insurance against a root the solver lost: apart now, overlapping at T means a crossing.
	const double fT = pool_v3_dot(pool_v3_madd(pool_v3_madd(dp, T, dv), T * T, da),
	                              pool_v3_madd(pool_v3_madd(dp, T, dv), T * T, da)) - d0 * d0;
	if (c[4] > 0.0 && fT < 0.0 && isfinite(T)) {
		double lo = 0.0, hi = T;
		for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
			double mid = 0.5 * (lo + hi);
			if (mid <= lo || mid >= hi)
				break;
			pool_vec3 p = pool_v3_madd(pool_v3_madd(dp, mid, dv), mid * mid, da);
			if (pool_v3_dot(p, p) - d0 * d0 > 0.0)
				lo = mid;
			else
				hi = mid;
		}
		return lo;
	}
	return INFINITY;
}

pool_pocket pool_pocket_at(const pool_table_def *table, pool_rail rail, double along) {
	const double L = table->length, W = table->width;
	const double corner = table->corner_mouth / sqrt(2.0);
	switch (rail) {
	case POOL_RAIL_SOUTH:
	case POOL_RAIL_NORTH: {
		int north = rail == POOL_RAIL_NORTH;
		if (along < corner)
			return north ? POOL_POCKET_NW : POOL_POCKET_SW;
		if (along > L - corner)
			return north ? POOL_POCKET_NE : POOL_POCKET_SE;
		if (fabs(along - 0.5 * L) < 0.5 * table->side_mouth)
			return north ? POOL_POCKET_N : POOL_POCKET_S;
		return POOL_POCKET_NONE;
	}
	case POOL_RAIL_WEST:
	case POOL_RAIL_EAST: {
		int east = rail == POOL_RAIL_EAST;
		if (along < corner)
			return east ? POOL_POCKET_SE : POOL_POCKET_SW;
		if (along > W - corner)
			return east ? POOL_POCKET_NE : POOL_POCKET_NW;
		return POOL_POCKET_NONE;
	}
	default: return POOL_POCKET_NONE;
	}
}

// Earliest tau in [0, T] where x0 + v tau + a/2 tau^2 reaches `target` moving in direction
// `sign` (+1: increasing) faster than POOL_APPROACH_EPS; INFINITY when never.
static double line_contact(double x0, double v, double a, double target, double sign, double T) {
	double gap = sign * (target - x0); // > 0 while short of the line
	if (gap <= POOL_TOUCH_TOLERANCE && sign * v > POOL_APPROACH_EPS)
		return 0.0;
	// Touching, not leaving, and pushed into the line (a ball frozen to a rail that slides along
	// it with a curve towards it): the root at 0 has no approach speed yet, so the loop below would
	// skip it and the ball would pass through the nose. Contact now; the event's separation floor
	// (sim.c) sends it off.
	if (gap <= POOL_TOUCH_TOLERANCE && sign * v >= 0.0 && sign * a > 0.0)
		return 0.0;
	// 0.5 a t^2 + v t + (x0 - target) = 0
	double A = 0.5 * a, B = v, C = x0 - target;
	double r[2];
	int n = 0;
	if (A == 0.0) {
		if (B != 0.0)
			r[n++] = -C / B;
	} else {
		double disc = B * B - 4.0 * A * C;
		if (disc >= 0.0) {
			double q = -0.5 * (B + copysign(sqrt(disc), B));
			if (q != 0.0) {
				r[n++] = q / A;
				r[n++] = C / q;
			} else {
				r[n++] = 0.0;
			}
		}
	}
	if (n == 2 && r[1] < r[0]) {
		double t = r[0];
		r[0] = r[1];
		r[1] = t;
	}
	for (int i = 0; i < n; ++i)
		if (r[i] >= 0.0 && r[i] <= T && sign * (v + a * r[i]) > POOL_APPROACH_EPS)
			return r[i];
	return INFINITY;
}

double pool_predict_cushion(const pool_table_def *table, double R, const pool_ball_state *s,
                            pool_vec3 acc, double T, pool_rail *rail, pool_pocket *pocket) {
	const double dc = 0.0 + sqrt(R * R - (table->cushion_height - R) * (table->cushion_height - R));
	double best = INFINITY;
	pool_rail best_rail = POOL_RAIL_NONE;
	const double tx[4] = {dc, table->width - dc, dc, table->length - dc};
	for (int r = 0; r < 4; ++r) {
		int along_x = r <= POOL_RAIL_NORTH;           // south / north rails: motion in y
		double sign = (r == POOL_RAIL_NORTH || r == POOL_RAIL_EAST) ? 1.0 : -1.0;
		double t = along_x ? line_contact(s->pos.y, s->vel.y, acc.y, tx[r], sign, T)
		                   : line_contact(s->pos.x, s->vel.x, acc.x, tx[r], sign, T);
		if (t < best) {
			best = t;
			best_rail = (pool_rail)r;
		}
	}
	*rail = best_rail;
	*pocket = POOL_POCKET_NONE;
	if (best_rail != POOL_RAIL_NONE) {
		double along = best_rail <= POOL_RAIL_NORTH ? s->pos.x + best * s->vel.x + 0.5 * acc.x * best * best
		                                            : s->pos.y + best * s->vel.y + 0.5 * acc.y * best * best;
		*pocket = pool_pocket_at(table, best_rail, along);
	}
	return best;
}
