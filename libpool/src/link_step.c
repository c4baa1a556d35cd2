// One LINK step of a cluster (docs/physics.md "LINK"; the API and its rules are in link_step.h): the
// contacts, the free velocities, the LCP by columns and Lemke; the warm start, which usually
// solves the step without them, is link_warm.c's (the shared layout: link_problem.h).
//
// Unknowns, in docs/physics.md's order, for nc contacts of eta friction directions each:
//   x = (dt beta [nc * eta], dt fn [nc], lambda [nc]),   size L = nc (eta + 2),
// the impulses of the step along each contact's friction directions and normal, and lambda, the
// magnitude of the post-step slip at a sliding contact. With W = J' M^-1 J over the stacked
// directions (normal and friction) and v* the free velocities (below):
//   w_beta   = D' W D x_beta + D' W N x_n + E lambda + D' J' v*          >= 0  _|_ x_beta
//   w_n      = N' W D x_beta + N' W N x_n + N' J' v* + gap term / dt     >= 0  _|_ x_n
//   w_lambda = mu x_n - E' x_beta                                        >= 0  _|_ lambda
// and then v+ = v* + M^-1 J x. w_n is the contact's normal velocity after the step plus the
// Stewart-Trinkle gap term, so a contact open by gap may close by exactly gap during the step
// and no contact opens into interpenetration: positions advance linearly (p += dt v+) and the
// distance between two spheres, from a sphere to a line or to a plane is convex in the
// positions, so the linearised gap gap + dt n'u+ >= 0 is a lower bound of the true gap at the
// step's end. The distance to a jaw's arc is convex only from outside its circle; from inside
// (a ball on the cushion's top over a jaw) the row asks gap + dt n'u+ >= bend instead, bend
// bounding how far the plane overstates the arc's distance over the step (arc_bend).
//
// Restitution is zero: the step is inelastic at velocity level (a closing contact ends the
// step at relative normal velocity >= 0, nothing bounces). Impacts with restitution are the
// event handlers' job (collision.c); inside a cluster contact is persistent by definition.
//
// Existing penetration (gap < 0: rounding, or a cluster formed overlapping): Baumgarte
// stabilisation, the normal row asks for a separation speed of POOL_LINK_BAUMGARTE of the depth
// per step, capped at POOL_LINK_PUSH_SPEED. Full projection (the whole depth in one step) would
// add 1/2 m (depth/dt)^2 of kinetic energy, unbounded as dt -> 0. With the cap, what a step can
// add is bounded: KE+ - KE* = -sum fn gap_term - sum mu fn lambda - 1/2 x'Wx <= sum_c fn_c
// POOL_LINK_PUSH_SPEED over the penetrating contacts (the friction and the x'Wx terms only
// dissipate).
//
// Free velocities v*: gravity (f_ext) over dt, and the two cloth resistances that are not
// point-contact friction, as explicit wrenches of a ball touching the cloth, each clamped so it
// stops a motion rather than reverse it within the step:
// - spin friction: a torque -mu_spin m g R sign(wz) k (I dwz/dt = -(5 mu_spin g / 2R) I), so wz
//   decays at 5 mu_spin g / (2R) as in the closed form; wz does not enter the cloth slip
//   v + R k x w, so the LCP's cloth contact never sees it;
// - rolling resistance, for a ball whose cloth slip at the step's start is within what the
//   cloth's sliding friction removes in one step ((7/2) mu_slide g dt, i.e. a rolling ball): the
//   wrench of the closed-form rolling deceleration, dv = -mu_roll g dt u^, dw = k x dv / R, with
//   u the velocity the ball rolls with once that slip is gone (v for a rolling ball). It
//   leaves the slip v + R k x w unchanged, so a rolling ball stays rolling without any
//   friction from the LCP and decelerates at mu_roll g exactly; a sliding ball gets none (the
//   closed form's sliding motion has no rolling resistance). The load is m g: a cushion
//   pressing the ball into the cloth does not raise it (the closed form's law).
#include "link_step.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "assert.h"
#include "geometry.h"
#include "lemke.h"
#include "link_problem.h"
#include "table_shape.h"
#include "vec3.h"

/// Fraction of an existing penetration the step removes (Baumgarte): a fifth per step spreads a
/// correction over a few steps, so a deep overlap is not cancelled by one violent push.
#define POOL_LINK_BAUMGARTE 0.2

/// m/s, the largest separation speed the penetration correction asks for (bounds the energy it
/// adds, see the top of the file): a millimetre per second is invisible and still removes the
/// micrometre overlaps of rounding in a step.
#define POOL_LINK_PUSH_SPEED 1e-3

/// m, added to the gap a step can close (speed bound x dt) when choosing the contacts: covers
/// gravity's dt^2 term and rounding. Extra contacts only enlarge the LCP; a missing one could
/// let two balls interpenetrate.
#define POOL_LINK_MARGIN POOL_LINK_TOUCH_GAP

/// Contacts above which a step refuses (POOL_ERR_OUT_OF_MEMORY) rather than size Lemke's
/// workspace, which grows as (contacts (eta + 2))^2: 2000 contacts are 28 GB at eta = 14, far
/// beyond any cluster of a rack's balls (a frozen 16-ball cluster has 47), and the product
/// stays inside size_t.
#define POOL_LINK_CONTACTS_MAX 2000

/// Contacts sharing a ball with a contact (itself included) that the first layout of a step's
/// matrix makes room for: a ball on the cloth touching two others has 3 contacts, so a contact
/// between two such balls shares a ball with 5; a larger cluster is laid out again.
#define POOL_LINK_NEAR_GUESS 5

#define LINK_PI 3.14159265358979323846

void pool_link_workspace_free(pool_link_workspace *ws, const pool_allocator *alloc) {
	if (!ws)
		return;
	if (ws->memory && alloc && alloc->free)
		alloc->free(ws->memory, alloc->context);
	pool_link_bases_free(&ws->bases, alloc);
	memset(ws, 0, sizeof *ws);
}

// ---- contacts

typedef struct link_scene {
	const pool_sim_def *def;
	const pool_table_shape *shape; ///< pockets "jaws": the parts of the nose curve, else NULL
	const pool_ball_state *s;
	int n;
	int planar;
	double reach;   ///< m, the most a ball's centre can move in the step (speed bound x dt)
	double dt;      ///< s, the step
} link_scene;

static pool_vec3 centre(const link_scene *sc, int k) {
	pool_vec3 p = sc->s[k].pos;
	if (sc->planar)
		p.z = sc->def->params.ball_radius;
	return p;
}

// Contact `count` of ball a (out[count] when out is not NULL) against ball b (-1: the cloth or a
// cushion, `cushion` its id), along the unit normal n towards a; returns count + 1.
static int put_contact(link_contact *out, int count, link_kind kind, int a, int b, int cushion, pool_vec3 n, double R,
                       double gap, double mu) {
	if (out) {
		POOL_ASSERT(fabs(pool_v3_len(n) - 1.0) < 1e-12); // a unit normal
		link_contact *c = &out[count];
		c->kind = kind;
		c->a = a;
		c->b = b;
		c->cushion = cushion;
		c->n = n;
		c->ra = kind == LINK_CLOTH ? pool_v3(0.0, 0.0, -R) : pool_v3_scale(n, -R); // (no -0.0 on the cloth)
		c->rb = b >= 0 ? pool_v3_scale(n, R) : pool_v3(0.0, 0.0, 0.0);
		c->gap = gap;
		c->bend = 0.0;
		c->mu = mu;
	}
	return count + 1;
}

// How much the linearised gap gap + n'dp of ball b against part k of the nose curve can overstate
// its true gap at the step's end (m; 0 for a line). The distance from a point to a straight part
// is convex, so its tangent plane is a lower bound (the top of the file). A jaw's arc is convex
// only from outside its circle: with the centre horizontally at rho < r from the arc's axis (a
// ball riding the top of the cushion over a jaw), moving along the arc brings the centre nearer
// the circle, and the plane lets it sink into the nose curve by s^2/2 times the distance's most
// negative curvature, (r - rho) / (d rho) (d = |p - q|: the Hessian's part (rho - r)/d times
// rho's, 1/rho along the arc), s the centre's move along the arc. Soak seed 49, mouth shot 27112:
// a ball linked on the cushion's top 3 mm inside a corner jaw's circle, moving at 0.6 m/s, sank
// 0.6 um a step, 7 um deep after 16 steps, which the capped correction (POOL_LINK_PUSH_SPEED)
// could not undo. s is the ball's own speed along the arc at the step's start plus g dt (what
// contacts pressing with about its weight change in a step), not the cluster's speed bound: that
// counts the spin's energy too, and lifting the ball by a bend three times too large would open
// the contact beyond POOL_LINK_TOUCH_GAP every step. (rho, d and r - rho are taken at their worst
// over a move of that speed.) Never more than 2 s (the distance and its plane each change by at
// most s).
static double arc_bend(const link_scene *sc, int k, const pool_ball_state *b, pool_vec3 pa, double d) {
	const pool_nose_part *np = &sc->shape->parts[k];
	if (np->kind != POOL_NOSE_ARC)
		return 0.0;
	const double ex = pa.x - np->ax, ey = pa.y - np->ay, rho = hypot(ex, ey), inside = np->length - rho;
	if (!(inside > 0.0 && rho > 0.0))
		return inside > 0.0 ? sc->reach : 0.0; // outside the circle: convex
	const double dt = sc->dt;
	const double slack = sc->def->params.g * dt;
	const double along = fabs(b->vel.x * ey - b->vel.y * ex) / rho + slack;        // m/s, along the arc
	const double move = (hypot(b->vel.x, b->vel.y) + slack) * dt, s = along * dt; // m
	const double rho_min = rho - move, d_min = d - move - fabs(b->vel.z) * dt;
	if (!(rho_min > 0.0 && d_min > 0.0))
		return 2.0 * move;
	return fmin(0.5 * s * s * (inside + move) / (d_min * rho_min), 2.0 * move);
}

// Finds the contacts (into out when not NULL) and returns their count; the same order every
// time: per ball its cloth contact, its cushions by rail, then its pairs with later balls.
static int find_contacts(const link_scene *sc, link_contact *out) {
	const double R = sc->def->params.ball_radius;
	const pool_params *p = &sc->def->params;
	const pool_table_def *table = &sc->def->table;
	int count = 0;
	for (int a = 0; a < sc->n; ++a) {
		const pool_vec3 pa = centre(sc, a);
		// Cloth: the plane z = 0; planar mode keeps every ball on it at gap 0.
		const double cloth_gap = sc->planar ? 0.0 : pa.z - R;
		if (sc->planar || cloth_gap < sc->reach + POOL_LINK_MARGIN)
			count = put_contact(out, count, LINK_CLOTH, a, -1, -1, pool_v3(0.0, 0.0, 1.0), R, cloth_gap, p->mu_slide);
		// Pockets "jaws": each part of the nose curve whose span the centre faces (a facing, a
		// jaw, a nose segment), its id for the warm start past the four rails'.
		for (int k = 0; sc->shape && k < sc->shape->n_parts; ++k) {
			if (!pool_shape_in_span(sc->shape, k, pa))
				continue;
			const pool_vec3 q = pool_shape_nearest(sc->shape, k, pa);
			const double gap = pool_v3_len(pool_v3_sub(pa, q)) - R;
			if (gap < sc->reach + POOL_LINK_MARGIN) {
				count = put_contact(out, count, LINK_CUSHION, a, -1, 4 + k, pool_shape_normal(sc->shape, k, pa), R, gap,
				                    p->mu_cushion);
				if (out)
					out[count - 1].bend = arc_bend(sc, k, &sc->s[a], pa, gap + R);
			}
		}
		for (int rail = POOL_RAIL_SOUTH; !sc->shape && rail <= POOL_RAIL_EAST; ++rail) {
			// The nose: its line, ending at the pocket mouths (over a mouth there is no nose but its
			// ends: the world pockets a ball crossing the contact line there). A contact per piece of
			// the nose, at its point nearest the ball: a ball over a mouth narrower than 2R touches
			// the ends on both sides, and each piece is convex, so the step's plane through that
			// point (the contact's normal) keeps the ball out of all of it.
			pool_vec3 nose[2];
			const int pieces = pool_nose_pieces_nearest(table, (pool_rail)rail, pa, nose);
			for (int k = 0; k < pieces; ++k) {
				const pool_vec3 d = pool_v3_sub(pa, nose[k]);
				const double dist = pool_v3_len(d);
				const double gap = dist - R;
				if (gap < sc->reach + POOL_LINK_MARGIN && dist > 0.0)
					count = put_contact(out, count, LINK_CUSHION, a, -1, rail + 4 * k, pool_v3_scale(d, 1.0 / dist), R, gap,
					                    p->mu_cushion);
			}
		}
		for (int b = a + 1; b < sc->n; ++b) {
			const pool_vec3 d = pool_v3_sub(pa, centre(sc, b));
			const double dist = pool_v3_len(d);
			const double gap = dist - 2.0 * R;
			// Two balls close at up to twice the speed bound.
			if (gap < 2.0 * sc->reach + POOL_LINK_MARGIN && dist > 0.0)
				count = put_contact(out, count, LINK_BALL, a, b, -1, pool_v3_scale(d, 1.0 / dist), R, gap, p->mu_ball);
		}
	}
	return count;
}

// ---- velocities of the contact points

/// Unit vectors t1, t2 completing n to a right-handed basis: t1 along the tangential slip u_t
/// when aligning and the slip is resolved, else fixed (k x n, or x on the cloth).
static void tangent_basis(pool_vec3 n, pool_vec3 slip, int align, double align_slip, pool_vec3 *t1, pool_vec3 *t2) {
	pool_vec3 ut = pool_v3_madd(slip, -pool_v3_dot(slip, n), n);
	const double speed = pool_v3_len(ut);
	if (align && speed > align_slip) {
		*t1 = pool_v3_scale(ut, 1.0 / speed);
	} else {
		pool_vec3 k = pool_v3(0.0, 0.0, 1.0);
		pool_vec3 a = pool_v3_cross(k, n);
		double la = pool_v3_len(a);
		if (la < 1e-3) { // n (anti)parallel to k: the cloth, or a ball on top of another
			a = pool_v3_cross(n, pool_v3(0.0, 1.0, 0.0)); // = x for n = k
			la = pool_v3_len(a);
		}
		*t1 = pool_v3_scale(a, 1.0 / la);
	}
	*t2 = pool_v3_cross(n, *t1);
}

// ---- workspace

static size_t align_up(size_t x) { return (x + 15u) & ~(size_t)15u; }

/// Lays out the step's arrays in `base` (NULL: only sizes them); returns the bytes needed.
/// nnz_max bounds the LCP matrix's nonzeros (matrix_nonzeros).
static size_t layout(void *base, int n, int nc, int eta, size_t nnz_max, link_memory *m) {
	const size_t L = (size_t)nc * (size_t)(eta + 2);
	const size_t warm = L < POOL_LINK_WARM_BASIC_MAX ? L : POOL_LINK_WARM_BASIC_MAX;
	const size_t dirs = (size_t)(1 + eta);
	size_t at = 0;
	char *b = base;
#define LINK_PLACE(field, type, count)                                                                                 \
	do {                                                                                                           \
		if (m)                                                                                                 \
			m->field = (type *)(void *)(b ? b + at : NULL);                                                \
		at = align_up(at + sizeof(type) * (size_t)(count));                                                    \
	} while (0)
	LINK_PLACE(basis, int, L);
	LINK_PLACE(basic, int, L);
	LINK_PLACE(S, double, warm * (warm + 1));
	LINK_PLACE(warm, link_warm_unknown, warm);
	LINK_PLACE(col_start, int, L + 1);
	LINK_PLACE(col_row, int, nnz_max);
	LINK_PLACE(col_val, double, nnz_max);
	LINK_PLACE(near, int, nc);
	LINK_PLACE(q, double, L);
	LINK_PLACE(z, double, L);
	LINK_PLACE(V, double, 6 * (size_t)n);
	LINK_PLACE(G, double, (size_t)nc * 2 * dirs * 6);
	LINK_PLACE(contacts, link_contact, nc);
	LINK_PLACE(inc, link_incidence, 2 * (size_t)nc);
	LINK_PLACE(inc_start, int, (size_t)n + 1);
	LINK_PLACE(ball_push, double, (size_t)n);
	LINK_PLACE(ball_touching, int, (size_t)n);
	LINK_PLACE(tail, double, 6 * (size_t)n);
	LINK_PLACE(V_free, double, 6 * (size_t)n);
#undef LINK_PLACE
	if (m)
		m->lemke = b ? b + at : NULL;
	at += pool_lemke_workspace_bytes((int)L);
	return at;
}

/// Makes the workspace hold `bytes`; POOL_ERR_OUT_OF_MEMORY leaves it as it was.
static pool_result reserve(pool_link_workspace *ws, const pool_allocator *alloc, size_t bytes) {
	if (ws->memory && ws->bytes >= bytes)
		return POOL_OK;
	size_t grown = ws->bytes + ws->bytes / 2; // amortised growth over a shot's growing clusters
	if (grown < bytes)
		grown = bytes;
	void *memory = alloc->alloc(grown, alloc->context);
	if (!memory)
		return POOL_ERR_OUT_OF_MEMORY;
	if (ws->memory)
		alloc->free(ws->memory, alloc->context);
	ws->memory = memory;
	ws->bytes = grown;
	return POOL_OK;
}

// ---- the step

static int finite_state(const pool_ball_state *b) {
	return pool_v3_finite(b->pos) && pool_v3_finite(b->vel) && pool_v3_finite(b->omega);
}

/// The explicit cloth resistances (top of the file) over a time h on the velocities v (6) of a
/// ball touching the cloth, each clamped so it stops a motion rather than reverse it; the
/// rolling criterion is that of a step of dt.
static void cloth_resistance(const pool_params *p, double h, double dt, double *v) {
	const double R = p->ball_radius;
	// Spin friction: wz towards 0 at 5 mu_spin g / (2R), never past it.
	const double dwz = 2.5 * p->mu_spin * p->g * h / R;
	v[5] = fabs(v[5]) <= dwz ? 0.0 : v[5] - copysign(dwz, v[5]);
	// Rolling resistance, for a ball rolling or about to (its slip within what the step's
	// cloth friction removes), against the velocity it rolls with once the slip is gone,
	// (5 v - 2 R k x w) / 7 (the cloth's friction keeps the angular momentum about the contact
	// point): v itself for a rolling ball. Along v instead, a ball sliding with backspin would
	// gain spin energy from the wrench (the soak's rail_struck shot 3517: +7e-9 J); along the
	// rolling velocity it dissipates (7/5) m |v_roll| dv whatever the spin.
	const pool_vec3 vel = pool_v3(v[0], v[1], 0.0), w = pool_v3(v[3], v[4], v[5]);
	const pool_vec3 slip = pool_v3_add(vel, pool_v3_scale(pool_v3_kcross(w), R));
	if (!(pool_v3_len(pool_v3_xy(slip)) <= 3.5 * p->mu_slide * p->g * dt))
		return;
	const pool_vec3 rolling = pool_v3_xy(pool_v3_scale(pool_v3_madd(pool_v3_scale(vel, 5.0), -2.0 * R, pool_v3_kcross(w)), 1.0 / 7.0));
	const double speed = pool_v3_len(rolling);
	if (!(speed > 0.0))
		return;
	const double dv = fmin(p->mu_roll * p->g * h, speed);
	const pool_vec3 delta = pool_v3_scale(rolling, -dv / speed);
	const pool_vec3 dw = pool_v3_scale(pool_v3_kcross(delta), 1.0 / R);
	v[0] += delta.x;
	v[1] += delta.y;
	v[3] += dw.x;
	v[4] += dw.y;
}

/// Free velocities: gravity and the explicit cloth resistances. The resistances act at the
/// step's midpoint: V gets their first half, so the LCP solves for the mean velocity over the
/// step, with which the positions advance; the second half acts on that mean (step_tail), so it
/// never reverses what the contacts stopped. Uniform motion at the mean is exact for a rolling
/// ball (constant deceleration), where the end velocity would lag it by 1/2 mu_roll g dt^2 per
/// step. Gravity stays whole in V: on the cloth the LCP cancels it.
static void free_velocities(const link_scene *sc, const link_contact *c, int nc, double dt, double *V) {
	const pool_params *p = &sc->def->params;
	for (int k = 0; k < sc->n; ++k) {
		const pool_ball_state *b = &sc->s[k];
		double *v = V + 6 * k;
		v[0] = b->vel.x;
		v[1] = b->vel.y;
		v[2] = sc->planar ? 0.0 : b->vel.z;
		v[3] = b->omega.x;
		v[4] = b->omega.y;
		v[5] = b->omega.z;
	}
	for (int i = 0; i < nc; ++i)
		if (c[i].kind == LINK_CLOTH && c[i].gap <= POOL_LINK_TOUCH_GAP)
			cloth_resistance(p, 0.5 * dt, dt, V + 6 * c[i].a);
	for (int k = 0; k < sc->n; ++k)
		V[6 * k + 2] -= p->g * dt;
}

/// tail: the second half of the cloth resistances, on the step's mean velocities V: the
/// velocities at the step's end are V + tail.
static void step_tail(const link_scene *sc, const link_contact *c, int nc, double dt, const double *V, double *tail) {
	for (int k = 0; k < 6 * sc->n; ++k)
		tail[k] = 0.0;
	for (int i = 0; i < nc; ++i) {
		if (c[i].kind != LINK_CLOTH || !(c[i].gap <= POOL_LINK_TOUCH_GAP))
			continue;
		double v[6];
		memcpy(v, V + 6 * c[i].a, sizeof v);
		cloth_resistance(&sc->def->params, 0.5 * dt, dt, v);
		for (int e = 0; e < 6; ++e)
			tail[6 * c[i].a + e] = v[e] - V[6 * c[i].a + e];
	}
}

/// The separation the normal row asks for, as a velocity: -gap/dt for an open contact (it may
/// close exactly), a capped Baumgarte push for a penetrating one.
static double gap_velocity(double gap, double dt) {
	if (gap >= 0.0)
		return gap / dt;
	return -fmin(POOL_LINK_BAUMGARTE * -gap / dt, POOL_LINK_PUSH_SPEED);
}

/// m/s: the fastest any ball's centre can move over the step. An inelastic step adds no kinetic
/// energy (beyond the capped penetration push), so no centre moves faster than the cluster's
/// whole kinetic energy, with gravity's dt, allows.
static double speed_bound(const link_scene *sc, double dt) {
	const pool_params *p = &sc->def->params;
	const double R = p->ball_radius;
	double energy = 0.0; // kinetic energy / (m / 2)
	for (int k = 0; k < sc->n; ++k) {
		const pool_ball_state *b = &sc->s[k];
		const double vz = sc->planar ? 0.0 : fabs(b->vel.z) + p->g * dt;
		energy += b->vel.x * b->vel.x + b->vel.y * b->vel.y + vz * vz + 0.4 * R * R * pool_v3_dot(b->omega, b->omega);
	}
	return sqrt(energy) + POOL_LINK_PUSH_SPEED;
}

/// G = sigma [d; r x d] per contact side (sigma = -1 for ball b): direction 0 the normal, 1 ...
/// eta the friction directions, d_{j + eta/2} = -d_j exactly.
static void build_directions(link_problem *P, int align) {
	const int eta = P->eta;
	P->aligned = align;
	double cosine[POOL_LINK_ETA_MAX / 2], sine[POOL_LINK_ETA_MAX / 2]; // of the directions' angles
	for (int j = 0; j < eta / 2; ++j) {
		cosine[j] = cos(2.0 * LINK_PI * j / eta);
		sine[j] = sin(2.0 * LINK_PI * j / eta);
	}
	for (int i = 0; i < P->nc; ++i) {
		const link_contact *c = &P->c[i];
		pool_vec3 t1, t2;
		tangent_basis(c->n, contact_velocity(c, P->m.V), align, align_slip_of(P, c), &t1, &t2);
		pool_vec3 d[POOL_LINK_ETA_MAX + 1];
		d[0] = c->n;
		for (int j = 0; j < eta / 2; ++j) {
			d[1 + j] = pool_v3_add(pool_v3_scale(t1, cosine[j]), pool_v3_scale(t2, sine[j]));
			d[1 + j + eta / 2] = pool_v3_scale(d[1 + j], -1.0);
		}
		for (int side = 0; side < (c->b >= 0 ? 2 : 1); ++side) {
			double *g = directions(P, i, side);
			const double sigma = side ? -1.0 : 1.0;
			const pool_vec3 r = side ? c->rb : c->ra;
			for (int j = 0; j < P->dirs; ++j) {
				const pool_vec3 t = pool_v3_cross(r, d[j]);
				double *gj = g + 6 * j;
				gj[0] = sigma * d[j].x;
				gj[1] = sigma * d[j].y;
				gj[2] = sigma * d[j].z;
				gj[3] = sigma * t.x;
				gj[4] = sigma * t.y;
				gj[5] = sigma * t.z;
			}
		}
	}
}

/// The contacts of each ball, as (contact, side) lists: J's block sparsity.
static void build_incidence(link_problem *P) {
	int *start = P->m.inc_start;
	for (int k = 0; k <= P->n; ++k)
		start[k] = 0;
	for (int i = 0; i < P->nc; ++i) {
		++start[P->c[i].a + 1];
		if (P->c[i].b >= 0)
			++start[P->c[i].b + 1];
	}
	for (int k = 0; k < P->n; ++k)
		start[k + 1] += start[k];
	for (int i = 0; i < P->nc; ++i) { // start[k] is meanwhile ball k's next free slot
		const link_incidence ia = {i, 0}, ib = {i, 1};
		P->m.inc[start[P->c[i].a]++] = ia;
		if (P->c[i].b >= 0)
			P->m.inc[start[P->c[i].b]++] = ib;
	}
	for (int k = P->n; k > 0; --k) // start[k - 1] now ends ball k - 1, where ball k starts
		start[k] = start[k - 1];
	start[0] = 0;
}

/// The contacts sharing a ball with contact i (itself included), ascending, into P->m.near;
/// returns their count. Each ball's incidence list is ascending, so this merges two lists.
static int near_contacts(const link_problem *P, int i) {
	const link_contact *c = &P->c[i];
	const link_incidence *inc = P->m.inc;
	int ea = P->m.inc_start[c->a], ea_end = P->m.inc_start[c->a + 1];
	int eb = c->b >= 0 ? P->m.inc_start[c->b] : 0, eb_end = c->b >= 0 ? P->m.inc_start[c->b + 1] : 0;
	int count = 0;
	while (ea < ea_end || eb < eb_end) {
		const int ca = ea < ea_end ? inc[ea].contact : INT32_MAX, cb = eb < eb_end ? inc[eb].contact : INT32_MAX;
		const int next = ca < cb ? ca : cb;
		ea += ca == next;
		eb += cb == next;
		P->m.near[count++] = next;
	}
	return count;
}

/// The most nonzeros the LCP matrix can have: per impulse column, the impulse rows of the
/// contacts sharing a ball with its contact and its own lambda row; per lambda column, its
/// contact's friction rows.
static size_t matrix_nonzeros(const link_problem *P) {
	size_t nnz = 0;
	for (int i = 0; i < P->nc; ++i)
		nnz += (size_t)P->dirs * ((size_t)near_contacts(P, i) * (size_t)P->dirs + 1) + (size_t)P->eta;
	return nnz;
}

/// The LCP matrix by columns (lemke.h's compressed columns, rows ascending, nonzeros only): J'
/// M^-1 J, one block per pair of contacts sharing a ball (M^-1 is per ball, so the blocks of
/// contacts with no ball in common are zero), then E, -E' and mu. In velocity units: the
/// impulse unknowns are impulses / mass (their columns times the mass) and the lambda rows
/// (mu fn - E' beta, impulses) are divided by it, which leaves E, -E' and mu as they are.
/// Positive scalings of unknowns and rows keep every solution; they make the entries O(1)
/// (J' M^-1 J is ~1/m, 6 per kg for a pool ball) and Lemke's residual a velocity, comparable
/// with q's. The retries add `friction_compliance` to the friction directions' diagonal and
/// `normal_compliance` to the normals'. Never formed densely: a rack's 47 contacts have 1.4e5
/// nonzeros of 5.7e5 entries.
static void build_matrix(link_problem *P, double mass, double friction_compliance, double normal_compliance) {
	int *start = P->m.col_start, *row = P->m.col_row;
	double *val = P->m.col_val;
	size_t t = 0;
#define LINK_PUT(r, v)                                                                                                 	do {                                                                                                           		const double value_ = (v);                                                                             		if (value_ != 0.0) {                                                                                   			row[t] = (int)(r);                                                                             			val[t++] = value_;                                                                             		}                                                                                                      	} while (0)
	// Columns in unknown order: the friction directions of every contact, its normals, its lambdas.
	int near_of = -1, near = 0;
	for (int col = 0; col < P->L; ++col) {
		start[col] = (int)t;
		int i2, j2;
		unknown_of(P, col, &i2, &j2);
		if (j2 < 0) { // lambda: E on its contact's friction rows
			for (int j = 1; j < P->dirs; ++j)
				LINK_PUT(row_of(P, i2, j), 1.0);
			continue;
		}
		double h[2][6];
		impulse_column(P, i2, j2, mass, h);
		const double compliance = j2 == 0 ? normal_compliance : friction_compliance; // its diagonal's
		if (i2 != near_of) { // (a contact's columns are consecutive: its neighbours once)
			near = near_contacts(P, i2);
			near_of = i2;
		}
		for (int pass = 0; pass < 2; ++pass) // the friction rows, then the normal rows
			for (int k = 0; k < near; ++k) {
				const int i1 = P->m.near[k];
				const link_shared sh = shared_sides(P, i1, i2);
				for (int j1 = pass ? 0 : 1; j1 < (pass ? 1 : P->dirs); ++j1) {
					const double w = coupling(P, i1, j1, &sh, h);
					LINK_PUT(row_of(P, i1, j1), i1 == i2 && j1 == j2 ? w + compliance : w);
				}
			}
		LINK_PUT(lambda_of(P, i2), j2 == 0 ? P->c[i2].mu : -1.0); // mu, or -E'
	}
	start[P->L] = (int)t;
#undef LINK_PUT
}

/// b: the free relative velocity along every direction, the gap term on the normals, 0 on the
/// lambda rows.
static void build_vector(link_problem *P, double dt) {
	for (int i = 0; i < P->nc; ++i) {
		const link_contact *c = &P->c[i];
		for (int j = 0; j < P->dirs; ++j) {
			double sum = 0.0;
			for (int side = 0; side < (c->b >= 0 ? 2 : 1); ++side) {
				const double *g = directions(P, i, side) + 6 * j;
				const double *v = P->m.V + 6 * (side ? c->b : c->a);
				sum += g[0] * v[0] + g[1] * v[1] + g[2] * v[2] + g[3] * v[3] + g[4] * v[4] + g[5] * v[5];
			}
			if (j == 0)
				sum += gap_velocity(c->gap, dt) - c->bend / dt; // the end's linearised gap >= bend
			P->m.q[row_of(P, i, j)] = sum;
		}
		P->m.q[lambda_of(P, i)] = 0.0;
	}
}

/// The step's own check of a solve, in the LCP's velocity units: max over i of -z_i, -w_i and
/// min(z_i, w_i), w = A z + q (A by columns), relative to 1 + max |q| (a velocity scale that a
/// wrong, huge z cannot inflate, unlike Lemke's own scale of the terms of A z). w goes in
/// `scratch` (L doubles).
static double velocity_residual(const link_problem *P, const double *z, double *w) {
	const int L = P->L;
	memcpy(w, P->m.q, sizeof(double) * (size_t)L);
	for (int j = 0; j < L; ++j)
		if (z[j] != 0.0)
			for (int t = P->m.col_start[j]; t < P->m.col_start[j + 1]; ++t)
				w[P->m.col_row[t]] += P->m.col_val[t] * z[j];
	double worst = 0.0, scale = 1.0;
	for (int i = 0; i < L; ++i) {
		worst = fmax(worst, fmax(fmax(-z[i], -w[i]), fmin(z[i], w[i])));
		scale = fmax(scale, 1.0 + fabs(P->m.q[i]));
	}
	return isfinite(worst) ? worst / scale : INFINITY;
}

/// v+ = v* + M^-1 J x.
static void apply_impulses(link_problem *P) {
	for (int i = 0; i < P->nc; ++i) {
		const link_contact *c = &P->c[i];
		for (int side = 0; side < (c->b >= 0 ? 2 : 1); ++side) {
			double *v = P->m.V + 6 * (side ? c->b : c->a);
			const double *g = directions(P, i, side);
			for (int j = 0; j < P->dirs; ++j) {
				const double x = P->m.z[row_of(P, i, j)];
				if (x != 0.0)
					for (int e = 0; e < 6; ++e)
						v[e] += x * g[6 * j + e] * P->inv[e];
			}
		}
	}
}

pool_result pool_link_step_with(const pool_sim_def *def, pool_ball_state *s, int n, double dt,
                                const pool_link_options *options, pool_link_workspace *ws,
                                const pool_allocator *alloc, pool_link_step_stats *stats) {
	if (stats)
		memset(stats, 0, sizeof *stats);
	if (!def || !s || n < 1 || !ws || !options || !alloc || !alloc->alloc || !alloc->free)
		return POOL_ERR_INVALID_ARGUMENT;
	const int eta = options->eta;
	if (eta < 4 || eta > POOL_LINK_ETA_MAX || eta % 2)
		return POOL_ERR_INVALID_ARGUMENT;
	if (isnan(dt) || !isfinite(dt))
		return POOL_ERR_NON_FINITE;
	if (!(dt > 0.0))
		return POOL_ERR_INVALID_ARGUMENT;
	for (int k = 0; k < n; ++k)
		if (!finite_state(&s[k]))
			return POOL_ERR_NON_FINITE;

	const pool_table_shape *shape = ws->shape && ws->shape->table.pockets == POOL_POCKETS_JAWS ? ws->shape : NULL;
	link_scene sc = {def, shape, s, n, !def->airborne, 0.0, dt};
	sc.reach = speed_bound(&sc, dt) * dt;
	const int nc = find_contacts(&sc, NULL);
	if (nc > POOL_LINK_CONTACTS_MAX)
		return POOL_ERR_OUT_OF_MEMORY;

	link_problem P;
	memset(&P, 0, sizeof P);
	const double mass = def->params.ball_mass, R = def->params.ball_radius, inertia = 0.4 * mass * R * R;
	for (int e = 0; e < 6; ++e)
		P.inv[e] = e < 3 ? 1.0 / mass : 1.0 / inertia;
	P.n = n;
	P.nc = nc;
	P.eta = eta;
	P.dirs = 1 + eta;
	P.L = nc * (eta + 2);
	P.stick_slip = 0.5 * 3.5 * def->params.mu_slide * def->params.g * dt;
	// The matrix's nonzeros are known once the contacts are: laid out for the workspace's room
	// (at least what contacts sharing a ball with four others each need), and again when this
	// step needs more.
	pool_result r = POOL_OK;
	const size_t dirs = (size_t)P.dirs;
	size_t room = (size_t)nc * (dirs * (POOL_LINK_NEAR_GUESS * dirs + 1) + (size_t)eta);
	if (room < ws->matrix_nonzeros)
		room = ws->matrix_nonzeros;
	for (int pass = 0; pass < 2; ++pass) {
		r = reserve(ws, alloc, layout(NULL, n, nc, eta, room, NULL));
		if (r)
			return r;
		layout(ws->memory, n, nc, eta, room, &P.m);
		find_contacts(&sc, P.m.contacts);
		P.c = P.m.contacts;
		build_incidence(&P);
		const size_t nnz = matrix_nonzeros(&P);
		if (nnz <= room)
			break;
		room = nnz;
	}
	ws->matrix_nonzeros = room;

	free_velocities(&sc, P.c, nc, dt, P.m.V);
	memcpy(P.m.V_free, P.m.V, sizeof(double) * 6 * (size_t)n);
	build_directions(&P, options->align_friction);
	build_vector(&P, dt);

	// Warm start: each contact's basis from the last step that solved it (none: all w basic,
	// right for a contact that stays open).
	pool_link_recall_bases(&P, s, &ws->bases);
	// The friction LCP always has a solution, but its degeneracy (every unused friction
	// direction of a sticking contact at w = 0) can defeat Lemke's tie-breaking in floating
	// point: a false ray, or a residual above the limit. Each failure is retried from a cold
	// start with a compliance of POOL_LINK_REGULARIZATION (then 1000 times that) on the
	// diagonal: a contact yielding 1e-9 (1e-6) m/s per m/s of impulse, far below anything the
	// step resolves. The friction directions take it first, alone, where the degeneracy is: a
	// compliant normal lets its ball into what presses it by the compliance times the impulse,
	// a ball on the cloth sinking at 1e-6 g dt (6e-8 m/s over a 6 ms step), and a cluster that
	// needed it step after step (the soak's extreme_params seeds 44 and 48, every cushion
	// friction 1) sank 1.5 to 5.5 nm, which putting the balls back onto the cloth turned into energy
	// from nowhere. The whole impulse block takes it next (redundant normals, a ball pressed
	// from several sides at once), and the last retry drops the alignment of the friction
	// directions with the slips (the fixed directions of the 2012 work): a slip that barely
	// exceeds POOL_LINK_ALIGN_SLIP puts a direction exactly along a contact velocity rounding
	// cannot resolve, and the soak's rare failures with every compliance above (a ball rolling
	// to within 1e-5 m/s while rubbing a neighbour) solve at once without it. That step's
	// friction is then off its slip by at most pi / eta. Every attempt's residual is checked.
	typedef struct retry {
		double friction_compliance, normal_compliance;
		int align;
	} retry;
	const double soft = POOL_LINK_REGULARIZATION, softer = 1e3 * POOL_LINK_REGULARIZATION;
	const int align = options->align_friction;
	const retry ladder[] = {{0.0, 0.0, align},       {soft, 0.0, align},       {softer, 0.0, align},
	                        {soft, soft, align},     {softer, softer, align},  {0.0, 0.0, 0}};
	const size_t attempts = sizeof ladder / sizeof ladder[0] - (align ? 0 : 1);
	pool_lemke_stats ls;
	memset(&ls, 0, sizeof ls);
	pool_lemke_status status = POOL_LEMKE_BAD_INPUT;
	int pivots = 0;
	if (pool_link_solve_from_basis(&P, mass, &ls.residual)) {
		status = POOL_LEMKE_SOLVED;
		ls.warm = 1;
	}
	// Otherwise Lemke pivots from that basis (lemke.h), or from scratch.
	for (size_t attempt = 0; attempt < attempts && status != POOL_LEMKE_SOLVED; ++attempt) {
		if (attempt > 0 && ladder[attempt].align != ladder[attempt - 1].align) {
			build_directions(&P, ladder[attempt].align);
			build_vector(&P, dt);
		}
		build_matrix(&P, mass, ladder[attempt].friction_compliance, ladder[attempt].normal_compliance);
		if (attempt > 0)
			for (int i = 0; i < P.L; ++i)
				P.m.basis[i] = 0;
		memset(&ls, 0, sizeof ls);
		status = pool_lemke_solve_columns(P.L, P.m.col_start, P.m.col_row, P.m.col_val, P.m.q, P.m.z, P.m.basis, 0,
		                                  P.m.lemke, &ls);
		pivots += ls.pivots;
		if (status == POOL_LEMKE_SOLVED || status == POOL_LEMKE_RESIDUAL) {
			// (Lemke's workspace, done with, holds w)
			ls.residual = velocity_residual(&P, P.m.z, (double *)P.m.lemke);
			if (ls.residual <= POOL_LINK_RESIDUAL_MAX) {
				status = POOL_LEMKE_SOLVED;
				break;
			}
			status = POOL_LEMKE_RESIDUAL;
		}
	}
	if (stats) {
		stats->contacts = nc;
		stats->pivots = pivots;
		stats->warm = ls.warm;
		stats->residual = ls.residual;
		stats->lcp_size = P.L;
	}
	if (status != POOL_LEMKE_SOLVED)
		return POOL_ERR_INTERNAL;

	for (int i = 0; i < nc * (eta + 1); ++i)
		P.m.z[i] *= mass; // back to impulses (build_matrix's velocity units)
	apply_impulses(&P);
	for (int k = 0; k < 6 * n; ++k)
		if (!isfinite(P.m.V[k]))
			return POOL_ERR_INTERNAL;
	if (sc.planar)
		for (int k = 0; k < n; ++k)
			P.m.V[6 * k + 2] = 0.0;
	pool_link_store_bases(&P, s, &ws->bases, alloc);

	// What presses each ball: the push its ball-ball and cushion contacts carried over the step,
	// as a speed (dt fn / m), touching at the start or closed by the step.
	ws->ball_push = P.m.ball_push;
	ws->ball_touching = P.m.ball_touching;
	step_tail(&sc, P.c, nc, dt, P.m.V, P.m.tail);
	ws->ball_tail = P.m.tail;
	if (sc.planar)
		for (int k = 0; k < n; ++k)
			P.m.tail[6 * k + 2] = 0.0;
	for (int k = 0; k < n; ++k) {
		P.m.ball_push[k] = 0.0;
		P.m.ball_touching[k] = 0;
	}
	for (int i = 0; i < nc; ++i) {
		const link_contact *c = &P.c[i];
		if (c->kind == LINK_CLOTH)
			continue;
		const double push = P.m.z[row_of(&P, i, 0)] / mass;
		const int touching = c->gap <= POOL_LINK_TOUCH_GAP;
		for (int side = 0; side < (c->kind == LINK_BALL ? 2 : 1); ++side) {
			const int k = side ? c->b : c->a;
			P.m.ball_push[k] = fmax(P.m.ball_push[k], push);
			P.m.ball_touching[k] += touching;
		}
	}
	if (stats)
		for (int k = 0; k < n; ++k) {
			// The contacts' change of the ball's horizontal velocity and of its surface speed
			// (a ball held against a rail by cloth friction changes its spin, not its velocity;
			// the cloth's cancelling of gravity is no change of motion).
			const double *a = P.m.V + 6 * k, *b = P.m.V_free + 6 * k;
			double dv = 0.0, dw = 0.0;
			for (int e = 0; e < 3; ++e) {
				if (e < 2)
					dv += (a[e] - b[e]) * (a[e] - b[e]);
				dw += (a[e + 3] - b[e + 3]) * (a[e + 3] - b[e + 3]);
			}
			const double change = sqrt(dv) + R * sqrt(dw);
			stats->max_contact_accel = fmax(stats->max_contact_accel, change / dt);
		}
	if (stats)
		for (int i = 0; i < nc; ++i) {
			if (!(P.c[i].gap <= POOL_LINK_TOUCH_GAP))
				continue;
			if (P.c[i].kind != LINK_CLOTH) {
				++stats->touching;
				stats->max_push = fmax(stats->max_push, P.m.z[row_of(&P, i, 0)] / mass);
			}
			stats->max_contact_speed = fmax(stats->max_contact_speed, pool_v3_len(contact_velocity(&P.c[i], P.m.V)));
		}
	for (int k = 0; k < n; ++k) {
		const double *v = P.m.V + 6 * k;
		s[k].vel = pool_v3(v[0], v[1], v[2]);
		s[k].omega = pool_v3(v[3], v[4], v[5]);
	}
	return POOL_OK;
}

pool_result pool_link_step(const pool_sim_def *def, pool_ball_state *s, int n, double dt, pool_link_workspace *ws,
                           const pool_allocator *alloc, pool_link_step_stats *stats) {
	const pool_link_options options = POOL_LINK_OPTIONS_DEFAULT;
	return pool_link_step_with(def, s, n, dt, &options, ws, alloc, stats);
}
