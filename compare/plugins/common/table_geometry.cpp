// Table geometry of the engine plugins (see table_geometry.h).
#include "table_geometry.h"

#include <algorithm>
#include <cmath>

namespace pool_plugin {
namespace {

// Adds the capsule for the stretch [lo, hi] of a rail line, whose axis lies at the constant
// coordinate `fixed` (across the line) and height z.
void add_segment(TableGeometry *g, const CushionLayout &layout, pool_rail rail, bool along_x,
                 double fixed, double z, double lo, double hi) {
	if (!(hi - lo > layout.min_length))
		return;
	RailSegment s{};
	s.rail = rail;
	const int along = along_x ? 0 : 1, across = along_x ? 1 : 0;
	s.a[along] = lo;
	s.b[along] = hi;
	s.a[across] = s.b[across] = fixed;
	s.a[2] = s.b[2] = z;
	g->segments.push_back(s);
}

// The cushions of one rail line: [lo, hi] along it minus the side pockets' mouth if it has one.
void add_line(TableGeometry *g, const CushionLayout &layout, pool_rail rail, bool along_x,
              double fixed, double z, double lo, double hi, bool side_gap) {
	if (side_gap && (layout.split_at_closed_side || g->side_hi > g->side_lo)) {
		add_segment(g, layout, rail, along_x, fixed, z, lo, std::min(hi, g->side_lo));
		add_segment(g, layout, rail, along_x, fixed, z, std::max(lo, g->side_hi), hi);
	} else {
		add_segment(g, layout, rail, along_x, fixed, z, lo, hi);
	}
}

} // namespace

TableGeometry make_table_geometry(const pool_table_def &table, double radius,
                                  const CushionLayout &layout) {
	TableGeometry g;
	g.length = table.length;
	g.width = table.width;
	g.nose_height = table.cushion_height;
	g.radius = radius;
	g.capsule_radius = layout.capsule_radius;
	const double R = radius, h = table.cushion_height, rc = layout.capsule_radius;
	// On the cloth the ball touches the nose line when its centre is d0 from it horizontally
	// (docs/physics.md); the unit normal from the nose point to the centre is n0 = (d0, R - h) / R
	// in (inward horizontal, up). The capsule axis sits rc behind the nose along -n0, so the
	// capsule surface passes through the nose point with the same normal there:
	// |centre - axis| = R + rc at that contact.
	g.touch_distance = std::sqrt(R * R - (h - R) * (h - R));
	const double out = rc * g.touch_distance / R; // outward shift of the axis
	const double z = h + rc * (h - R) / R;        // height of the axis
	g.corner_open = table.corner_mouth / std::sqrt(2.0);
	g.side_lo = 0.5 * table.length - 0.5 * table.side_mouth;
	g.side_hi = 0.5 * table.length + 0.5 * table.side_mouth;
	const double L = table.length, W = table.width, c = g.corner_open;
	add_line(&g, layout, POOL_RAIL_SOUTH, true, -out, z, c, L - c, true);
	add_line(&g, layout, POOL_RAIL_NORTH, true, W + out, z, c, L - c, true);
	add_line(&g, layout, POOL_RAIL_WEST, false, -out, z, c, W - c, false);
	add_line(&g, layout, POOL_RAIL_EAST, false, L + out, z, c, W - c, false);
	return g;
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
	const double t = len2 > 0.0 ? std::clamp(dot / len2, 0.0, 1.0) : 0.0;
	double d2 = 0.0;
	for (int k = 0; k < 3; ++k) {
		const double e = ap[k] - t * ab[k];
		d2 += e * e;
	}
	return std::sqrt(d2);
}

} // namespace pool_plugin
