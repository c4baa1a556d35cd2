// Geometry of the pool table as the time-stepped engine plugins build it: libpool's cushion nose
// lines turned into capsules that touch a ball on the cloth exactly where the line does, the
// pocket mouths (gaps between the capsules), and which pocket a ball crossing a rail line falls
// into (docs/physics.md, "Ball-cushion" and "Pocket").
#ifndef POOL_PLUGIN_TABLE_GEOMETRY_H
#define POOL_PLUGIN_TABLE_GEOMETRY_H

#include <vector>

#include "pool/event.h"
#include "pool/table.h"

namespace pool_plugin {

/// One capsule of the cushions: a stretch of a rail's nose between two pockets (its axis parallel
/// to x or y), or with pockets "jaws" a facing, a chord of a jaw's arc, or a jaw as a vertical
/// capsule (docs/physics.md "Table geometry"; docs/engines.md says how each touches a ball).
struct RailSegment {
	pool_rail rail; ///< which rail line it belongs to
	double a[3];    ///< m, one end of the capsule axis
	double b[3];    ///< m, the other end
	double radius = 0.0; ///< m, the capsule's radius
};

/// A pocket's hole with pockets "jaws": a ball whose centre is over it has fallen in.
struct PocketHole {
	pool_pocket pocket;
	double x, y, r;      ///< m, centre and radius of the hole
	double mx, my, zone; ///< m, the mouth's middle and the radius about it that holds the pocket
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
	std::vector<RailSegment> segments; ///< the cushions: six for the thesis model's mouths
	bool jaws = false;                  ///< pockets "jaws": holes decide pocketing
	std::vector<PocketHole> holes;      ///< with jaws
};

/// How an engine cuts the rail lines into capsules (the plugins differ here; each keeps its own).
struct CushionLayout {
	double capsule_radius;     ///< m, rc (any rc > 0 gives libpool's contact on the cloth)
	double min_length;         ///< m, a stretch no longer than this gets no capsule
	bool split_at_closed_side; ///< a zero side mouth still splits the long rails at L/2
};

/// Builds the geometry of a table that libpool validated (pool_table_def_validate) for a nose a
/// ball on the cloth can touch: the caller must have checked 0 < h < 2R (its own message).
TableGeometry make_table_geometry(const pool_table_def &table, double radius,
                                  const CushionLayout &layout);

/// The pocket a ball whose centre is at (x, y) has entered: its centre is within the touch
/// distance of a rail line, inside that line's pocket mouth (with jaws: over its hole).
/// POOL_POCKET_NONE otherwise.
pool_pocket pocket_entered(const TableGeometry &geometry, double x, double y);

/// Whether a centre lies beyond a rail line (a ball that tunnelled through a cushion or flew
/// off), outside every pocket's mouth and shelf with jaws; false for NaN coordinates (the
/// engines report those as a non-finite state).
bool outside_table(const TableGeometry &geometry, double x, double y);

/// Distance from point p to a capsule's axis segment (m).
double distance_to_axis(const RailSegment &segment, const double p[3]);

} // namespace pool_plugin

#endif
