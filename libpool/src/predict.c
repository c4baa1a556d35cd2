// Event prediction (PHYSICS.md "Predicting events").
#include "predict.h"

#include <math.h>

#include "collision.h"
#include "contact.h"

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
	const double d0 = 2.0 * R, touch = d0 + POOL_TOUCH_TOLERANCE;
	const double dd = pool_v3_dot(dp, dp);
	if (!(T >= 0.0))
		return INFINITY;
	// f = |p|^2 - (2R)^2 with p(tau) = dp + dv tau + da tau^2.
	const double pv = pool_v3_dot(dp, dv), vv = pool_v3_dot(dv, dv);
	pool_contact_gap g;
	g.f[0] = dd - d0 * d0;
	g.f[1] = 2.0 * pv;
	g.f[2] = vv + 2.0 * pool_v3_dot(da, dp);
	g.f[3] = 2.0 * pool_v3_dot(da, dv);
	g.f[4] = pool_v3_dot(da, da);
	if (dd > touch * touch) // apart: the hot path, no square root
		return T > 0.0 && may_touch(dp, dv, da, R, T) ? pool_contact_first_falling_root(g.f, 4, T) : INFINITY;
	const double dist = sqrt(dd);
	if (!(dist > 0.0))
		return INFINITY; // coincident centres have no normal (placement refuses them)
	g.gap = dist - d0;
	// Rate and curvature of the distance |p|: |p|' = p.p'/|p|, |p|'' = (p'.p' + p.p'')/|p| - (p.p')^2/|p|^3
	// (the tangential part of dv curves a touching pair apart).
	g.speed = -pv / dist;
	g.accel = -((vv + 2.0 * pool_v3_dot(dp, da)) / dist - pv * pv / (dd * dist));
	return pool_contact_next(&g, T);
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

// Earliest tau in [0, T] where x0 + v tau + a/2 tau^2 meets `target` coming from the side
// where sign (target - x) > 0 (sign +1: increasing towards it); INFINITY when never.
static double line_contact(double x0, double v, double a, double target, double sign, double T) {
	pool_contact_gap g;
	g.gap = sign * (target - x0);
	g.speed = sign * v;
	g.accel = sign * a;
	g.f[0] = g.gap;
	g.f[1] = -g.speed;
	g.f[2] = -0.5 * g.accel;
	g.f[3] = g.f[4] = 0.0;
	return pool_contact_next(&g, T);
}

double pool_predict_cushion(const pool_table_def *table, double R, const pool_ball_state *s,
                            pool_vec3 acc, double T, pool_rail *rail, pool_pocket *pocket) {
	const double dc = pool_cushion_contact_distance(R, table->cushion_height);
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
