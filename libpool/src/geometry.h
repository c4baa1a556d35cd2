// Table geometry in one place: where a ball on the cloth meets each cushion nose, which pocket
// mouth a contact falls in, and the contact normal (docs/physics.md "Ball–cushion", "Pocket").
#ifndef POOL_GEOMETRY_H
#define POOL_GEOMETRY_H

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/table.h"

/// +1 for the north and east rails (reached by increasing the coordinate), -1 for south, west.
static inline double pool_rail_side(pool_rail rail) { return rail == POOL_RAIL_NORTH || rail == POOL_RAIL_EAST ? 1.0 : -1.0; }

/// 1 for the south and north rails (their coordinate is y, the motion along them x), else 0.
static inline int pool_rail_along_x(pool_rail rail) { return rail == POOL_RAIL_SOUTH || rail == POOL_RAIL_NORTH; }

/// Coordinate of a rail's nose line, the table's edge: y = 0 (south), W (north), x = 0 (west),
/// L (east).
static inline double pool_rail_nose_line(const pool_table_def *table, pool_rail rail) {
	return rail == POOL_RAIL_NORTH ? table->width : rail == POOL_RAIL_EAST ? table->length : 0.0;
}

/// Coordinate of a rail's contact line for a ball on the cloth: contact_distance inside its nose
/// line (the centre is pool_table_contact_distance from the nose there). Inline, like the three
/// above: every segment start asks them for four rails.
static inline double pool_rail_contact_line(const pool_table_def *table, double contact_distance, pool_rail rail) {
	return pool_rail_nose_line(table, rail) - pool_rail_side(rail) * contact_distance;
}

/// Pocket whose mouth contains a contact with `rail` at coordinate `along` (x on the south and
/// north rails, y on the west and east rails), or POOL_POCKET_NONE. A side pocket of mouth w
/// opens the interval of width w centred at x = L/2 on its rail; a corner pocket of mouth w
/// (jaw to jaw across the corner) opens the last w / sqrt(2) of each of its two rail lines.
pool_pocket pool_pocket_at(const pool_table_def *table, pool_rail rail, double along);

/// Contact normal of a ball centred at pos against a rail's nose (height h): from the nearest
/// point of the nose to the centre, normalised. The nose is its line outside the pocket mouths:
/// over a mouth its nearest point is the end of the nose at the mouth's edge.
pool_vec3 pool_cushion_normal(const pool_table_def *table, pool_vec3 pos, pool_rail rail);

/// The point of each piece of a rail's nose (the rail less its mouths: one piece on a short
/// rail, two on a long rail with side pockets) nearest to a ball centred at pos, into
/// points[0..2); returns how many pieces there are (0: the mouths cover the rail). A ball over a
/// mouth narrower than 2R touches both its ends at once (pool_cushion_normal takes the nearer only).
int pool_nose_pieces_nearest(const pool_table_def *table, pool_rail rail, pool_vec3 pos, pool_vec3 points[2]);

/// The nose's ends on a rail: the coordinates along the rail where a pocket mouth begins or ends
/// (the mouths' edges, within the rail), into ends[0..4); returns how many.
int pool_nose_ends(const pool_table_def *table, pool_rail rail, double ends[4]);

/// The pocket a ball centred at pos has fallen into on the cloth: past a rail's contact line
/// (contact_distance inside its nose line) inside that rail's pocket mouth (the first such
/// rail: south, north, west, east); POOL_POCKET_NONE when it is in no mouth past a line.
pool_pocket pool_table_pocket_past(const pool_table_def *table, double contact_distance, pool_vec3 pos);

/// The cushions a ball centred at pos on the cloth touches to within `gap` (its centre within
/// gap of their contact lines, or past them), with each one's horizontal unit direction from the
/// ball into the cushion; returns how many (at most 4), in rail order.
int pool_table_cushions_near(const pool_table_def *table, double contact_distance, pool_vec3 pos, double gap,
                             pool_rail rails[4], pool_vec3 into[4]);

/// m, the smallest gap between a ball of radius R centred at pos and a cushion nose outside the
/// pocket mouths (its distance to the nose line, less R; negative: inside the nose), and in
/// *rail that cushion (POOL_RAIL_NONE, INFINITY when the ball is over mouths only).
double pool_table_nose_gap(const pool_table_def *table, pool_vec3 pos, double R, pool_rail *rail);

#endif
