// The nose curve of a table (docs/physics.md "Table geometry"): with pockets "jaws", per rail its
// nose segments, per pocket its two facings, two jaws and its hole; built once from the table
// and the ball radius when a simulation is created, and refused with a message naming the field
// when it cannot be built. A carom table ("none") is four nose segments from corner to corner;
// the thesis model ("mouth_lines") keeps the four nose lines of geometry.h, and its shape only
// records the table.
#ifndef POOL_TABLE_SHAPE_H
#define POOL_TABLE_SHAPE_H

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/table.h"

/// Parts of a nose curve: 6 nose segments, and per pocket 2 facings and 2 jaws.
#define POOL_SHAPE_MAX_PARTS 30

/// Straight part (a nose segment or a facing) or circular arc (a jaw).
typedef enum pool_nose_kind { POOL_NOSE_LINE = 0, POOL_NOSE_ARC = 1 } pool_nose_kind;

/// One part of the nose curve, in the table's plane at the nose height.
typedef struct pool_nose_part {
	pool_nose_kind kind;
	pool_cushion_part part; ///< nose, facing or jaw
	pool_rail rail;         ///< the rail whose cushion it ends
	pool_pocket pocket;     ///< the pocket of a facing or jaw; POOL_POCKET_NONE for a nose segment
	double ax, ay;          ///< m, a line's start; an arc's centre
	double dx, dy;          ///< a line's unit direction from its start
	double nx, ny;          ///< a line's unit normal towards the ball's side (out of the cushion)
	double length;          ///< m, a line's length; an arc's radius
	double e0x, e0y, e1x, e1y; ///< an arc's span: unit directions from its centre, e0 to e1 counter-clockwise
	int free_end;           ///< a line whose end (a + length d) is a free corner: a facing where it meets the hole
} pool_nose_part;

/// One pocket: its mouth, its hole and the parts that bound it.
typedef struct pool_pocket_shape {
	double mx, my;      ///< m, middle of the mouth line
	double ox, oy;      ///< unit axis, out of the table
	double hx, hy;      ///< m, the hole's centre
	double hole_radius; ///< m
	double zone;        ///< m, radius about (mx, my) holding its parts widened by R and its hole
	double ex[2], ey[2]; ///< m, where the two facings meet the hole (the throat's end)
	int hole_inside;    ///< the hole reaches inside the rails' contact lines
	int parts[4];       ///< its facings and jaws (indices into pool_table_shape.parts)
} pool_pocket_shape;

/// A table's nose curve for a ball of radius R.
typedef struct pool_table_shape {
	pool_table_def table; ///< the table it was built from
	double R;             ///< m, ball radius
	double dc;            ///< m, horizontal centre distance from a nose at contact on the cloth
	int n_parts;
	pool_nose_part parts[POOL_SHAPE_MAX_PARTS]; ///< nose segments first (by rail), then each pocket's
	pool_pocket_shape pockets[6];               ///< by pool_pocket
	int has_pocket[6];       ///< the pocket exists (a mouth of 0 means none of its kind)
	int rail_segments[4][2]; ///< per rail, its nose segments in order along it (-1: none)
	pool_pocket gap_pocket[4][3]; ///< per rail, the pocket before, between and after its segments
} pool_table_shape;

/// Builds the shape (with pockets "jaws": the nose curve; otherwise just the table). Refuses
/// geometry that cannot be built: a jaw that cannot be tangent to its nose and its facing within
/// them, a facing that never meets the hole, a mouth or throat narrower than a ball.
pool_result pool_table_shape_build(const pool_table_def *table, double R, pool_table_shape *shape, pool_error *error);

/// Along rail `rail` at coordinate `along` (x on south and north, y on west and east): the nose
/// segment whose span holds it (its part index), or -1 with *pocket the pocket whose mouth it is in.
int pool_shape_span(const pool_table_shape *shape, pool_rail rail, double along, pool_pocket *pocket);

/// 1 when the nearest point of part k to pos (in plan) lies within the part, not at an end.
int pool_shape_in_span(const pool_table_shape *shape, int k, pool_vec3 pos);

/// The nearest point of part k's nose (at the nose height) to pos, within the part.
pool_vec3 pool_shape_nearest(const pool_table_shape *shape, int k, pool_vec3 pos);

/// Unit normal of a contact of a ball centred at pos with part k: from its nearest point to pos.
pool_vec3 pool_shape_normal(const pool_table_shape *shape, int k, pool_vec3 pos);

/// The pocket whose hole holds the point (x, y) of the cloth, or POOL_POCKET_NONE.
pool_pocket pool_shape_hole_at(const pool_table_shape *shape, double x, double y);

/// The same from the table alone (no shape built): its holes' centres from the mouths, shelves
/// and hole radii; POOL_POCKET_NONE unless the pocket model is "jaws".
pool_pocket pool_table_hole_at(const pool_table_def *table, double x, double y);

/// Distance (m) from the point (x, y, z) to the nose curve (every part), and the part it is
/// nearest to (*part, may be NULL).
double pool_shape_distance(const pool_table_shape *shape, pool_vec3 pos, int *part);

/// 1 when a ball centred at (x, y) on the cloth is on the table: inside the rails' contact lines,
/// or in a pocket's mouth clear of its parts (within tol) and not over its hole.
int pool_shape_on_cloth(const pool_table_shape *shape, double x, double y, double tol);

#endif
