// Table geometry of the Bullet model (see bullet_table.h).
#include "bullet_table.h"

#include <algorithm>
#include <cmath>

namespace pool_bullet {
namespace {

// Adds the cushion stretches of one rail line: [lo, hi] along the line minus the open mouths.
// fixed is the line's constant coordinate shifted outwards to the capsule axis, z its height.
void add_line(TableGeometry *g, pool_rail rail, bool along_x, double fixed, double z, double lo,
              double hi, bool side_gap) {
	std::vector<std::pair<double, double>> parts;
	if (side_gap && g->side_hi > g->side_lo) {
		parts.push_back({lo, std::min(hi, g->side_lo)});
		parts.push_back({std::max(lo, g->side_hi), hi});
	} else {
		parts.push_back({lo, hi});
	}
	for (const auto &p : parts) {
		// A capsule shorter than a micrometre is no cushion (the mouths meet there).
		if (!(p.second - p.first > 1e-6))
			continue;
		RailSegment s{};
		s.rail = rail;
		const int along = along_x ? 0 : 1, across = along_x ? 1 : 0;
		s.a[along] = p.first;
		s.b[along] = p.second;
		s.a[across] = s.b[across] = fixed;
		s.a[2] = s.b[2] = z;
		g->segments.push_back(s);
	}
}

} // namespace

bool make_table_geometry(const pool_table_def &table, double radius, double capsule_radius,
                         TableGeometry *out, std::string *error) {
	TableGeometry g;
	g.length = table.length;
	g.width = table.width;
	g.nose_height = table.cushion_height;
	g.radius = radius;
	g.capsule_radius = capsule_radius;
	const double R = radius, h = table.cushion_height, rc = capsule_radius;
	if (!(std::isfinite(R) && R > 0.0)) {
		*error = "params.ball_radius: must be > 0";
		return false;
	}
	if (!(std::isfinite(h) && h > 0.0 && h < 2.0 * R)) {
		*error = "table.cushion_height: the Bullet model needs 0 < h < 2R (a nose a ball on the "
		         "cloth can touch)";
		return false;
	}
	if (!(std::isfinite(table.length) && std::isfinite(table.width) && table.length > 2.0 * R &&
	      table.width > 2.0 * R)) {
		*error = "table.length: the table must be larger than a ball";
		return false;
	}
	// On the cloth the ball touches the nose line when its centre is dh from it horizontally
	// (PHYSICS.md); the unit normal from the nose point to the centre is n0 = (dh, R - h) / R
	// in (inward horizontal, up). The capsule axis sits rc behind the nose along -n0, so the
	// capsule surface passes through the nose point with the same normal there.
	g.touch_distance = std::sqrt(R * R - (h - R) * (h - R));
	const double out_shift = rc * g.touch_distance / R; // outwards, horizontally
	const double axis_z = h + rc * (h - R) / R;
	g.corner_open = std::max(0.0, table.corner_mouth) / std::sqrt(2.0);
	const double side = std::max(0.0, table.side_mouth);
	g.side_lo = 0.5 * table.length - 0.5 * side;
	g.side_hi = 0.5 * table.length + 0.5 * side;
	const double L = table.length, W = table.width, c = g.corner_open;
	add_line(&g, POOL_RAIL_SOUTH, true, -out_shift, axis_z, c, L - c, true);
	add_line(&g, POOL_RAIL_NORTH, true, W + out_shift, axis_z, c, L - c, true);
	add_line(&g, POOL_RAIL_WEST, false, -out_shift, axis_z, c, W - c, false);
	add_line(&g, POOL_RAIL_EAST, false, L + out_shift, axis_z, c, W - c, false);
	*out = g;
	return true;
}

pool_pocket pocket_entered(const TableGeometry &g, double x, double y) {
	const double L = g.length, W = g.width, d = g.touch_distance, c = g.corner_open;
	const bool side = g.side_hi > g.side_lo;
	if (y <= d || y >= W - d) {
		const bool north = y >= W - d;
		if (x < c)
			return north ? POOL_POCKET_NW : POOL_POCKET_SW;
		if (x > L - c)
			return north ? POOL_POCKET_NE : POOL_POCKET_SE;
		if (side && x > g.side_lo && x < g.side_hi)
			return north ? POOL_POCKET_N : POOL_POCKET_S;
	}
	if (x <= d || x >= L - d) {
		const bool east = x >= L - d;
		if (y < c)
			return east ? POOL_POCKET_SE : POOL_POCKET_SW;
		if (y > W - c)
			return east ? POOL_POCKET_NE : POOL_POCKET_NW;
	}
	return POOL_POCKET_NONE;
}

bool outside_table(const TableGeometry &g, double x, double y) {
	return !(x >= 0.0 && x <= g.length && y >= 0.0 && y <= g.width);
}

double distance_to_axis(const RailSegment &s, const double p[3]) {
	double ab[3], ap[3];
	double ab2 = 0.0, t = 0.0;
	for (int i = 0; i < 3; ++i) {
		ab[i] = s.b[i] - s.a[i];
		ap[i] = p[i] - s.a[i];
		ab2 += ab[i] * ab[i];
		t += ab[i] * ap[i];
	}
	t = ab2 > 0.0 ? std::clamp(t / ab2, 0.0, 1.0) : 0.0;
	double d2 = 0.0;
	for (int i = 0; i < 3; ++i) {
		const double e = ap[i] - t * ab[i];
		d2 += e * e;
	}
	return std::sqrt(d2);
}

} // namespace pool_bullet
