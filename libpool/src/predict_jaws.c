// Contacts with the nose curve of pockets "jaws" (docs/physics.md "Table geometry"), on the cloth
// and in flight, each part's gap polynomial handed to the one contact rule (contact.h): a nose
// segment or facing is its line within its span, a jaw its circle within its arc, a hole its edge.
// A root whose contact point lies outside the part (on the line's or circle's extension: a ghost)
// is no contact, and the search goes on past it.
#include <float.h>
#include <math.h>

#include "contact.h"
#include "geometry.h"
#include "poly_roots.h"
#include "predict.h"
#include "table_shape.h"
#include "vec3.h"

/// Relative step past a ghost root before the next root is searched (contact.c's root step).
#define JAWS_GHOST_STEP 1e-13
/// Ghost roots passed at most per part: a quartic has four roots, a degree-8 gap eight.
#define JAWS_MAX_GHOSTS 8
/// m, how far outside a part's span a contact point may fall and still count (rounding at the
/// tangent point where a nose meets its jaw: either part takes that contact).
#define JAWS_SPAN_SLACK 1e-12

// A ball's path p(t) = p + v t + a t^2 (a: half the acceleration).
typedef struct path {
	pool_vec3 p, v, a;
} path;

static pool_vec3 path_at(const path *q, double t) { return pool_v3_madd(pool_v3_madd(q->p, t, q->v), t * t, q->a); }

// The contact point of a ball at pos on part np is within the part.
static int in_span(const pool_nose_part *np, pool_vec3 pos) {
	const double wx = pos.x - np->ax, wy = pos.y - np->ay;
	if (np->kind == POOL_NOSE_LINE) {
		const double u = wx * np->dx + wy * np->dy;
		return u >= -JAWS_SPAN_SLACK && u <= np->length + JAWS_SPAN_SLACK;
	}
	const double w = sqrt(wx * wx + wy * wy);
	return np->e0x * wy - np->e0y * wx >= -JAWS_SPAN_SLACK * w && wx * np->e1y - wy * np->e1x >= -JAWS_SPAN_SLACK * w;
}

// Earliest tau in [0, T] at which the gap g (degree <= 4) closes with its contact point on part
// np: the contact rule where the ball starts on the part within the touching band, the first
// falling root elsewhere, and past every ghost root the next one.
static double part_contact(const pool_nose_part *np, const pool_contact_gap *g, const path *q, double T) {
	double t;
	if (g->gap > POOL_TOUCH_TOLERANCE)
		t = T > 0.0 ? pool_contact_first_falling_root(g->f, 4, T) : INFINITY;
	else if (in_span(np, q->p))
		t = pool_contact_next(g, T);
	else
		t = pool_contact_first_falling_root(g->f, 4, T);
	for (int i = 0; t <= T && i < JAWS_MAX_GHOSTS; ++i) {
		if (in_span(np, path_at(q, t)))
			return t;
		t = pool_contact_first_falling_root_from(g->f, 4, t + JAWS_GHOST_STEP * (1.0 + t), T);
	}
	return INFINITY;
}

// The gap |w|^2 - d^2 of a point following w(t) = w + v t + a t^2 (3D or in plan) from a point,
// at contact distance d, with the rates of its distance |w| for the contact rule.
static pool_contact_gap sphere_gap(const path *w, double d) {
	pool_contact_gap g;
	const double ww = pool_v3_dot(w->p, w->p), wv = pool_v3_dot(w->p, w->v), vv = pool_v3_dot(w->v, w->v);
	g.f[0] = ww - d * d;
	g.f[1] = 2.0 * wv;
	g.f[2] = vv + 2.0 * pool_v3_dot(w->p, w->a);
	g.f[3] = 2.0 * pool_v3_dot(w->v, w->a);
	g.f[4] = pool_v3_dot(w->a, w->a);
	const double dist = sqrt(ww);
	g.gap = dist - d;
	g.speed = dist > 0.0 ? -wv / dist : 0.0;
	// (the curvature from v's part across w, never negative: pool_v3_across2)
	g.accel = dist > 0.0 ? -(pool_v3_across2(w->v, w->p) + 2.0 * pool_v3_dot(w->p, w->a)) / dist : 0.0;
	return g;
}

// The gap s(t) - d of a point at signed distance s(t) = s0 + s1 t + s2 t^2 from a line.
static pool_contact_gap line_gap(double s0, double s1, double s2, double d) {
	pool_contact_gap g;
	g.f[0] = s0 - d;
	g.f[1] = s1;
	g.f[2] = s2;
	g.f[3] = g.f[4] = 0.0;
	g.gap = s0 - d;
	g.speed = -s1;
	g.accel = -2.0 * s2;
	return g;
}

// The path relative to point (x, y, z).
static path relative(const path *q, double x, double y, double z) {
	path w = *q;
	w.p = pool_v3_sub(q->p, pool_v3(x, y, z));
	return w;
}

// Ball on the cloth against part k: its line at dc, or its jaw's axis at r + dc.
static double cloth_part(const pool_table_shape *sh, int k, const path *q, double T) {
	const pool_nose_part *np = &sh->parts[k];
	path w = relative(q, np->ax, np->ay, q->p.z);
	w.p.z = w.v.z = w.a.z = 0.0;
	if (np->kind == POOL_NOSE_LINE) {
		const double s0 = w.p.x * np->nx + w.p.y * np->ny, s1 = w.v.x * np->nx + w.v.y * np->ny;
		const double s2 = w.a.x * np->nx + w.a.y * np->ny;
		// Apart by more than the path can close over the window: no contact, no root finder.
		if (s0 - sh->dc > POOL_TOUCH_TOLERANCE && pool_line_reach(s1, 2.0 * s2, T) < s0 - sh->dc)
			return INFINITY;
		const pool_contact_gap g = line_gap(s0, s1, s2, sh->dc);
		if (g.gap > POOL_TOUCH_TOLERANCE && pool_contact_quadratic_apart(g.f[0], g.f[1], g.f[2], T))
			return INFINITY; // clear of the line over the window
		return part_contact(np, &g, q, T);
	}
	const pool_contact_gap g = sphere_gap(&w, np->length + sh->dc);
	return part_contact(np, &g, q, T);
}

// First tau in [0, T] at which a centre following q enters the circle (cx, cy, radius r) in plan
// (0 when it is inside already).
static double enter_circle(const path *q, double cx, double cy, double r, double T) {
	path w = relative(q, cx, cy, q->p.z);
	w.p.z = w.v.z = w.a.z = 0.0;
	const pool_contact_gap g = sphere_gap(&w, r);
	if (g.f[0] <= 0.0)
		return 0.0;
	return T > 0.0 ? pool_contact_first_falling_root(g.f, 4, T) : INFINITY;
}

static void found(double t, double *best, pool_event_type kind, pool_rail rail, pool_pocket pocket, int part,
                  pool_event_type *out_kind, pool_site *site) {
	if (!(t < *best))
		return;
	*best = t;
	*out_kind = kind;
	site->rail = rail;
	site->pocket = pocket;
	site->part = part;
}

double pool_predict_cushion_jaws(const pool_table_shape *sh, const pool_ball_state *s, pool_vec3 acc, double T,
                                 pool_event_type *kind, pool_site *site) {
	const path q = {s->pos, s->vel, pool_v3_scale(acc, 0.5)};
	double best = INFINITY;
	*kind = POOL_EVENT_BALL_CUSHION;
	site->rail = POOL_RAIL_NONE;
	site->pocket = POOL_POCKET_NONE;
	site->part = -1;
	int involved[6] = {0, 0, 0, 0, 0, 0};
	for (int p = 0; p < 6; ++p)
		involved[p] = sh->pockets[p].hole_inside;
	// The rails' contact lines: a crossing within a nose segment's span is a contact with it;
	// elsewhere the ball enters a pocket's mouth, whose parts are searched below. Every part of
	// a pocket lies beyond the contact lines, so a ball reaches none without crossing one first
	// in that pocket's mouth, or starting there. A line out of reach over the whole segment is out
	// of reach over the window: each axis' reach over T, taken once, leaves most rails out at once.
	const double reach_x = pool_line_reach(s->vel.x, acc.x, T), reach_y = pool_line_reach(s->vel.y, acc.y, T);
	for (int r = 0; r < 4; ++r) {
		const pool_rail rail = (pool_rail)r;
		const int along_x = pool_rail_along_x(rail);
		const double side = pool_rail_side(rail), line = pool_rail_contact_line(&sh->table, sh->dc, rail);
		const double q0 = along_x ? s->pos.y : s->pos.x, vq = along_x ? s->vel.y : s->vel.x, aq = along_x ? acc.y : acc.x;
		const double gap = side * (line - q0);
		if (gap > POOL_TOUCH_TOLERANCE && (along_x ? reach_y : reach_x) < gap)
			continue;
		const pool_contact_gap g = line_gap(gap, -side * vq, -0.5 * side * aq, 0.0);
		const double window = fmin(T, best);
		if (gap > POOL_TOUCH_TOLERANCE && pool_line_reach(vq, aq, window) < gap)
			continue;
		// Nor a line the ball stays well clear of over the window (its least gap there): no
		// crossing, in a mouth or not.
		if (g.gap > POOL_TOUCH_TOLERANCE && pool_contact_quadratic_apart(g.f[0], g.f[1], g.f[2], window))
			continue;
		pool_pocket pocket = POOL_POCKET_NONE;
		// Beyond the line: in a pocket's mouth (or, within a nose's span, inside its cushion).
		const int start = g.gap < -POOL_TOUCH_TOLERANCE ? pool_shape_span(sh, rail, along_x ? s->pos.x : s->pos.y, &pocket) : 0;
		double t;
		if (g.gap < -POOL_TOUCH_TOLERANCE && start < 0 && pocket != POOL_POCKET_NONE) {
			involved[pocket] = 1; // in that pocket's mouth
			t = pool_contact_first_falling_root(g.f, 2, window);
		} else {
			t = pool_contact_next(&g, window);
		}
		for (int i = 0; t <= window && i < 3; ++i) {
			const pool_vec3 at = path_at(&q, t);
			const int k = pool_shape_span(sh, rail, along_x ? at.x : at.y, &pocket);
			if (k >= 0) {
				found(t, &best, POOL_EVENT_BALL_CUSHION, rail, POOL_POCKET_NONE, k, kind, site);
				break;
			}
			if (pocket != POOL_POCKET_NONE)
				involved[pocket] = 1;
			t = pool_contact_first_falling_root_from(g.f, 2, t + JAWS_GHOST_STEP * (1.0 + t), window);
		}
	}
	for (int p = 0; p < 6; ++p) {
		if (!involved[p])
			continue;
		const pool_pocket_shape *ps = &sh->pockets[p];
		for (int j = 0; j < 4; ++j) {
			const int k = ps->parts[j];
			const double t = cloth_part(sh, k, &q, fmin(T, best));
			found(t, &best, POOL_EVENT_BALL_CUSHION, sh->parts[k].rail, (pool_pocket)p, k, kind, site);
		}
		const double t = enter_circle(&q, ps->hx, ps->hy, ps->hole_radius, fmin(T, best));
		found(t, &best, POOL_EVENT_POCKET, POOL_RAIL_NONE, (pool_pocket)p, -1, kind, site);
	}
	return best;
}

// A linked ball's hole: the step's LCP holds it off every part of the nose curve, but nothing
// but this holds it up over a hole. Every pocket's hole is searched, whatever the parts: a
// part contact found first (the ball is pressed on a facing or a jaw as it slides into the
// hole) is the LCP's, no event, and must not hide the hole behind it.
double pool_predict_hole_jaws(const pool_table_shape *sh, const pool_ball_state *s, pool_vec3 acc, double T,
                              pool_pocket *pocket) {
	const path q = {s->pos, s->vel, pool_v3_scale(acc, 0.5)};
	double best = INFINITY;
	*pocket = POOL_POCKET_NONE;
	for (int p = 0; p < 6; ++p) {
		if (!sh->has_pocket[p])
			continue;
		const pool_pocket_shape *ps = &sh->pockets[p];
		// Out of reach within the window (plan distance to the edge beyond the path's bound).
		const double reach = (hypot(q.v.x, q.v.y) + hypot(q.a.x, q.a.y) * T) * T * (1.0 + 1e-12);
		if (hypot(q.p.x - ps->hx, q.p.y - ps->hy) - ps->hole_radius > reach + POOL_TOUCH_TOLERANCE)
			continue;
		double t = enter_circle(&q, ps->hx, ps->hy, ps->hole_radius, fmin(T, best));
		// Into it below the nose only, as in flight: a ball above the nose over a hole (riding
		// a facing's or jaw's nose line from above) is not in the pocket (soak seed 21, mouth
		// shot 184749 and extreme_params shot 12377: a ball landing on a facing from above,
		// linked at once, dropped into the hole 2R above the cloth). A linked ball moves
		// uniformly: if it comes down below the nose while over the hole, it falls in then.
		if (t < best && !(q.p.z + (q.v.z + q.a.z * t) * t < sh->table.cushion_height)) {
			const double below = q.a.z == 0.0 && q.v.z < 0.0 ? (q.p.z - sh->table.cushion_height) / -q.v.z : INFINITY;
			const pool_vec3 at = path_at(&q, below);
			t = below <= fmin(T, best) && hypot(at.x - ps->hx, at.y - ps->hy) <= ps->hole_radius ? below : INFINITY;
		}
		if (t < best) {
			best = t;
			*pocket = (pool_pocket)p;
		}
	}
	return best;
}

// ---- in flight

// A flying ball against a jaw of radius r > 0 (a horizontal circle at the nose height): the
// distance from the centre to the circle is R where (rho - r)^2 + z^2 = R^2 (rho the horizontal
// distance from the jaw's axis, z the height above the nose), squared out
//     F = (rho^2 + z^2 + r^2 - R^2)^2 - 4 r^2 rho^2 = (d_near^2 - R^2)(d_far^2 - R^2),
// of degree 8 in t, handed to the Bernstein search (poly_roots.h), which finds its first
// falling root however close its roots lie. A root counts when the near factor vanishes (not
// the far side of the circle) and the nearest point is within the jaw's arc.
static int jaw_root_counts(const pool_nose_part *np, const path *w, double R, double t) {
	const pool_vec3 at = path_at(w, t);
	const double rho = sqrt(at.x * at.x + at.y * at.y), r = np->length;
	const double Q = rho * rho + at.z * at.z + r * r - R * R;
	if (!(fabs(Q - 2.0 * r * rho) <= fabs(Q + 2.0 * r * rho)))
		return 0;
	const pool_vec3 plan = pool_v3(at.x + np->ax, at.y + np->ay, 0.0);
	return in_span(np, plan);
}

// F of a path w relative to the jaw's centre at the nose height (above), into F[9]; rho2[5]
// receives rho^2.
static void jaw_gap_poly(const path *w, double r, double R, double F[9], double rho2[5]) {
	const double X[3] = {w->p.x, w->v.x, w->a.x}, Y[3] = {w->p.y, w->v.y, w->a.y}, Z[3] = {w->p.z, w->v.z, w->a.z};
	double xx[5], yy[5], zz[5], Q[5], QQ[9];
	pool_poly_mul(X, 2, X, 2, xx);
	pool_poly_mul(Y, 2, Y, 2, yy);
	pool_poly_mul(Z, 2, Z, 2, zz);
	for (int k = 0; k < 5; ++k) {
		rho2[k] = xx[k] + yy[k];
		Q[k] = rho2[k] + zz[k];
	}
	Q[0] += r * r - R * R;
	pool_poly_mul(Q, 4, Q, 4, QQ);
	for (int k = 0; k < 9; ++k)
		F[k] = QQ[k] - (k < 5 ? 4.0 * r * r * rho2[k] : 0.0);
}

/// m: a root of the jaw's F whose position along the path its rounding leaves more uncertain
/// than this is searched again on F rebuilt from the path where the uncertainty begins (a
/// hundredth of POOL_TOUCH_TOLERANCE: below it a root stays as found, bit for bit).
#define JAWS_ROOT_UNCERTAINTY 1e-11

// F is a square of distances squared: far along a long flight (seconds, metres up and down) its
// terms reach 1e5 where it crosses zero with a slope of 1e-3 per second, and its rounding moves
// the root by nanoseconds, 0.2 um at the 18 m/s of a ball falling from 4 m (soak seed 2, mouth
// shot 40719: the ball was 2.35e-7 m into the jaw at the contact). The uncertainty is the
// rounding of F's evaluation at t over its slope there; where it matters the path is restarted
// at the earliest time the root may be and F rebuilt from there (terms of the size of the ball's
// local motion), and its first root from there is the contact.
static double polish_jaw_root(const path *w, const double F[9], double r, double R, double t, double lo, double T) {
	double size = 0.0, slope = 0.0, power = 1.0;
	for (int k = 0; k <= 8; ++k) {
		size += fabs(F[k]) * power;
		if (k < 8)
			slope += (k + 1) * F[k + 1] * power;
		power *= t;
	}
	const pool_vec3 vel = pool_v3_madd(w->v, 2.0 * t, w->a);
	const double uncertainty = 16.0 * DBL_EPSILON * size / fabs(slope);
	if (!(uncertainty * pool_v3_len(vel) > JAWS_ROOT_UNCERTAINTY))
		return t;
	const double from = fmax(lo, t - 2.0 * uncertainty), to = fmin(T, t + 2.0 * uncertainty);
	path ws = *w;
	ws.p = path_at(w, from);
	ws.v = pool_v3_madd(w->v, 2.0 * from, w->a);
	double Fs[9], rho2[5];
	jaw_gap_poly(&ws, r, R, Fs, rho2);
	const double u = pool_poly_first_falling_root(Fs, 8, 0.0, to - from);
	return u <= to - from ? from + u : t;
}

static double flight_jaw(const pool_nose_part *np, const path *q, double R, double h, double T) {
	const path w = relative(q, np->ax, np->ay, h);
	const double r = np->length;
	if (!(r > 0.0)) { // a sharp jaw: a point
		const pool_contact_gap g = sphere_gap(&w, R);
		return part_contact(np, &g, q, T);
	}
	double F[9], rho2[5];
	jaw_gap_poly(&w, r, R, F, rho2);
	// Now: the distance to the circle and its rates (d = |(rho - r, z)|).
	const double rho = sqrt(rho2[0]);
	const double drho = rho > 0.0 ? (w.p.x * w.v.x + w.p.y * w.v.y) / rho : 0.0;
	const double d2rho = rho > 0.0 ? (w.v.x * w.v.x + w.v.y * w.v.y + 2.0 * (w.p.x * w.a.x + w.p.y * w.a.y)) / rho - drho * drho / rho : 0.0;
	const double u = rho - r, z = w.p.z, dz = w.v.z, d2z = 2.0 * w.a.z;
	const double d = sqrt(u * u + z * z);
	const double gap = d - R;
	double lo = 0.0, t;
	if (gap <= POOL_TOUCH_TOLERANCE && in_span(np, q->p) && d > 0.0) {
		const double dd = (u * drho + z * dz) / d;
		const double d2 = (drho * drho + u * d2rho + dz * dz + z * d2z) / d - dd * dd / d;
		if (pool_contact_now(gap, -dd, -d2))
			return 0.0;
		// Touching, not colliding now: F = t G(t) with the gap taken as zero (contact.h).
		double G[8];
		for (int k = 0; k < 8; ++k)
			G[k] = F[k + 1];
		t = pool_poly_first_falling_root(G, 7, 0.0, T);
		for (int i = 0; t <= T && i < JAWS_MAX_GHOSTS; ++i) {
			if (jaw_root_counts(np, &w, R, t))
				return t;
			t = pool_poly_first_falling_root(G, 7, t + JAWS_GHOST_STEP * (1.0 + t), T);
		}
		return INFINITY;
	}
	t = pool_poly_first_falling_root(F, 8, lo, T);
	for (int i = 0; t <= T && i < JAWS_MAX_GHOSTS; ++i) {
		const double found_at = t;
		t = polish_jaw_root(&w, F, r, R, t, lo, T);
		if (jaw_root_counts(np, &w, R, t))
			return t;
		t = pool_poly_first_falling_root(F, 8, fmax(t, found_at) + JAWS_GHOST_STEP * (1.0 + fmax(t, found_at)), T);
	}
	return INFINITY;
}

// A flying ball against a straight part: its distance to the line at the nose height is R (a
// quartic); past the free end of a facing, its distance to that corner.
static double flight_line(const pool_table_shape *sh, const pool_nose_part *np, const path *q, double T) {
	const double h = sh->table.cushion_height, R = sh->R;
	const path w = relative(q, np->ax, np->ay, h);
	const double s0 = w.p.x * np->nx + w.p.y * np->ny, s1 = w.v.x * np->nx + w.v.y * np->ny, s2 = w.a.x * np->nx + w.a.y * np->ny;
	if (s0 - R > POOL_TOUCH_TOLERANCE && (fabs(s1) + fabs(s2) * T) * T * (1.0 + 1e-12) < s0 - R)
		return INFINITY;
	// In the line's normal plane: (s, z) from the line, the ball-ball gap with one radius 0.
	path n;
	n.p = pool_v3(s0, w.p.z, 0.0);
	n.v = pool_v3(s1, w.v.z, 0.0);
	n.a = pool_v3(s2, w.a.z, 0.0);
	const pool_contact_gap g = sphere_gap(&n, R);
	double t = part_contact(np, &g, q, T);
	if (np->free_end) {
		const path e = relative(q, np->ax + np->length * np->dx, np->ay + np->length * np->dy, h);
		const pool_contact_gap ge = sphere_gap(&e, R);
		double te = ge.gap > POOL_TOUCH_TOLERANCE ? (T > 0.0 ? pool_contact_first_falling_root(ge.f, 4, T) : INFINITY)
		                                          : pool_contact_next(&ge, T);
		for (int i = 0; te <= T && i < JAWS_MAX_GHOSTS; ++i) {
			const pool_vec3 at = path_at(&e, te);
			if ((at.x * np->dx + at.y * np->dy) >= 0.0)
				break; // beyond the end: the corner is the nearest point
			te = pool_contact_first_falling_root_from(ge.f, 4, te + JAWS_GHOST_STEP * (1.0 + te), T);
		}
		t = fmin(t, te);
	}
	return t;
}

static double reach(const path *q, double T);

// The centre crosses part k's vertical surface outwards (over the cushion) within its span.
static double flight_over(const pool_nose_part *np, const path *q, double T) {
	path w = relative(q, np->ax, np->ay, q->p.z);
	w.p.z = w.v.z = w.a.z = 0.0;
	pool_contact_gap g;
	if (np->kind == POOL_NOSE_LINE)
		g = line_gap(w.p.x * np->nx + w.p.y * np->ny, w.v.x * np->nx + w.v.y * np->ny, w.a.x * np->nx + w.a.y * np->ny, 0.0);
	else
		g = sphere_gap(&w, np->length);
	// Farther from the surface than the path reaches over the window: no crossing.
	const double away = np->kind == POOL_NOSE_LINE ? g.gap : sqrt(w.p.x * w.p.x + w.p.y * w.p.y) - np->length;
	if (away > 0.0 && reach(q, T) * (1.0 + 1e-12) < away)
		return INFINITY;
	double t = T > 0.0 ? pool_contact_first_falling_root(g.f, 4, T) : INFINITY;
	for (int i = 0; t <= T && i < JAWS_MAX_GHOSTS; ++i) {
		if (in_span(np, path_at(q, t)))
			return t;
		t = pool_contact_first_falling_root_from(g.f, 4, t + JAWS_GHOST_STEP * (1.0 + t), T);
	}
	return INFINITY;
}

// The horizontal reach of a path over [0, T] from its start (bound).
static double reach(const path *q, double T) {
	return (sqrt(q->v.x * q->v.x + q->v.y * q->v.y) + sqrt(q->a.x * q->a.x + q->a.y * q->a.y) * T) * T;
}

// A bound below the horizontal distance from (x, y) to the path over [0, T]: in flight the path
// is straight in plan (the segment from its start to where it is at T); a path that curves in
// plan is bounded by its start less its reach.
static double plan_distance(const path *q, double T, double x, double y) {
	const double dx = x - q->p.x, dy = y - q->p.y;
	if (q->a.x != 0.0 || q->a.y != 0.0 || !isfinite(T))
		return sqrt(dx * dx + dy * dy) - (isfinite(T) ? reach(q, T) : INFINITY);
	const double ex = q->v.x * T, ey = q->v.y * T, ee = ex * ex + ey * ey;
	double u = ee > 0.0 ? (dx * ex + dy * ey) / ee : 0.0;
	u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
	return sqrt((dx - u * ex) * (dx - u * ex) + (dy - u * ey) * (dy - u * ey)) * (1.0 - 1e-12);
}

double pool_predict_flight_jaws(const pool_table_shape *sh, const pool_ball_state *s, pool_vec3 acc, double T,
                                pool_event_type *kind, pool_site *site) {
	const double R = sh->R, h = sh->table.cushion_height;
	const path q = {s->pos, s->vel, pool_v3_scale(acc, 0.5)};
	*kind = POOL_EVENT_BALL_TABLE;
	site->rail = POOL_RAIL_NONE;
	site->pocket = POOL_POCKET_NONE;
	site->part = -1;
	// Landing: the height above the cloth z - R reaches 0.
	pool_contact_gap land;
	land.gap = s->pos.z - R;
	land.speed = -s->vel.z;
	land.accel = -acc.z;
	land.f[0] = land.gap;
	land.f[1] = s->vel.z;
	land.f[2] = 0.5 * acc.z;
	land.f[3] = land.f[4] = 0.0;
	double best = pool_contact_next(&land, T);
	const double T_reach = isfinite(best) ? fmin(best, T) : T;
	// The pockets the path passes within reach of (their parts widened by R and holes lie in
	// their zone): the others' parts are not searched.
	int near[6];
	for (int p = 0; p < 6; ++p)
		near[p] = sh->table.pockets == POOL_POCKETS_JAWS && sh->has_pocket[p] &&
		          !(plan_distance(&q, T_reach, sh->pockets[p].mx, sh->pockets[p].my) > sh->pockets[p].zone);
	for (int k = 0; k < sh->n_parts; ++k) {
		const pool_nose_part *np = &sh->parts[k];
		if (np->pocket != POOL_POCKET_NONE && !near[np->pocket])
			continue;
		const double window = fmin(best, T);
		const double t = np->kind == POOL_NOSE_LINE ? flight_line(sh, np, &q, window) : flight_jaw(np, &q, R, h, window);
		found(t, &best, POOL_EVENT_BALL_CUSHION, np->rail, np->pocket, k, kind, site);
		const double to = flight_over(np, &q, fmin(best, T));
		found(to, &best, POOL_EVENT_OFF_TABLE, np->rail, POOL_POCKET_NONE, -1, kind, site);
	}
	// Into a hole below the nose height (it drops), or out past its far side over the rail.
	for (int p = 0; p < 6; ++p) {
		const pool_pocket_shape *ps = &sh->pockets[p];
		if (!near[p])
			continue;
		double window = fmin(best, T);
		const double t = enter_circle(&q, ps->hx, ps->hy, ps->hole_radius, window);
		if (t <= window && path_at(&q, t).z < h)
			found(t, &best, POOL_EVENT_POCKET, POOL_RAIL_NONE, (pool_pocket)p, -1, kind, site);
		// Leaving the hole's circle beyond the throat (the line between the facings' ends), above
		// the nose height: over the pocket's back and the rail, off the table.
		window = fmin(best, T);
		path w = relative(&q, ps->hx, ps->hy, q.p.z);
		w.p.z = w.v.z = w.a.z = 0.0;
		const pool_contact_gap g = sphere_gap(&w, ps->hole_radius);
		const double out[5] = {-g.f[0], -g.f[1], -g.f[2], -g.f[3], -g.f[4]};
		double te = window > 0.0 ? pool_contact_first_falling_root(out, 4, window) : INFINITY;
		for (int i = 0; te <= window && i < 2; ++i) {
			const pool_vec3 at = path_at(&q, te);
			const double lx = ps->ex[1] - ps->ex[0], ly = ps->ey[1] - ps->ey[0];
			const double side_m = lx * (ps->my - ps->ey[0]) - ly * (ps->mx - ps->ex[0]);
			const double side_p = lx * (at.y - ps->ey[0]) - ly * (at.x - ps->ex[0]);
			if (side_m * side_p < 0.0) {
				found(te, &best, POOL_EVENT_OFF_TABLE, POOL_RAIL_NONE, POOL_POCKET_NONE, -1, kind, site);
				break;
			}
			te = pool_contact_first_falling_root_from(out, 4, te + JAWS_GHOST_STEP * (1.0 + te), window);
		}
	}
	if (*kind == POOL_EVENT_BALL_TABLE && isfinite(best)) {
		// Landing over a hole pockets the ball; anywhere else off the cloth (the rail top, the
		// pocket's back: crossed above the nose), it has left the table.
		const pool_vec3 at = path_at(&q, best);
		const pool_pocket pocket = pool_shape_hole_at(sh, at.x, at.y);
		if (pocket != POOL_POCKET_NONE) {
			*kind = POOL_EVENT_POCKET;
			site->pocket = pocket;
		} else if (!pool_shape_on_cloth(sh, at.x, at.y, 1e-6)) {
			*kind = POOL_EVENT_OFF_TABLE;
		}
	}
	return best;
}

double pool_predict_flight_shape(const pool_table_shape *sh, const pool_ball_state *s, pool_vec3 acc, double T,
                                 pool_event_type *kind, pool_site *site) {
	if (sh->table.pockets != POOL_POCKETS_MOUTH_LINES)
		return pool_predict_flight_jaws(sh, s, acc, T, kind, site);
	site->part = -1;
	return pool_predict_flight(&sh->table, sh->R, s, acc, T, kind, &site->rail, &site->pocket);
}
