// Table geometry in one place (the rules are in geometry.h).
#include "geometry.h"

#include <math.h>

#include "table_shape.h"
#include "vec3.h"

double pool_table_contact_distance(const pool_table_def *table, double ball_radius) {
	if (!table)
		return NAN;
	const double d = table->cushion_height - ball_radius;
	return sqrt(ball_radius * ball_radius - d * d);
}

pool_pocket pool_pocket_at(const pool_table_def *table, pool_rail rail, double along) {
	const double L = table->length, W = table->width;
	const double corner = table->corner_mouth / sqrt(2.0);
	if (table->pockets == POOL_POCKETS_NONE)
		return POOL_POCKET_NONE;
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

/// The nose's pieces on a rail, [lo[k], hi[k]] along it: the rail less its mouths, [0, c] and
/// [len - c, len] at the corners and on the long rails [len/2 - w/2, len/2 + w/2]; returns how
/// many (mouths may overlap on a small table, and leave no nose at all).
static int nose_pieces(const pool_table_def *table, pool_rail rail, double lo[2], double hi[2]) {
	const double len = pool_rail_along_x(rail) ? table->length : table->width;
	const double corner = table->corner_mouth / sqrt(2.0);
	double a[2] = {corner, len}, b[2] = {len - corner, len};
	int pieces = 1;
	if (pool_rail_along_x(rail) && table->side_mouth > 0.0) {
		a[1] = 0.5 * (len + table->side_mouth);
		b[1] = b[0];
		b[0] = 0.5 * (len - table->side_mouth);
		pieces = 2;
	}
	int count = 0;
	for (int k = 0; k < pieces; ++k)
		if (a[k] < b[k]) {
			lo[count] = a[k];
			hi[count] = b[k];
			++count;
		}
	return count;
}

int pool_nose_ends(const pool_table_def *table, pool_rail rail, double ends[4]) {
	// Where what is left of the rail begins and ends (not the rail's own ends).
	const double len = pool_rail_along_x(rail) ? table->length : table->width;
	double lo[2], hi[2];
	const int pieces = nose_pieces(table, rail, lo, hi);
	int count = 0;
	for (int k = 0; k < pieces; ++k) {
		if (lo[k] > 0.0)
			ends[count++] = lo[k];
		if (hi[k] < len)
			ends[count++] = hi[k];
	}
	return count;
}

int pool_nose_pieces_nearest(const pool_table_def *table, pool_rail rail, pool_vec3 pos, pool_vec3 points[2]) {
	const int along_x = pool_rail_along_x(rail);
	const double along = along_x ? pos.x : pos.y;
	const double line = pool_rail_nose_line(table, rail);
	double lo[2], hi[2];
	const int pieces = nose_pieces(table, rail, lo, hi);
	for (int k = 0; k < pieces; ++k) {
		const double at = along < lo[k] ? lo[k] : along > hi[k] ? hi[k] : along;
		points[k] = along_x ? pool_v3(at, line, table->cushion_height) : pool_v3(line, at, table->cushion_height);
	}
	return pieces;
}

// The point of a rail's nose nearest to a ball centred at pos: on its line at pos's coordinate
// along the rail, or over a pocket mouth the nearest end of the nose; 0 when the rail has no
// nose left (its mouths cover it).
static int nose_nearest(const pool_table_def *table, pool_rail rail, pool_vec3 pos, pool_vec3 *point) {
	const int along_x = pool_rail_along_x(rail);
	const double along = along_x ? pos.x : pos.y;
	double at = along;
	if (pool_pocket_at(table, rail, along) != POOL_POCKET_NONE) {
		double ends[4], dist = INFINITY;
		const int n = pool_nose_ends(table, rail, ends);
		if (n == 0)
			return 0;
		for (int k = 0; k < n; ++k)
			if (fabs(ends[k] - along) < dist) {
				dist = fabs(ends[k] - along);
				at = ends[k];
			}
	}
	const double line = pool_rail_nose_line(table, rail);
	*point = along_x ? pool_v3(at, line, table->cushion_height) : pool_v3(line, at, table->cushion_height);
	return 1;
}

pool_vec3 pool_cushion_normal(const pool_table_def *table, pool_vec3 pos, pool_rail rail) {
	pool_vec3 nose;
	if (!nose_nearest(table, rail, pos, &nose)) { // (no nose on the rail: its line, as ever)
		nose = pos;
		nose.z = table->cushion_height;
		if (pool_rail_along_x(rail))
			nose.y = pool_rail_nose_line(table, rail);
		else
			nose.x = pool_rail_nose_line(table, rail);
	}
	pool_vec3 d = pool_v3_sub(pos, nose);
	return pool_v3_scale(d, 1.0 / pool_v3_len(d));
}

pool_pocket pool_table_pocket_past(const pool_table_def *table, double contact_distance, pool_vec3 pos) {
	// Pockets "jaws": over a hole (the slate ends there), wherever the contact lines are.
	if (table->pockets == POOL_POCKETS_JAWS)
		return pool_table_hole_at(table, pos.x, pos.y);
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_EAST; ++r) {
		const pool_rail rail = (pool_rail)r;
		const int along_x = pool_rail_along_x(rail);
		const double across = along_x ? pos.y : pos.x, along = along_x ? pos.x : pos.y;
		const double line = pool_rail_contact_line(table, contact_distance, rail);
		const pool_pocket pocket = pool_pocket_at(table, rail, along);
		if (pool_rail_side(rail) * (across - line) > 0.0 && pocket != POOL_POCKET_NONE)
			return pocket;
	}
	return POOL_POCKET_NONE;
}

int pool_table_cushions_near(const pool_table_def *table, double contact_distance, pool_vec3 pos, double gap,
                             pool_rail rails[4], pool_vec3 into[4]) {
	int count = 0;
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_EAST; ++r) {
		const pool_rail rail = (pool_rail)r;
		const int along_x = pool_rail_along_x(rail);
		const double side = pool_rail_side(rail);
		const double line = pool_rail_contact_line(table, contact_distance, rail);
		if (!(side * (line - (along_x ? pos.y : pos.x)) <= gap))
			continue;
		rails[count] = rail;
		into[count] = along_x ? pool_v3(0.0, side, 0.0) : pool_v3(side, 0.0, 0.0);
		++count;
	}
	return count;
}

double pool_table_nose_gap(const pool_table_def *table, pool_vec3 pos, double R, pool_rail *rail) {
	double best = INFINITY;
	*rail = POOL_RAIL_NONE;
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_EAST; ++r) {
		const pool_rail rr = (pool_rail)r;
		const int along_x = pool_rail_along_x(rr);
		if (pool_pocket_at(table, rr, along_x ? pos.x : pos.y) != POOL_POCKET_NONE)
			continue;
		const double in = pool_rail_side(rr) * (pool_rail_nose_line(table, rr) - (along_x ? pos.y : pos.x));
		const double up = pos.z - table->cushion_height;
		const double gap = sqrt(in * in + up * up) - R;
		if (gap < best) {
			best = gap;
			*rail = rr;
		}
	}
	return best;
}
