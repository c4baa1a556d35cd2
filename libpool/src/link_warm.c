// A LINK step's warm start (link_problem.h): the step's basis kept by contact, and solving that
// basis without the LCP's matrix.
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "lemke.h"
#include "link_problem.h"
#include "vec3.h"

/// The warm start's elimination treats a pivot below this fraction of its column's largest
/// entry as zero (the basis is then singular and Lemke solves the step), Lemke's own rule.
#define POOL_LINK_SINGULAR_REL 1e-14

/// Who contact c is between (link_basis.h): its kind, the ball ids, the rail of a cushion.
static pool_link_contact_id contact_id(const link_contact *c, const pool_ball_state *s) {
	const pool_link_contact_id id = {(int32_t)c->kind, s[c->a].id,
	                                 c->kind == LINK_BALL ? s[c->b].id : (int32_t)c->rail};
	return id;
}

/// The basic unknowns B[0..k) decoded into u (once: the k x k system reads each k times).
static void decode_unknowns(const link_problem *P, const int *B, int k, double mass, link_warm_unknown *u) {
	for (int p = 0; p < k; ++p) {
		unknown_of(P, B[p], &u[p].contact, &u[p].dir);
		if (u[p].dir >= 0)
			impulse_column(P, u[p].contact, u[p].dir, mass, u[p].h);
	}
}

/// Entry (r, c) of the LCP matrix as build_matrix makes it (without a compliance), for two
/// decoded unknowns: coupling, 1 (E), -1 (-E') and mu inside a contact, 0 elsewhere.
static double matrix_entry(const link_problem *P, const link_warm_unknown *r, const link_warm_unknown *c) {
	if (r->dir < 0) // a lambda row: mu fn - E' beta of its own contact
		return r->contact != c->contact || c->dir < 0 ? 0.0 : c->dir == 0 ? P->c[r->contact].mu : -1.0;
	if (c->dir < 0) // the lambda column: E on its contact's friction rows
		return r->contact == c->contact && r->dir > 0 ? 1.0 : 0.0;
	const link_shared sh = shared_sides(P, r->contact, c->contact);
	return coupling(P, r->contact, r->dir, &sh, c->h);
}

/// Solves the k x k system S y = b in place (Gaussian elimination, partial pivoting; y in b).
/// Returns -1 when S is numerically singular (a pivot below POOL_LINK_SINGULAR_REL of its
/// column's largest entry).
static int solve_dense(double *S, double *b, int k) {
	for (int c = 0; c < k; ++c) {
		int best = c;
		double big = 0.0, colmax = 0.0;
		for (int r = 0; r < k; ++r) {
			const double e = fabs(S[r * k + c]);
			colmax = e > colmax ? e : colmax;
			if (r >= c && e > big)
				big = e, best = r;
		}
		if (!(big > POOL_LINK_SINGULAR_REL * colmax) || !isfinite(big))
			return -1;
		if (best != c) {
			for (int e = 0; e < k; ++e) {
				const double t = S[c * k + e];
				S[c * k + e] = S[best * k + e];
				S[best * k + e] = t;
			}
			const double t = b[c];
			b[c] = b[best];
			b[best] = t;
		}
		for (int r = c + 1; r < k; ++r) {
			const double f = S[r * k + c] / S[c * k + c];
			if (f == 0.0)
				continue;
			for (int e = c; e < k; ++e)
				S[r * k + e] -= f * S[c * k + e];
			b[r] -= f * b[c];
		}
	}
	for (int r = k - 1; r >= 0; --r) {
		double sum = b[r];
		for (int e = r + 1; e < k; ++e)
			sum -= S[r * k + e] * b[e];
		b[r] = sum / S[r * k + r];
	}
	return 0;
}

/// A touching contact no step has solved yet is guessed pressed (the cluster formed because
/// its balls press), sliding against its slip when its first friction direction lies along one
/// (its lambda and the opposite direction basic), else sticking with no friction: right for a
/// ball on the cloth and for most pushes, so the first step of a cluster rarely needs Lemke.
static void guess_basis(link_problem *P, int i) {
	const link_contact *c = &P->c[i];
	if (!(c->gap <= POOL_LINK_TOUCH_GAP))
		return; // open: all w basic
	P->m.basis[row_of(P, i, 0)] = 1;
	if (!P->aligned)
		return;
	const pool_vec3 u = contact_velocity(c, P->m.V);
	const pool_vec3 ut = pool_v3_madd(u, -pool_v3_dot(u, c->n), c->n);
	if (pool_v3_len(ut) > align_slip_of(P, c)) {
		P->m.basis[lambda_of(P, i)] = 1;
		P->m.basis[row_of(P, i, 1 + P->eta / 2)] = 1;
	}
}

void pool_link_recall_bases(link_problem *P, const pool_ball_state *s, const pool_link_bases *bases) {
	for (int j = 0; j < P->L; ++j)
		P->m.basis[j] = 0;
	for (int i = 0; i < P->nc; ++i) {
		pool_link_contact_basis b;
		if (!pool_link_bases_find(bases, contact_id(&P->c[i], s), &b)) {
			guess_basis(P, i);
			continue;
		}
		P->m.basis[row_of(P, i, 0)] = b.normal;
		P->m.basis[lambda_of(P, i)] = b.lambda;
		for (int j = 1; j < P->dirs; ++j)
			P->m.basis[row_of(P, i, j)] = (int)((b.friction >> (j - 1)) & 1u);
	}
}

/// Keeps each contact's part of the solved basis for the next step. A table that cannot grow
/// loses the bases it has no room for: the steps stay right, the next ones solve cold.
void pool_link_store_bases(const link_problem *P, const pool_ball_state *s, pool_link_bases *bases,
                           const pool_allocator *alloc) {
	for (int i = 0; i < P->nc; ++i) {
		pool_link_contact_basis b = {0, (uint8_t)(P->m.basis[row_of(P, i, 0)] != 0),
		                             (uint8_t)(P->m.basis[lambda_of(P, i)] != 0)};
		for (int j = 1; j < P->dirs; ++j)
			if (P->m.basis[row_of(P, i, j)])
				b.friction |= (uint64_t)1 << (j - 1);
		if (pool_link_bases_store(bases, alloc, contact_id(&P->c[i], s), b))
			return;
	}
}

/// The previous step's basis, tried before any matrix is built: a cluster's contacts rarely
/// change between steps, so its basic unknowns (per touching contact the normal, lambda and
/// one or two friction directions: k of L, k ~ L / 6) usually still solve it. Their k x k
/// system M_BB z_B = -q_B is formed from matrix_entry and the answer (rounding below zero
/// clamped) is accepted when every row of w = M z + q passes the step's velocity residual at
/// Lemke's bound, POOL_LEMKE_RESIDUAL_MAX relative to 1 + max |q| (stricter than Lemke's own
/// test, relative to the size of the terms, and than the POOL_LINK_RESIDUAL_MAX a step accepts).
/// w comes from the velocities the impulses make (M z is J' of them), so the whole check costs
/// L + k^3 / 3 operations, where Lemke needs the matrix's nonzeros built first: 3-4 us instead
/// of 17 for a pushing pair. Returns 1 with P->m.z set (velocity units) and *residual.
int pool_link_solve_from_basis(link_problem *P, double mass, double *residual) {
	const int L = P->L;
	int *B = P->m.basic, k = 0;
	for (int j = 0; j < L; ++j)
		if (P->m.basis[j])
			B[k++] = j;
	if (k > POOL_LINK_WARM_BASIC_MAX)
		return 0;
	link_warm_unknown *u = P->m.warm;
	decode_unknowns(P, B, k, mass, u);
	double *S = P->m.S, *y = P->m.S + (size_t)k * (size_t)k;
	for (int p = 0; p < k; ++p) {
		for (int t = 0; t < k; ++t)
			S[p * k + t] = matrix_entry(P, &u[p], &u[t]);
		y[p] = -P->m.q[B[p]];
	}
	if (solve_dense(S, y, k))
		return 0;
	double *z = P->m.z;
	for (int j = 0; j < L; ++j)
		z[j] = 0.0;
	for (int p = 0; p < k; ++p)
		z[B[p]] = y[p] > 0.0 ? y[p] : 0.0;
	// The velocity change the impulses make (z in velocity units: impulse / mass), in the
	// tail's memory (step_tail fills it after the solve).
	double *dV = P->m.tail;
	for (int e = 0; e < 6 * P->n; ++e)
		dV[e] = 0.0;
	for (int p = 0; p < k; ++p) {
		if (u[p].dir < 0 || z[B[p]] == 0.0)
			continue;
		const link_contact *c = &P->c[u[p].contact];
		for (int side = 0; side < (c->b >= 0 ? 2 : 1); ++side) {
			double *d = dV + 6 * (side ? c->b : c->a);
			for (int e = 0; e < 6; ++e)
				d[e] += z[B[p]] * u[p].h[side][e];
		}
	}
	double worst = 0.0, qmax = 0.0;
	for (int i = 0; i < P->nc; ++i) {
		const link_contact *c = &P->c[i];
		double friction = 0.0;
		for (int j = 0; j < P->dirs; ++j) {
			const size_t r = row_of(P, i, j);
			double w = P->m.q[r];
			for (int side = 0; side < (c->b >= 0 ? 2 : 1); ++side) {
				const double *g = directions(P, i, side) + 6 * j, *d = dV + 6 * (side ? c->b : c->a);
				w += g[0] * d[0] + g[1] * d[1] + g[2] * d[2] + g[3] * d[3] + g[4] * d[4] + g[5] * d[5];
			}
			if (j > 0) {
				w += z[lambda_of(P, i)];
				friction += z[r];
			}
			const double term = -w > (z[r] < w ? z[r] : w) ? -w : (z[r] < w ? z[r] : w);
			worst = term > worst || term != term ? term : worst; // (NaN sticks)
			qmax = fabs(P->m.q[r]) > qmax ? fabs(P->m.q[r]) : qmax;
		}
		const size_t l = lambda_of(P, i);
		const double w = c->mu * z[row_of(P, i, 0)] - friction;
		worst = fmax(worst, fmax(-w, fmin(z[l], w)));
	}
	*residual = isfinite(worst) ? worst / (1.0 + qmax) : INFINITY;
	return *residual <= POOL_LEMKE_RESIDUAL_MAX;
}
