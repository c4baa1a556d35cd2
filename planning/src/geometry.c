// The table as aiming sees it: pockets' aiming points, the cushions' contact lines and mirror
// images (docs/physics.md "Frame, units, defaults" and "Predicting events").
#include <math.h>

#include "aim_internal.h"

// Widest angle between a ball's approach and a pocket's axis that is tried: a corner pocket takes
// a ball along a rail (45 degrees) and somewhat beyond; a side pocket's mouth, seen from a shallow
// angle, is narrower than a ball (Alciatore, TP 3.5 and 3.6).
#define AIM_CORNER_ACCEPT_DEG 60.0
#define AIM_SIDE_ACCEPT_DEG 55.0

aim_xy aim_sub(aim_xy a, aim_xy b) { return (aim_xy){a.x - b.x, a.y - b.y}; }
aim_xy aim_add_scaled(aim_xy a, aim_xy d, double s) { return (aim_xy){a.x + s * d.x, a.y + s * d.y}; }
double aim_dot(aim_xy a, aim_xy b) { return a.x * b.x + a.y * b.y; }
double aim_cross(aim_xy a, aim_xy b) { return a.x * b.y - a.y * b.x; }
double aim_norm(aim_xy a) { return hypot(a.x, a.y); }

aim_xy aim_unit(aim_xy a) {
	double n = aim_norm(a);
	return n > 0.0 ? (aim_xy){a.x / n, a.y / n} : (aim_xy){0.0, 0.0};
}

void aim_table_init(aim_table *t, const pool_sim_def *def) {
	const double L = def->table.length, W = def->table.width, R = def->params.ball_radius;
	t->length = L;
	t->width = W;
	t->radius = R;
	t->contact = pool_table_contact_distance(&def->table, R);
	const double s2 = sqrt(0.5), corner = cos(AIM_CORNER_ACCEPT_DEG * AIM_DEG), side = cos(AIM_SIDE_ACCEPT_DEG * AIM_DEG);
	// The middle of each mouth, on the line joining its jaws' points (a corner mouth opens
	// corner_mouth / sqrt 2 of each rail line): a path through it passes both jaws at the same
	// distance, whatever the angle it comes in at and whatever the pocket behind the mouth.
	const double m = def->table.corner_mouth * s2 / 2.0;
	t->target[POOL_POCKET_SW] = (aim_xy){m, m};
	t->target[POOL_POCKET_SE] = (aim_xy){L - m, m};
	t->target[POOL_POCKET_NW] = (aim_xy){m, W - m};
	t->target[POOL_POCKET_NE] = (aim_xy){L - m, W - m};
	t->target[POOL_POCKET_S] = (aim_xy){L / 2, 0.0};
	t->target[POOL_POCKET_N] = (aim_xy){L / 2, W};
	t->axis[POOL_POCKET_SW] = (aim_xy){-s2, -s2};
	t->axis[POOL_POCKET_SE] = (aim_xy){s2, -s2};
	t->axis[POOL_POCKET_NW] = (aim_xy){-s2, s2};
	t->axis[POOL_POCKET_NE] = (aim_xy){s2, s2};
	t->axis[POOL_POCKET_S] = (aim_xy){0.0, -1.0};
	t->axis[POOL_POCKET_N] = (aim_xy){0.0, 1.0};
	for (int p = 0; p < 6; ++p)
		t->accept[p] = p < 4 ? corner : side;
	// Cushion stretches a ball can bounce off: the rail minus each pocket's opening (a corner
	// mouth opens corner_mouth / sqrt 2 of each rail line, a side mouth side_mouth) and a ball's
	// radius more, so the bounce is on the straight cushion.
	const double c = def->table.corner_mouth * s2 + R, h = def->table.side_mouth / 2 + R;
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_NORTH; ++r) {
		t->spans[r] = 2;
		t->span_lo[r][0] = c, t->span_hi[r][0] = L / 2 - h;
		t->span_lo[r][1] = L / 2 + h, t->span_hi[r][1] = L - c;
	}
	for (int r = POOL_RAIL_WEST; r <= POOL_RAIL_EAST; ++r) {
		t->spans[r] = 1;
		t->span_lo[r][0] = c, t->span_hi[r][0] = W - c;
	}
}

/// The coordinate of the rail's contact line, and whether it is a line of constant y.
static double contact_line(const aim_table *t, pool_rail rail, bool *horizontal) {
	*horizontal = rail == POOL_RAIL_SOUTH || rail == POOL_RAIL_NORTH;
	switch (rail) {
	case POOL_RAIL_SOUTH: return t->contact;
	case POOL_RAIL_NORTH: return t->width - t->contact;
	case POOL_RAIL_WEST: return t->contact;
	default: return t->length - t->contact;
	}
}

aim_xy aim_mirror(const aim_table *t, pool_rail rail, aim_xy p) {
	bool horizontal;
	double line = contact_line(t, rail, &horizontal);
	return horizontal ? (aim_xy){p.x, 2 * line - p.y} : (aim_xy){2 * line - p.x, p.y};
}

bool aim_bounce(const aim_table *t, pool_rail rail, aim_xy a, aim_xy b, aim_xy *at) {
	bool horizontal;
	double line = contact_line(t, rail, &horizontal);
	double from = horizontal ? a.y : a.x, to = horizontal ? b.y : b.x;
	if ((from - line) * (to - line) >= 0.0)
		return false; // both on one side: no crossing
	double f = (line - from) / (to - from);
	*at = aim_add_scaled(a, aim_sub(b, a), f);
	double along = horizontal ? at->x : at->y;
	for (int k = 0; k < t->spans[rail]; ++k)
		if (along >= t->span_lo[rail][k] && along <= t->span_hi[rail][k])
			return true;
	return false;
}

bool aim_clear(const pool_ball_state *balls, int count, double radius, aim_xy a, aim_xy b, int skip1, int skip2) {
	const double reach = 2.0 * radius;
	aim_xy d = aim_sub(b, a);
	double length2 = aim_dot(d, d);
	for (int k = 0; k < count; ++k) {
		if (k == skip1 || k == skip2 || balls[k].motion == POOL_MOTION_POCKETED || balls[k].motion == POOL_MOTION_OFF_TABLE)
			continue;
		aim_xy p = aim_sub((aim_xy){balls[k].pos.x, balls[k].pos.y}, a);
		double f = length2 > 0.0 ? fmin(fmax(aim_dot(p, d) / length2, 0.0), 1.0) : 0.0;
		if (aim_norm(aim_add_scaled(p, d, -f)) < reach)
			return false;
	}
	return true;
}
