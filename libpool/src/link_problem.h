// The inside of a LINK step (link_step.c), shared with its warm start (link_warm.c): the contacts,
// the step's memory, the problem's layout of unknowns and the few helpers both use.
#ifndef POOL_LINK_PROBLEM_H
#define POOL_LINK_PROBLEM_H

#include <math.h>
#include <stddef.h>

#include "link_step.h"
#include "vec3.h"

/// m/s, tangential slip below which a contact's friction directions are not aligned with it
/// (its direction is then rounding noise): fixed directions instead.
#define POOL_LINK_ALIGN_SLIP 1e-9

/// Basic unknowns above which the warm start goes straight to Lemke rather than solve their
/// system densely itself (k^3 / 3): a rack's cluster keeps about 150 basic.
#define POOL_LINK_WARM_BASIC_MAX 256

typedef enum link_kind { LINK_BALL = 0, LINK_CLOTH = 1, LINK_CUSHION = 2 } link_kind;

/// One contact of the step: ball a (body 1) against ball b, the cloth or a cushion nose.
typedef struct link_contact {
	link_kind kind;
	int a, b;         ///< ball indices; b = -1 for the cloth and the cushions
	int cushion;      ///< which cushion, for the warm start: the rail + 4 times the piece of its
	                  ///< nose (geometry.h), or with pockets "jaws" 4 + the part of the nose curve;
	                  ///< -1 for the cloth and ball pairs
	pool_vec3 n;      ///< unit normal, towards ball a
	pool_vec3 ra, rb; ///< from each centre to the contact point
	double gap;       ///< m, distance between the surfaces (< 0: penetration)
	double bend;      ///< m, the most the linearised gap can overstate the true one at the step's
	                  ///< end (a jaw's arc seen from its concave side, link_step.c); else 0
	double mu;        ///< friction of the pair
} link_contact;

/// A contact's place in a ball's incidence list: the contact and which side the ball is on.
typedef struct link_incidence {
	int contact;
	int side; ///< 0: ball a, 1: ball b
} link_incidence;

/// Velocity of ball k's material point at offset r from its centre.
static inline pool_vec3 point_velocity(const double *V, int k, pool_vec3 r) {
	const double *v = V + 6 * k;
	return pool_v3_add(pool_v3(v[0], v[1], v[2]), pool_v3_cross(pool_v3(v[3], v[4], v[5]), r));
}

/// Relative velocity at a contact: ball a's contact point minus the other body's.
static inline pool_vec3 contact_velocity(const link_contact *c, const double *V) {
	pool_vec3 u = point_velocity(V, c->a, c->ra);
	if (c->b >= 0)
		u = pool_v3_sub(u, point_velocity(V, c->b, c->rb));
	return u;
}

/// A basic unknown of the warm start (link_warm.c): its contact and direction (unknown_of), and
/// for an impulse its M^-1 J column per side, times the mass (the LCP's velocity units).
typedef struct link_warm_unknown {
	int contact, dir;
	double h[2][6];
} link_warm_unknown;

typedef struct link_memory {
	int *basis;            // L
	int *basic;            // L: the warm start's basic unknowns
	double *S;             // the warm start's k x k system and right-hand side, k <= POOL_LINK_WARM_BASIC_MAX
	link_warm_unknown *warm; // the warm start's k basic unknowns, decoded
	int *col_start;        // L + 1: the LCP matrix by columns (lemke.h), nonzeros only
	int *col_row;          // nnz_max
	double *col_val;       // nnz_max
	int *near;             // nc: scratch, the contacts sharing a ball with one contact
	double *q, *z;         // L
	double *V;             // 6 n: free velocities, then the step's
	double *G;             // nc x 2 x (1 + eta) x 6: generalized directions, per side
	link_contact *contacts; // nc
	link_incidence *inc;   // 2 nc
	int *inc_start;        // n + 1
	double *ball_push;     // n
	int *ball_touching;    // n
	double *tail;          // 6 n: end-of-step velocity less the mean (half the cloth wrenches)
	double *V_free;        // 6 n: the free velocities, kept to measure the contacts' effect
	void *lemke;
} link_memory;

/// What the building blocks of a step share.
typedef struct link_problem {
	link_memory m;
	const link_contact *c;
	int n, nc, eta, dirs, L;
	double inv[6]; ///< M^-1 of a ball: 1/m three times, 1/I three times
	double stick_slip; ///< m/s, cloth slip the step's cloth friction surely stops (build_directions)
	int aligned;       ///< the friction directions lie along the slips (build_directions)
} link_problem;

/// Contact i's side of ball a (side 0) or b (side 1): its dirs generalized directions, 6 each.
static inline double *directions(const link_problem *P, int i, int side) {
	return P->m.G + ((size_t)i * 2 + (size_t)side) * (size_t)P->dirs * 6;
}

/// Index in x of contact i's direction j (0 the normal, 1 ... eta friction): friction first,
/// then the normals, then the lambdas, as docs/physics.md orders them.
static inline size_t row_of(const link_problem *P, int i, int j) {
	return (size_t)(j == 0 ? P->nc * P->eta + i : i * P->eta + j - 1);
}
static inline size_t lambda_of(const link_problem *P, int i) { return (size_t)(P->nc * (P->eta + 1) + i); }

/// Unknown r of the LCP: its contact, and its direction (0 the normal, 1 ... eta friction, -1
/// the contact's lambda); the inverse of row_of and lambda_of.
static inline void unknown_of(const link_problem *P, int r, int *contact, int *dir) {
	const int friction = P->nc * P->eta, impulses = friction + P->nc;
	if (r < friction) {
		*contact = r / P->eta;
		*dir = 1 + r % P->eta;
	} else if (r < impulses) {
		*contact = r - friction;
		*dir = 0;
	} else {
		*contact = r - impulses;
		*dir = -1;
	}
}

/// M^-1 times contact i's generalized direction j, per side, times the mass (the LCP's velocity
/// units): an impulse unknown's column before a row's J' meets it (coupling).
static inline void impulse_column(const link_problem *P, int i, int j, double mass, double h[2][6]) {
	const link_contact *c = &P->c[i];
	for (int side = 0; side < (c->b >= 0 ? 2 : 1); ++side) {
		const double *g = directions(P, i, side) + 6 * j;
		for (int e = 0; e < 6; ++e)
			h[side][e] = P->inv[e] * g[e] * mass;
	}
}

/// The sides through which contacts i1 and i2 share a ball: none, one, or two (a contact with
/// itself, between two balls).
typedef struct link_shared {
	int count;
	int s1[2], s2[2];
} link_shared;

static inline link_shared shared_sides(const link_problem *P, int i1, int i2) {
	const link_contact *c1 = &P->c[i1], *c2 = &P->c[i2];
	link_shared sh = {0, {0, 0}, {0, 0}};
	for (int s1 = 0; s1 < (c1->b >= 0 ? 2 : 1); ++s1)
		for (int s2 = 0; s2 < (c2->b >= 0 ? 2 : 1); ++s2)
			if ((s1 ? c1->b : c1->a) == (s2 ? c2->b : c2->a)) {
				sh.s1[sh.count] = s1;
				sh.s2[sh.count++] = s2;
			}
	return sh;
}

/// The LCP matrix's entry between the impulse row of contact i1's direction j1 and an impulse
/// column h (impulse_column) of a contact sharing sh with it: J' M^-1 J over the shared balls.
static inline double coupling(const link_problem *P, int i1, int j1, const link_shared *sh, const double h[2][6]) {
	double w = 0.0;
	for (int q = 0; q < sh->count; ++q) {
		const double *a = directions(P, i1, sh->s1[q]) + 6 * j1, *b = h[sh->s2[q]];
		w += a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
	}
	return w;
}

/// coupling without a link_shared: the shared balls found as it goes, in the same order (the
/// same sum, bit for bit). For one entry at a time (the warm start's), where building and
/// returning the struct stalled on its store (16 % of the warm start's time).
static inline double coupling_of(const link_problem *P, int i1, int j1, int i2, const double h[2][6]) {
	const link_contact *c1 = &P->c[i1], *c2 = &P->c[i2];
	double w = 0.0;
	for (int s1 = 0; s1 < (c1->b >= 0 ? 2 : 1); ++s1)
		for (int s2 = 0; s2 < (c2->b >= 0 ? 2 : 1); ++s2)
			if ((s1 ? c1->b : c1->a) == (s2 ? c2->b : c2->a)) {
				const double *a = directions(P, i1, s1) + 6 * j1, *b = h[s2];
				w += a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
			}
	return w;
}

/// m/s, the tangential slip above which contact c's first friction direction lies along it.
static inline double align_slip_of(const link_problem *P, const link_contact *c) {
	return c->kind == LINK_CLOTH ? fmax(POOL_LINK_ALIGN_SLIP, P->stick_slip) : POOL_LINK_ALIGN_SLIP;
}

/// Sets P->m.basis from each contact's kept basis (link_basis.h), a guess for a contact no step
/// has solved yet.
void pool_link_recall_bases(link_problem *P, const pool_ball_state *s, const pool_link_bases *bases);

/// Keeps each contact's part of the solved basis P->m.basis for the next step.
void pool_link_store_bases(const link_problem *P, const pool_ball_state *s, pool_link_bases *bases,
                           const pool_allocator *alloc);

/// Solves the step from the basis P->m.basis, or a mend of it, without the matrix (link_warm.c
/// says how); 1 with P->m.z (velocity units) and *residual when one solves it, else 0 with
/// P->m.basis unchanged. Uses the matrix's column memory (col_start, col_row) as scratch.
int pool_link_solve_from_basis(link_problem *P, double mass, double *residual);

#endif
