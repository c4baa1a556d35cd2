// The nose curve of a table (table_shape.h; docs/physics.md "Table geometry").
#include "table_shape.h"

#include <math.h>
#include <string.h>

#include "error.h"
#include "geometry.h"
#include "vec3.h"

// One cushion's end at a pocket: its virtual corner v, the unit direction t along the rail away
// from the pocket, the unit direction m into the cushion (out of the table).
typedef struct cushion_end {
	pool_rail rail;
	double vx, vy, tx, ty, mx, my;
} cushion_end;

// The two cushion ends of each pocket (sw, se, nw, ne, s, n), corner mouth a = w / sqrt 2 along
// each rail, side mouth s centred at L / 2.
static void cushion_ends(const pool_table_def *t, pool_pocket p, cushion_end e[2]) {
	const double L = t->length, W = t->width, a = t->corner_mouth / sqrt(2.0), s = 0.5 * t->side_mouth;
	const cushion_end ends[6][2] = {
		{{POOL_RAIL_SOUTH, a, 0, 1, 0, 0, -1}, {POOL_RAIL_WEST, 0, a, 0, 1, -1, 0}},
		{{POOL_RAIL_SOUTH, L - a, 0, -1, 0, 0, -1}, {POOL_RAIL_EAST, L, a, 0, 1, 1, 0}},
		{{POOL_RAIL_NORTH, a, W, 1, 0, 0, 1}, {POOL_RAIL_WEST, 0, W - a, 0, -1, -1, 0}},
		{{POOL_RAIL_NORTH, L - a, W, -1, 0, 0, 1}, {POOL_RAIL_EAST, L, W - a, 0, -1, 1, 0}},
		{{POOL_RAIL_SOUTH, 0.5 * L - s, 0, -1, 0, 0, -1}, {POOL_RAIL_SOUTH, 0.5 * L + s, 0, 1, 0, 0, -1}},
		{{POOL_RAIL_NORTH, 0.5 * L - s, W, -1, 0, 0, 1}, {POOL_RAIL_NORTH, 0.5 * L + s, W, 1, 0, 0, 1}},
	};
	e[0] = ends[p][0];
	e[1] = ends[p][1];
}

static double cross2(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Distance from (x, y) to the rectangle inside the rails' contact lines (0 inside).
static double outside_contact_lines(const pool_table_shape *sh, double x, double y) {
	const double dx = fmax(fmax(sh->dc - x, x - (sh->table.length - sh->dc)), 0.0);
	const double dy = fmax(fmax(sh->dc - y, y - (sh->table.width - sh->dc)), 0.0);
	return sqrt(dx * dx + dy * dy);
}

// Builds pocket p's facings and jaws (appended to the parts) and its hole; the along-rail
// coordinate of each jaw's tangent point on its nose goes to nose_end[c].
static pool_result build_pocket(pool_table_shape *sh, pool_pocket p, double nose_end[2], pool_error *error) {
	const pool_table_def *t = &sh->table;
	const int corner = p <= POOL_POCKET_NE;
	const char *kind = corner ? "corner" : "side";
	const double cut = corner ? t->corner_cut_angle : t->side_cut_angle;
	const double r = corner ? t->corner_jaw_radius : t->side_jaw_radius;
	const double shelf = corner ? t->corner_shelf : t->side_shelf;
	const double rh = corner ? t->corner_hole_radius : t->side_hole_radius;
	const double mouth = corner ? t->corner_mouth : t->side_mouth;
	const double R = sh->R;
	if (!(mouth > 2.0 * R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "table.%s_mouth: %g m is narrower than a ball (2 R = %g m)",
		                      kind, mouth, 2.0 * R);
	cushion_end e[2];
	cushion_ends(t, p, e);
	pool_pocket_shape *ps = &sh->pockets[p];
	ps->mx = 0.5 * (e[0].vx + e[1].vx);
	ps->my = 0.5 * (e[0].vy + e[1].vy);
	const double ox = e[0].mx + e[1].mx, oy = e[0].my + e[1].my, ol = sqrt(ox * ox + oy * oy);
	ps->ox = ox / ol;
	ps->oy = oy / ol;
	ps->hx = ps->mx + (shelf + rh) * ps->ox;
	ps->hy = ps->my + (shelf + rh) * ps->oy;
	ps->hole_radius = rh;
	ps->zone = sqrt((ps->hx - ps->mx) * (ps->hx - ps->mx) + (ps->hy - ps->my) * (ps->hy - ps->my)) + rh;
	const double tangent = r / tan(0.5 * cut); // from the virtual corner to each tangent point
	double throat[2][2];
	for (int c = 0; c < 2; ++c) {
		const cushion_end *ce = &e[c];
		const double fx = cos(cut) * ce->tx + sin(cut) * ce->mx, fy = cos(cut) * ce->ty + sin(cut) * ce->my;
		// The facing's normal out of the cushion: across the facing, away from the nose.
		double nx = -fy, ny = fx;
		if (nx * ce->tx + ny * ce->ty > 0.0)
			nx = -nx, ny = -ny;
		// Where the facing's line meets the hole: |v + s f - H|^2 = rh^2, the first crossing.
		const double qx = ce->vx - ps->hx, qy = ce->vy - ps->hy;
		const double b = fx * qx + fy * qy, disc = b * b - (qx * qx + qy * qy - rh * rh);
		if (!(disc > 0.0))
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
			                      "table.%s_hole_radius: the hole does not reach the facings (its edge %g m behind the mouth)",
			                      kind, shelf);
		const double s_hole = -b - sqrt(disc);
		if (!(s_hole > tangent))
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
			                      "table.%s_jaw_radius: %g m cannot be tangent to the facing before it meets the hole", kind, r);
		ps->ex[c] = ce->vx + s_hole * fx;
		ps->ey[c] = ce->vy + s_hole * fy;
		// The facing at the depth of the hole's near edge, for the throat's width.
		const double s_shelf = shelf / (fx * ps->ox + fy * ps->oy);
		throat[c][0] = ce->vx + s_shelf * fx;
		throat[c][1] = ce->vy + s_shelf * fy;
		// The facing: from its tangent point to the hole.
		pool_nose_part *fp = &sh->parts[sh->n_parts];
		memset(fp, 0, sizeof *fp);
		fp->kind = POOL_NOSE_LINE;
		fp->part = POOL_PART_FACING;
		fp->rail = ce->rail;
		fp->pocket = p;
		fp->ax = ce->vx + tangent * fx;
		fp->ay = ce->vy + tangent * fy;
		fp->dx = fx;
		fp->dy = fy;
		fp->nx = nx;
		fp->ny = ny;
		fp->length = s_hole - tangent;
		fp->free_end = 1;
		ps->parts[2 * c] = sh->n_parts++;
		// The jaw: the circle tangent to the nose and the facing, inside the cushion.
		pool_nose_part *jp = &sh->parts[sh->n_parts];
		memset(jp, 0, sizeof *jp);
		jp->kind = POOL_NOSE_ARC;
		jp->part = POOL_PART_JAW;
		jp->rail = ce->rail;
		jp->pocket = p;
		jp->ax = ce->vx + tangent * ce->tx + r * ce->mx;
		jp->ay = ce->vy + tangent * ce->ty + r * ce->my;
		jp->length = r;
		double e0x = -ce->mx, e0y = -ce->my, e1x = nx, e1y = ny; // the nose's normal, then the facing's
		if (cross2(e0x, e0y, e1x, e1y) < 0.0) {
			double sx = e0x, sy = e0y;
			e0x = e1x, e0y = e1y, e1x = sx, e1y = sy;
		}
		jp->e0x = e0x, jp->e0y = e0y, jp->e1x = e1x, jp->e1y = e1y;
		ps->parts[2 * c + 1] = sh->n_parts++;
		nose_end[c] = pool_rail_along_x(ce->rail) ? ce->vx + tangent * ce->tx : ce->vy + tangent * ce->ty;
		// The zone holds the jaw and the facing widened by R.
		const double dj = sqrt((jp->ax - ps->mx) * (jp->ax - ps->mx) + (jp->ay - ps->my) * (jp->ay - ps->my)) + r + R;
		const double df = fmax(sqrt((fp->ax - ps->mx) * (fp->ax - ps->mx) + (fp->ay - ps->my) * (fp->ay - ps->my)),
		                       sqrt((ps->ex[c] - ps->mx) * (ps->ex[c] - ps->mx) + (ps->ey[c] - ps->my) * (ps->ey[c] - ps->my))) + R;
		ps->zone = fmax(ps->zone, fmax(dj, df));
	}
	const double width = sqrt((throat[0][0] - throat[1][0]) * (throat[0][0] - throat[1][0]) +
	                          (throat[0][1] - throat[1][1]) * (throat[0][1] - throat[1][1]));
	if (!(width > 2.0 * R))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "table.%s_cut_angle: the facings are %g m apart at the hole, narrower than a ball (2 R = %g m)",
		                      kind, width, 2.0 * R);
	ps->hole_inside = outside_contact_lines(sh, ps->hx, ps->hy) < rh;
	return POOL_OK;
}

static void add_nose(pool_table_shape *sh, pool_rail rail, double lo, double hi, int slot) {
	pool_nose_part *np = &sh->parts[sh->n_parts];
	memset(np, 0, sizeof *np);
	np->kind = POOL_NOSE_LINE;
	np->part = POOL_PART_NOSE;
	np->rail = rail;
	np->pocket = POOL_POCKET_NONE;
	const double line = pool_rail_nose_line(&sh->table, rail), side = pool_rail_side(rail);
	if (pool_rail_along_x(rail)) {
		np->ax = lo, np->ay = line, np->dx = 1.0, np->nx = 0.0, np->ny = -side;
	} else {
		np->ax = line, np->ay = lo, np->dy = 1.0, np->nx = -side, np->ny = 0.0;
	}
	np->length = hi - lo;
	sh->rail_segments[rail][slot] = sh->n_parts++;
}

pool_result pool_table_shape_build(const pool_table_def *table, double R, pool_table_shape *sh, pool_error *error) {
	memset(sh, 0, sizeof *sh);
	sh->table = *table;
	sh->R = R;
	sh->dc = pool_table_contact_distance(table, R);
	for (int r = 0; r < 4; ++r)
		sh->rail_segments[r][0] = sh->rail_segments[r][1] = -1;
	if (table->pockets == POOL_POCKETS_NONE) {
		// A carom table: each rail one nose segment from corner to corner.
		add_nose(sh, POOL_RAIL_SOUTH, 0.0, table->length, 0);
		add_nose(sh, POOL_RAIL_NORTH, 0.0, table->length, 0);
		add_nose(sh, POOL_RAIL_WEST, 0.0, table->width, 0);
		add_nose(sh, POOL_RAIL_EAST, 0.0, table->width, 0);
		return POOL_OK;
	}
	if (table->pockets != POOL_POCKETS_JAWS)
		return POOL_OK;
	// Nose segments first (at most 6), then the pockets' parts. A mouth of 0 means no such
	// pockets: the corner is the two rails' meeting, a long rail without a side pocket one
	// nose segment.
	const int corners = table->corner_mouth > 0.0, sides = table->side_mouth > 0.0;
	sh->n_parts = 2 + 2 * sides + 2; // the noses' slots: south, north (one or two each), west, east
	double ends[6][2] = {{0.0, 0.0}, {table->length, 0.0}, {0.0, table->width}, {table->length, table->width},
	                     {0.0, 0.0}, {0.0, 0.0}};
	for (int p = 0; p < 6; ++p) {
		if (p <= POOL_POCKET_NE ? !corners : !sides)
			continue;
		const pool_result r = build_pocket(sh, (pool_pocket)p, ends[p], error);
		if (r)
			return r;
		sh->has_pocket[p] = 1;
	}
	const int count = sh->n_parts;
	sh->n_parts = 0;
	// South: sw .. s (west side), s (east side) .. se (or sw .. se); north likewise; west sw ..
	// nw; east se .. ne.
	struct nose {
		pool_rail rail;
		double lo, hi;
		const char *field;
	} noses[6];
	int nn = 0;
	const pool_rail longs[2] = {POOL_RAIL_SOUTH, POOL_RAIL_NORTH};
	const pool_pocket lo_corner[2] = {POOL_POCKET_SW, POOL_POCKET_NW}, hi_corner[2] = {POOL_POCKET_SE, POOL_POCKET_NE};
	const pool_pocket side[2] = {POOL_POCKET_S, POOL_POCKET_N};
	for (int k = 0; k < 2; ++k) {
		if (sides) {
			noses[nn++] = (struct nose){longs[k], ends[lo_corner[k]][0], ends[side[k]][0], "table.length"};
			noses[nn++] = (struct nose){longs[k], ends[side[k]][1], ends[hi_corner[k]][0], "table.length"};
		} else {
			noses[nn++] = (struct nose){longs[k], ends[lo_corner[k]][0], ends[hi_corner[k]][0], "table.length"};
		}
	}
	noses[nn++] = (struct nose){POOL_RAIL_WEST, corners ? ends[POOL_POCKET_SW][1] : 0.0, corners ? ends[POOL_POCKET_NW][1] : table->width, "table.width"};
	noses[nn++] = (struct nose){POOL_RAIL_EAST, corners ? ends[POOL_POCKET_SE][1] : 0.0, corners ? ends[POOL_POCKET_NE][1] : table->width, "table.width"};
	for (int k = 0; k < nn; ++k) {
		if (!(noses[k].hi > noses[k].lo))
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "%s: too short for its pockets' mouths and jaws",
			                      noses[k].field);
		const int slot = sh->rail_segments[noses[k].rail][0] < 0 ? 0 : 1;
		add_nose(sh, noses[k].rail, noses[k].lo, noses[k].hi, slot);
	}
	sh->n_parts = count;
	// Along each rail, the pocket of each gap between (and beyond) its nose segments.
	for (int r = 0; r < 4; ++r)
		for (int g = 0; g < 3; ++g)
			sh->gap_pocket[r][g] = POOL_POCKET_NONE;
	for (int k = 0; k < 2; ++k) {
		int g = 0;
		sh->gap_pocket[longs[k]][g++] = corners ? lo_corner[k] : POOL_POCKET_NONE;
		if (sides)
			sh->gap_pocket[longs[k]][g++] = side[k];
		sh->gap_pocket[longs[k]][g] = corners ? hi_corner[k] : POOL_POCKET_NONE;
	}
	sh->gap_pocket[POOL_RAIL_WEST][0] = corners ? POOL_POCKET_SW : POOL_POCKET_NONE;
	sh->gap_pocket[POOL_RAIL_WEST][1] = corners ? POOL_POCKET_NW : POOL_POCKET_NONE;
	sh->gap_pocket[POOL_RAIL_EAST][0] = corners ? POOL_POCKET_SE : POOL_POCKET_NONE;
	sh->gap_pocket[POOL_RAIL_EAST][1] = corners ? POOL_POCKET_NE : POOL_POCKET_NONE;
	return POOL_OK;
}

int pool_shape_span(const pool_table_shape *sh, pool_rail rail, double along, pool_pocket *pocket) {
	int gap = 0;
	for (int slot = 0; slot < 2; ++slot) {
		const int k = sh->rail_segments[rail][slot];
		if (k < 0)
			break;
		const pool_nose_part *np = &sh->parts[k];
		const double lo = pool_rail_along_x(rail) ? np->ax : np->ay;
		if (along < lo)
			break;
		if (along <= lo + np->length) {
			*pocket = POOL_POCKET_NONE;
			return k;
		}
		gap = slot + 1;
	}
	*pocket = sh->gap_pocket[rail][gap];
	return -1;
}

int pool_shape_in_span(const pool_table_shape *sh, int k, pool_vec3 pos) {
	const pool_nose_part *np = &sh->parts[k];
	const double wx = pos.x - np->ax, wy = pos.y - np->ay;
	if (np->kind == POOL_NOSE_LINE) {
		const double u = wx * np->dx + wy * np->dy;
		return u >= 0.0 && u <= np->length;
	}
	return cross2(np->e0x, np->e0y, wx, wy) >= 0.0 && cross2(wx, wy, np->e1x, np->e1y) >= 0.0;
}

pool_vec3 pool_shape_nearest(const pool_table_shape *sh, int k, pool_vec3 pos) {
	const pool_nose_part *np = &sh->parts[k];
	pool_vec3 q;
	q.z = sh->table.cushion_height;
	if (np->kind == POOL_NOSE_LINE) {
		double u = (pos.x - np->ax) * np->dx + (pos.y - np->ay) * np->dy;
		u = u < 0.0 ? 0.0 : u > np->length ? np->length : u;
		q.x = np->ax + u * np->dx;
		q.y = np->ay + u * np->dy;
		return q;
	}
	double wx = pos.x - np->ax, wy = pos.y - np->ay;
	// Outside the span, the nearer end of the arc.
	if (cross2(np->e0x, np->e0y, wx, wy) < 0.0 || cross2(wx, wy, np->e1x, np->e1y) < 0.0) {
		const double d0 = (wx - np->length * np->e0x) * (wx - np->length * np->e0x) + (wy - np->length * np->e0y) * (wy - np->length * np->e0y);
		const double d1 = (wx - np->length * np->e1x) * (wx - np->length * np->e1x) + (wy - np->length * np->e1y) * (wy - np->length * np->e1y);
		wx = d0 <= d1 ? np->e0x : np->e1x;
		wy = d0 <= d1 ? np->e0y : np->e1y;
	} else {
		const double w = sqrt(wx * wx + wy * wy);
		if (w > 0.0)
			wx /= w, wy /= w;
		else
			wx = np->e0x, wy = np->e0y;
	}
	q.x = np->ax + np->length * wx;
	q.y = np->ay + np->length * wy;
	return q;
}

pool_vec3 pool_shape_normal(const pool_table_shape *sh, int k, pool_vec3 pos) {
	const pool_vec3 d = pool_v3_sub(pos, pool_shape_nearest(sh, k, pos));
	const double len = pool_v3_len(d);
	if (len > 0.0)
		return pool_v3_scale(d, 1.0 / len);
	const pool_nose_part *np = &sh->parts[k];
	return pool_v3(np->kind == POOL_NOSE_LINE ? np->nx : np->e0x, np->kind == POOL_NOSE_LINE ? np->ny : np->e0y, 0.0);
}

pool_pocket pool_shape_hole_at(const pool_table_shape *sh, double x, double y) {
	if (sh->table.pockets != POOL_POCKETS_JAWS)
		return POOL_POCKET_NONE;
	for (int p = 0; p < 6; ++p) {
		const pool_pocket_shape *ps = &sh->pockets[p];
		if (!sh->has_pocket[p])
			continue;
		const double dx = x - ps->hx, dy = y - ps->hy;
		if (dx * dx + dy * dy < ps->hole_radius * ps->hole_radius)
			return (pool_pocket)p;
	}
	return POOL_POCKET_NONE;
}

pool_pocket pool_table_hole_at(const pool_table_def *t, double x, double y) {
	if (t->pockets != POOL_POCKETS_JAWS)
		return POOL_POCKET_NONE;
	for (int p = 0; p < 6; ++p) {
		cushion_end e[2];
		cushion_ends(t, (pool_pocket)p, e);
		const int corner = p <= POOL_POCKET_NE;
		if (!((corner ? t->corner_mouth : t->side_mouth) > 0.0))
			continue; // no such pockets
		const double rh = corner ? t->corner_hole_radius : t->side_hole_radius;
		const double back = (corner ? t->corner_shelf : t->side_shelf) + rh;
		const double ox = e[0].mx + e[1].mx, oy = e[0].my + e[1].my, ol = sqrt(ox * ox + oy * oy);
		const double hx = 0.5 * (e[0].vx + e[1].vx) + back * ox / ol, hy = 0.5 * (e[0].vy + e[1].vy) + back * oy / ol;
		if ((x - hx) * (x - hx) + (y - hy) * (y - hy) < rh * rh)
			return (pool_pocket)p;
	}
	return POOL_POCKET_NONE;
}

double pool_shape_distance(const pool_table_shape *sh, pool_vec3 pos, int *part) {
	double best = INFINITY;
	int which = -1;
	for (int k = 0; k < sh->n_parts; ++k) {
		const double d = pool_v3_len(pool_v3_sub(pos, pool_shape_nearest(sh, k, pos)));
		if (d < best)
			best = d, which = k;
	}
	if (part)
		*part = which;
	return best;
}

int pool_shape_on_cloth(const pool_table_shape *sh, double x, double y, double tol) {
	if (outside_contact_lines(sh, x, y) <= tol)
		return 1;
	if (sh->table.pockets != POOL_POCKETS_JAWS)
		return 0;
	// Beyond a contact line: in a pocket's mouth (not beyond a nose segment), clear of the parts,
	// not over a hole.
	for (int r = 0; r < 4; ++r) {
		const pool_rail rail = (pool_rail)r;
		const double across = pool_rail_along_x(rail) ? y : x, along = pool_rail_along_x(rail) ? x : y;
		const double line = pool_rail_contact_line(&sh->table, sh->dc, rail);
		pool_pocket pocket;
		if (pool_rail_side(rail) * (line - across) < -tol && pool_shape_span(sh, rail, along, &pocket) >= 0)
			return 0;
	}
	const pool_vec3 p = pool_v3(x, y, sh->R);
	return pool_shape_distance(sh, p, NULL) >= sh->R - tol && pool_shape_hole_at(sh, x, y) == POOL_POCKET_NONE;
}
