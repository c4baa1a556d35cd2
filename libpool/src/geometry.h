// Table geometry in one place: where a ball on the cloth meets each cushion nose, which pocket
// mouth a contact falls in, and the contact normal (PHYSICS.md "Ball–cushion", "Pocket").
#ifndef POOL_GEOMETRY_H
#define POOL_GEOMETRY_H

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/table.h"

/// Coordinate of a rail's contact line for a ball on the cloth: y for the south and north
/// rails, x for the west and east rails (the centre is pool_table_contact_distance from the nose
/// line there). Inline, like the two below: every segment start asks them for four rails.
static inline double pool_rail_contact_line(const pool_table_def *table, double contact_distance, pool_rail rail) {
	switch (rail) {
	case POOL_RAIL_SOUTH:
	case POOL_RAIL_WEST: return contact_distance;
	case POOL_RAIL_NORTH: return table->width - contact_distance;
	case POOL_RAIL_EAST: return table->length - contact_distance;
	default: return 0.0;
	}
}

/// +1 for the north and east rails (reached by increasing the coordinate), -1 for south, west.
static inline double pool_rail_side(pool_rail rail) { return rail == POOL_RAIL_NORTH || rail == POOL_RAIL_EAST ? 1.0 : -1.0; }

/// 1 for the south and north rails (their coordinate is y, the motion along them x), else 0.
static inline int pool_rail_along_x(pool_rail rail) { return rail == POOL_RAIL_SOUTH || rail == POOL_RAIL_NORTH; }

/// How far (m) the centre at pos lies beyond the nearest cushion contact line (negative inside).
double pool_outside_contact_lines(const pool_table_def *table, double contact_distance, pool_vec3 pos);

/// Pocket whose mouth contains a contact with `rail` at coordinate `along` (x on the south and
/// north rails, y on the west and east rails), or POOL_POCKET_NONE. A side pocket of mouth w
/// opens the interval of width w centred at x = L/2 on its rail; a corner pocket of mouth w
/// (jaw to jaw across the corner) opens the last w / sqrt(2) of each of its two rail lines.
pool_pocket pool_pocket_at(const pool_table_def *table, pool_rail rail, double along);

/// Contact normal of a ball centred at pos against a rail's nose (height h): from the nearest
/// point of the nose line to the centre, normalised.
pool_vec3 pool_cushion_normal(const pool_table_def *table, pool_vec3 pos, pool_rail rail);

#endif
