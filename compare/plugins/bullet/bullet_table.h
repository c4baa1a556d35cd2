// Geometry of the pool table as the Bullet plugin builds it: libpool's cushion nose lines turned
// into capsules that touch a ball on the cloth exactly where the line does, the pocket mouths
// (gaps between the capsules), and which pocket a ball crossing a rail line falls into
// (PHYSICS.md, "Ball-cushion" and "Pocket").
#ifndef POOL_BULLET_TABLE_H
#define POOL_BULLET_TABLE_H

#include <string>
#include <vector>

#include "pool/event.h"
#include "pool/table.h"

namespace pool_bullet {

/// One cushion between two pockets: a capsule whose axis runs from a to b (parallel to x or y).
struct RailSegment {
	pool_rail rail; ///< which rail line it belongs to
	double a[3];    ///< m, one end of the capsule axis
	double b[3];    ///< m, the other end
};

/// Derived table geometry for one ball radius and capsule radius.
struct TableGeometry {
	double length = 0.0;         ///< m, L
	double width = 0.0;          ///< m, W
	double nose_height = 0.0;    ///< m, h
	double radius = 0.0;         ///< m, ball radius R
	double capsule_radius = 0.0; ///< m, rc
	double touch_distance = 0.0; ///< m, horizontal centre-to-nose distance at contact on the cloth
	double corner_open = 0.0;    ///< m, length of each rail line a corner pocket opens (mouth/sqrt 2)
	double side_lo = 0.0;        ///< m, x where the side pockets' mouths begin
	double side_hi = 0.0;        ///< m, x where they end
	std::vector<RailSegment> segments; ///< the cushions, at most six
};

/// Builds the geometry; false with a message naming the field when the table cannot be modelled
/// (a nose the ball cannot reach from the cloth: h must lie in (0, 2R)).
bool make_table_geometry(const pool_table_def &table, double radius, double capsule_radius,
                         TableGeometry *out, std::string *error);

/// The pocket a ball whose centre is at (x, y) has entered: its centre is within the touch
/// distance of a rail line, inside that line's pocket mouth. POOL_POCKET_NONE otherwise.
pool_pocket pocket_entered(const TableGeometry &geometry, double x, double y);

/// Whether a centre lies beyond a rail line (a ball that tunnelled through a cushion).
bool outside_table(const TableGeometry &geometry, double x, double y);

/// Distance from point p to a capsule's axis segment (m).
double distance_to_axis(const RailSegment &segment, const double p[3]);

} // namespace pool_bullet

#endif
