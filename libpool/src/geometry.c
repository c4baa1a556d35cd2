// Table geometry in one place (the rules are in geometry.h).
#include "geometry.h"

#include <math.h>

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

pool_vec3 pool_cushion_normal(const pool_table_def *table, pool_vec3 pos, pool_rail rail) {
	pool_vec3 nose = pos; // nearest point of the nose line: same coordinate along the rail
	nose.z = table->cushion_height;
	if (pool_rail_along_x(rail))
		nose.y = pool_rail_nose_line(table, rail);
	else
		nose.x = pool_rail_nose_line(table, rail);
	pool_vec3 d = pool_v3_sub(pos, nose);
	return pool_v3_scale(d, 1.0 / pool_v3_len(d));
}

pool_pocket pool_table_pocket_past(const pool_table_def *table, double contact_distance, pool_vec3 pos) {
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
