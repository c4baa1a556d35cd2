// Rail geometry of the ODE table (see ode_table.h).
#include "ode_table.h"

#include <cmath>

namespace pool_ode {

namespace {

// Adds the capsule for the stretch [lo, hi] of a rail line. libpool's nose is a line at height
// h; a ball on the cloth touches it with its centre at horizontal distance d0 inside the line
// and the unit normal n0 = (-d0 o, R - h) / R from the nose to the centre (o the rail's outward
// horizontal direction). A capsule of radius rc whose axis is the nose line moved by -rc n0
// touches that ball at the same point with the same normal: |centre - axis| = (R + rc).
void add_segment(TableGeometry *g, pool_rail rail, double lo, double hi) {
	if (!(hi > lo))
		return;
	const double R = g->radius, rc = g->capsule_radius, h = g->nose_height;
	const double out = rc * g->touch_distance / R; // outward shift of the axis
	const double up = h + rc * (h - R) / R;        // height of the axis
	RailSegment s;
	s.rail = rail;
	switch (rail) {
	case POOL_RAIL_SOUTH:
		s.a[0] = lo, s.a[1] = -out, s.b[0] = hi, s.b[1] = -out;
		break;
	case POOL_RAIL_NORTH:
		s.a[0] = lo, s.a[1] = g->width + out, s.b[0] = hi, s.b[1] = g->width + out;
		break;
	case POOL_RAIL_WEST:
		s.a[0] = -out, s.a[1] = lo, s.b[0] = -out, s.b[1] = hi;
		break;
	default:
		s.a[0] = g->length + out, s.a[1] = lo, s.b[0] = g->length + out, s.b[1] = hi;
		break;
	}
	s.a[2] = s.b[2] = up;
	g->segments.push_back(s);
}

} // namespace

bool make_table_geometry(const pool_table_def &table, double radius, double capsule_radius,
                         TableGeometry *out, const char **message) {
	TableGeometry g;
	g.length = table.length;
	g.width = table.width;
	g.nose_height = table.cushion_height;
	g.radius = radius;
	g.capsule_radius = capsule_radius;
	const double dh = table.cushion_height - radius;
	if (!(std::fabs(dh) < radius)) {
		*message = "table.cushion_height: the ODE model needs a nose a ball on the cloth can "
		           "touch (0 < h < 2R)";
		return false;
	}
	g.touch_distance = std::sqrt(radius * radius - dh * dh);
	g.corner_open = table.corner_mouth / std::sqrt(2.0);
	g.side_lo = 0.5 * table.length - 0.5 * table.side_mouth;
	g.side_hi = 0.5 * table.length + 0.5 * table.side_mouth;
	const double c = g.corner_open, L = g.length, W = g.width;
	for (pool_rail rail : {POOL_RAIL_SOUTH, POOL_RAIL_NORTH}) {
		add_segment(&g, rail, c, g.side_lo);
		add_segment(&g, rail, g.side_hi, L - c);
	}
	add_segment(&g, POOL_RAIL_WEST, c, W - c);
	add_segment(&g, POOL_RAIL_EAST, c, W - c);
	*out = g;
	return true;
}

pool_pocket pocket_entered(const TableGeometry &g, double x, double y) {
	const double d = g.touch_distance, c = g.corner_open, L = g.length, W = g.width;
	const bool south = y <= d, north = y >= W - d;
	if (south || north) {
		if (x < c)
			return south ? POOL_POCKET_SW : POOL_POCKET_NW;
		if (x > L - c)
			return south ? POOL_POCKET_SE : POOL_POCKET_NE;
		if (x > g.side_lo && x < g.side_hi)
			return south ? POOL_POCKET_S : POOL_POCKET_N;
	}
	const bool west = x <= d, east = x >= L - d;
	if (west || east) {
		if (y < c)
			return west ? POOL_POCKET_SW : POOL_POCKET_SE;
		if (y > W - c)
			return west ? POOL_POCKET_NW : POOL_POCKET_NE;
	}
	return POOL_POCKET_NONE;
}

bool outside_table(const TableGeometry &g, double x, double y) {
	return x < 0.0 || x > g.length || y < 0.0 || y > g.width;
}

double distance_to_axis(const RailSegment &s, const double p[3]) {
	double ab[3], ap[3], dot = 0.0, len2 = 0.0;
	for (int k = 0; k < 3; ++k) {
		ab[k] = s.b[k] - s.a[k];
		ap[k] = p[k] - s.a[k];
		dot += ab[k] * ap[k];
		len2 += ab[k] * ab[k];
	}
	double t = len2 > 0.0 ? dot / len2 : 0.0;
	t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
	double d2 = 0.0;
	for (int k = 0; k < 3; ++k) {
		double e = ap[k] - t * ab[k];
		d2 += e * e;
	}
	return std::sqrt(d2);
}

} // namespace pool_ode
