// Table geometry of the engine plugins (see table_geometry.h).
#include "table_geometry.h"

#include <algorithm>
#include <cmath>

namespace pool_plugin {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Adds the capsule for the stretch [lo, hi] of a rail line, whose axis lies at the constant
// coordinate `fixed` (across the line) and height z.
void add_segment(TableGeometry *g, const CushionLayout &layout, pool_rail rail, bool along_x,
                 double fixed, double z, double lo, double hi) {
	if (!(hi - lo > layout.min_length))
		return;
	RailSegment s{};
	s.rail = rail;
	s.radius = layout.capsule_radius;
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

void push(TableGeometry *g, pool_rail rail, double ax, double ay, double az, double bx, double by, double bz,
          double radius) {
	RailSegment s{};
	s.rail = rail;
	s.a[0] = ax, s.a[1] = ay, s.a[2] = az;
	s.b[0] = bx, s.b[1] = by, s.b[2] = bz;
	s.radius = radius;
	g->segments.push_back(s);
}

// Pockets "jaws" (docs/physics.md "Table geometry"): per pocket its facings (capsules out behind
// the facing line as the rails' are behind theirs), its jaws (chords of the arc out behind it, or
// a vertical capsule on the jaw's axis touching a ball on the cloth at r + d where that arc would
// have no room), its hole; the rails' capsules run between the jaws' tangent points.
void add_jaws(TableGeometry *g, const pool_table_def &t, const CushionLayout &layout, double out, double z) {
	const double L = t.length, W = t.width, R = g->radius, d = g->touch_distance, rc = layout.capsule_radius;
	const double a = t.corner_mouth / std::sqrt(2.0), s = 0.5 * t.side_mouth;
	struct End {
		pool_rail rail;
		double vx, vy, tx, ty, mx, my;
	};
	const End ends[6][2] = {
		{{POOL_RAIL_SOUTH, a, 0, 1, 0, 0, -1}, {POOL_RAIL_WEST, 0, a, 0, 1, -1, 0}},
		{{POOL_RAIL_SOUTH, L - a, 0, -1, 0, 0, -1}, {POOL_RAIL_EAST, L, a, 0, 1, 1, 0}},
		{{POOL_RAIL_NORTH, a, W, 1, 0, 0, 1}, {POOL_RAIL_WEST, 0, W - a, 0, -1, -1, 0}},
		{{POOL_RAIL_NORTH, L - a, W, -1, 0, 0, 1}, {POOL_RAIL_EAST, L, W - a, 0, -1, 1, 0}},
		{{POOL_RAIL_SOUTH, 0.5 * L - s, 0, -1, 0, 0, -1}, {POOL_RAIL_SOUTH, 0.5 * L + s, 0, 1, 0, 0, -1}},
		{{POOL_RAIL_NORTH, 0.5 * L - s, W, -1, 0, 0, 1}, {POOL_RAIL_NORTH, 0.5 * L + s, W, 1, 0, 0, 1}},
	};
	double nose_end[6][2] = {{0, 0}, {L, 0}, {0, W}, {L, W}, {0, 0}, {0, 0}};
	const bool corners = t.corner_mouth > 0.0, sides = t.side_mouth > 0.0;
	for (int p = 0; p < 6; ++p) {
		const bool corner = p <= POOL_POCKET_NE;
		if (!(corner ? corners : sides))
			continue;
		const double cut = corner ? t.corner_cut_angle : t.side_cut_angle;
		const double r = corner ? t.corner_jaw_radius : t.side_jaw_radius;
		const double rh = corner ? t.corner_hole_radius : t.side_hole_radius;
		const double back = (corner ? t.corner_shelf : t.side_shelf) + rh;
		const End *e = ends[p];
		const double mx = 0.5 * (e[0].vx + e[1].vx), my = 0.5 * (e[0].vy + e[1].vy);
		double ox = e[0].mx + e[1].mx, oy = e[0].my + e[1].my;
		const double ol = std::hypot(ox, oy);
		ox /= ol, oy /= ol;
		PocketHole hole{pool_pocket(p), mx + back * ox, my + back * oy, rh, mx, my, back + rh + R};
		const double tangent = r / std::tan(0.5 * cut);
		for (int c = 0; c < 2; ++c) {
			const double fx = std::cos(cut) * e[c].tx + std::sin(cut) * e[c].mx;
			const double fy = std::cos(cut) * e[c].ty + std::sin(cut) * e[c].my;
			double nx = -fy, ny = fx; // the facing's normal out of the cushion
			if (nx * e[c].tx + ny * e[c].ty > 0.0)
				nx = -nx, ny = -ny;
			const double qx = e[c].vx - hole.x, qy = e[c].vy - hole.y, b = fx * qx + fy * qy;
			const double s_hole = -b - std::sqrt(std::max(b * b - (qx * qx + qy * qy - rh * rh), 0.0));
			// The facing: from the jaw's tangent point to the hole, its axis `out` behind it.
			push(g, e[c].rail, e[c].vx + tangent * fx - out * nx, e[c].vy + tangent * fy - out * ny, z,
			     e[c].vx + s_hole * fx - out * nx, e[c].vy + s_hole * fy - out * ny, z, rc);
			// The jaw: centre, and its arc from the nose's normal to the facing's.
			const double jx = e[c].vx + tangent * e[c].tx + r * e[c].mx, jy = e[c].vy + tangent * e[c].ty + r * e[c].my;
			if (r - out > 0.0) {
				const double a0 = std::atan2(-e[c].my, -e[c].mx);
				double a1 = std::atan2(ny, nx);
				while (a1 - a0 > kPi)
					a1 -= 2.0 * kPi;
				while (a0 - a1 > kPi)
					a1 += 2.0 * kPi;
				const int chords = 6;
				for (int k = 0; k < chords; ++k) {
					const double u0 = a0 + (a1 - a0) * k / chords, u1 = a0 + (a1 - a0) * (k + 1) / chords;
					push(g, e[c].rail, jx + (r - out) * std::cos(u0), jy + (r - out) * std::sin(u0), z,
					     jx + (r - out) * std::cos(u1), jy + (r - out) * std::sin(u1), z, rc);
				}
			} else {
				push(g, e[c].rail, jx, jy, 0.0, jx, jy, 2.0 * R, std::max(r + d - R, 1e-6));
			}
			nose_end[p][c] = (e[c].rail == POOL_RAIL_SOUTH || e[c].rail == POOL_RAIL_NORTH) ? e[c].vx + tangent * e[c].tx
			                                                                               : e[c].vy + tangent * e[c].ty;
			hole.zone = std::max(hole.zone, std::hypot(e[c].vx + s_hole * fx - mx, e[c].vy + s_hole * fy - my) + R);
		}
		g->holes.push_back(hole);
	}
	// The rails' noses between the jaws.
	if (sides) {
		add_segment(g, layout, POOL_RAIL_SOUTH, true, -out, z, nose_end[POOL_POCKET_SW][0], nose_end[POOL_POCKET_S][0]);
		add_segment(g, layout, POOL_RAIL_SOUTH, true, -out, z, nose_end[POOL_POCKET_S][1], nose_end[POOL_POCKET_SE][0]);
		add_segment(g, layout, POOL_RAIL_NORTH, true, W + out, z, nose_end[POOL_POCKET_NW][0], nose_end[POOL_POCKET_N][0]);
		add_segment(g, layout, POOL_RAIL_NORTH, true, W + out, z, nose_end[POOL_POCKET_N][1], nose_end[POOL_POCKET_NE][0]);
	} else {
		add_segment(g, layout, POOL_RAIL_SOUTH, true, -out, z, nose_end[POOL_POCKET_SW][0], nose_end[POOL_POCKET_SE][0]);
		add_segment(g, layout, POOL_RAIL_NORTH, true, W + out, z, nose_end[POOL_POCKET_NW][0], nose_end[POOL_POCKET_NE][0]);
	}
	add_segment(g, layout, POOL_RAIL_WEST, false, -out, z, nose_end[POOL_POCKET_SW][1], nose_end[POOL_POCKET_NW][1]);
	add_segment(g, layout, POOL_RAIL_EAST, false, L + out, z, nose_end[POOL_POCKET_SE][1], nose_end[POOL_POCKET_NE][1]);
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
	if (table.pockets == POOL_POCKETS_JAWS) {
		g.jaws = true;
		add_jaws(&g, table, layout, out, z);
		return g;
	}
	if (table.pockets == POOL_POCKETS_NONE) {
		g.corner_open = 0.0;
		g.side_lo = g.side_hi = 0.5 * table.length;
		add_line(&g, layout, POOL_RAIL_SOUTH, true, -out, z, 0.0, L, false);
		add_line(&g, layout, POOL_RAIL_NORTH, true, W + out, z, 0.0, L, false);
		add_line(&g, layout, POOL_RAIL_WEST, false, -out, z, 0.0, W, false);
		add_line(&g, layout, POOL_RAIL_EAST, false, L + out, z, 0.0, W, false);
		return g;
	}
	add_line(&g, layout, POOL_RAIL_SOUTH, true, -out, z, c, L - c, true);
	add_line(&g, layout, POOL_RAIL_NORTH, true, W + out, z, c, L - c, true);
	add_line(&g, layout, POOL_RAIL_WEST, false, -out, z, c, W - c, false);
	add_line(&g, layout, POOL_RAIL_EAST, false, L + out, z, c, W - c, false);
	return g;
}

pool_pocket pocket_entered(const TableGeometry &g, double x, double y) {
	if (g.jaws) {
		for (const PocketHole &h : g.holes)
			if (std::hypot(x - h.x, y - h.y) < h.r)
				return h.pocket;
		return POOL_POCKET_NONE;
	}
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
	if (!(x < 0.0 || x > g.length || y < 0.0 || y > g.width))
		return false;
	for (const PocketHole &h : g.holes) // a mouth's shelf lies beyond the rail lines
		if (std::hypot(x - h.mx, y - h.my) < h.zone)
			return false;
	return true;
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
