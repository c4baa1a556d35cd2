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

/// Who contact c is between (link_basis.h): its kind, the ball ids, which cushion.
static pool_link_contact_id contact_id(const link_contact *c, const pool_ball_state *s) {
	const pool_link_contact_id id = {(int32_t)c->kind, s[c->a].id, c->kind == LINK_BALL ? s[c->b].id : (int32_t)c->cushion};
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
	return coupling_of(P, r->contact, r->dir, c->contact, c->h);
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
static void guess_friction(link_problem *P, int i);

static void guess_basis(link_problem *P, int i) {
	const link_contact *c = &P->c[i];
	if (!(c->gap <= POOL_LINK_TOUCH_GAP))
		return; // open: all w basic
	P->m.basis[row_of(P, i, 0)] = 1;
	guess_friction(P, i);
}

/// The friction part of guess_basis: sliding against the slip (lambda and the opposite
/// direction basic) when the first direction lies along one, else nothing basic. An open
/// contact takes the same: its lambda is then the slip (the rows of its directions ask
/// lambda + d_j . u >= 0), its opposite direction basic at zero.
static void guess_friction(link_problem *P, int i) {
	const link_contact *c = &P->c[i];
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
/// of 17 for a pushing pair. Returns 1 with P->m.z set (velocity units) and *residual, 0 when
/// the answer fails, -1 when the system is singular (or larger than POOL_LINK_WARM_BASIC_MAX).
/// After a regular system its k (*basic_count) basic unknowns are in P->m.basic, their values
/// before clamping after the k x k system in P->m.S, the velocity change of the clamped ones in
/// P->m.tail (mend_basis reads them).
static int solve_basis(link_problem *P, double mass, double *residual, int *basic_count) {
	const int L = P->L;
	int *B = P->m.basic, k = 0;
	for (int j = 0; j < L; ++j)
		if (P->m.basis[j])
			B[k++] = j;
	*basic_count = k;
	if (k > POOL_LINK_WARM_BASIC_MAX)
		return -1;
	link_warm_unknown *u = P->m.warm;
	decode_unknowns(P, B, k, mass, u);
	double *S = P->m.S, *y = P->m.S + (size_t)k * (size_t)k;
	for (int p = 0; p < k; ++p) {
		for (int t = 0; t < k; ++t)
			S[p * k + t] = matrix_entry(P, &u[p], &u[t]);
		y[p] = -P->m.q[B[p]];
	}
	if (solve_dense(S, y, k))
		return -1;
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
		// J dV of a direction is the direction (ball a's first three entries) dotted with the
		// change of the contact's relative velocity: one 3-vector per contact, not 12 products a
		// row.
		const pool_vec3 du = contact_velocity(c, dV);
		double friction = 0.0;
		for (int j = 0; j < P->dirs; ++j) {
			const size_t r = row_of(P, i, j);
			const double *g = directions(P, i, 0) + 6 * j;
			double w = P->m.q[r] + g[0] * du.x + g[1] * du.y + g[2] * du.z;
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

/// Friction direction d of 1 ... eta, cyclically.
static int cyclic(const link_problem *P, int d) { return ((d - 1) % P->eta + P->eta) % P->eta + 1; }

/// Mends the basis where its answer failed, contact by contact, by the role the answer says the
/// contact wants (in the manner of block principal pivoting, Judice & Pires 1994, a contact's
/// unknowns one block). The normals first: a normal impulse gone negative opens its contact (none of its unknowns
/// basic), an open contact the answer drives into its neighbour closes (pressed, with its kept
/// friction or the guess). Only when no normal is wrong, the friction, whose verdicts mean
/// little while the normal forces are wrong: a pressed contact whose friction left its cone
/// slides (lambda and its largest direction basic), one whose sliding friction went negative
/// sticks (its direction and the next), one that slips while sticking slides against the slip,
/// and a sticking force outside the sector of its two directions takes the next direction past
/// the other one. Values below -tol (Lemke's residual bound) count as negative.
/// Returns the contacts changed. y: the raw basic values, B/k: the basic unknowns.
static int mend_basis(link_problem *P, const int *B, int k, const double *y, double tol) {
	int *basis = P->m.basis, *slot = P->m.col_row; // (the matrix's rows: not built yet)
	const double *z = P->m.z, *dV = P->m.tail;
	for (int j = 0; j < P->L; ++j)
		slot[j] = -1;
	for (int p = 0; p < k; ++p)
		slot[B[p]] = p;
	int changed = 0;
	for (int phase = 0; phase < 2 && changed == 0; ++phase)
		for (int i = 0; i < P->nc; ++i) {
			const link_contact *c = &P->c[i];
			const size_t nrow = row_of(P, i, 0), lrow = lambda_of(P, i);
			double w[1 + POOL_LINK_ETA_MAX], friction = 0.0;
			int slip_dir = -1, big_dir = -1, neg_dir = -1;
			const pool_vec3 du = contact_velocity(c, dV); // (as in solve_basis)
			for (int j = 0; j < P->dirs; ++j) {
				const size_t r = row_of(P, i, j);
				const double *g = directions(P, i, 0) + 6 * j;
				w[j] = P->m.q[r] + g[0] * du.x + g[1] * du.y + g[2] * du.z;
				if (j == 0)
					continue;
				w[j] += z[lrow];
				friction += z[r];
				if (basis[r] && slot[r] >= 0 && y[slot[r]] < -tol && neg_dir < 0)
					neg_dir = j;
				if (!basis[r] && w[j] < -tol && (slip_dir < 0 || w[j] < w[slip_dir]))
					slip_dir = j;
				if (basis[r] && (big_dir < 0 || z[r] > z[row_of(P, i, big_dir)]))
					big_dir = j;
			}
			const int pressed = basis[nrow], sliding = basis[lrow];
			int mended = 1;
			if (phase == 0) {
				if (pressed && slot[nrow] >= 0 && y[slot[nrow]] < -tol) {
					for (int j = 0; j < P->dirs; ++j)
						basis[row_of(P, i, j)] = 0;
					basis[lrow] = 0;
					guess_friction(P, i);
				} else if (!pressed && w[0] < -tol) {
					basis[nrow] = 1;
					int any = basis[lrow];
					for (int j = 1; j < P->dirs; ++j)
						any |= basis[row_of(P, i, j)];
					if (!any)
						guess_basis(P, i);
				} else {
					mended = 0;
				}
			} else if (!pressed) {
				mended = 0;
			} else if (sliding && slot[lrow] >= 0 && y[slot[lrow]] < -tol && big_dir > 0) {
				basis[lrow] = 0;
				basis[row_of(P, i, cyclic(P, big_dir + 1))] = 1;
			} else if (!sliding && c->mu * z[nrow] - friction < -tol && big_dir > 0) {
				for (int j = 1; j < P->dirs; ++j)
					basis[row_of(P, i, j)] = j == big_dir;
				basis[lrow] = 1;
			} else if (neg_dir > 0) {
				int other = -1, others = 0;
				for (int j = 1; j < P->dirs; ++j)
					if (j != neg_dir && basis[row_of(P, i, j)])
						other = j, others++;
				basis[row_of(P, i, neg_dir)] = 0;
				const int next = others == 1 && !sliding ? cyclic(P, 2 * other - neg_dir) : cyclic(P, neg_dir + P->eta / 2);
				basis[row_of(P, i, next)] = 1;
			} else if (slip_dir > 0) {
				for (int j = 1; j < P->dirs; ++j)
					basis[row_of(P, i, j)] = j == slip_dir;
				basis[lrow] = 1;
			} else {
				mended = 0;
			}
			changed += mended;
		}
	return changed;
}

/// Mends the warm start tries on a kept basis that fails before Lemke pivots from it. Each costs
/// a solve of the basis (k^3 / 3); over 500 random frozen breaks, 1 / 2 / 6 / 10 mends leave
/// 593 / 505 / 298 / 245 of the 4,652 steps to Lemke (962 without), and 6 cost the fewest
/// instructions (-10 %; 10: -9 %).
#define POOL_LINK_WARM_MENDS 6

/// The kept basis (solve_basis), then up to POOL_LINK_WARM_MENDS mends of it; when none solves
/// the step, P->m.basis is the kept basis again for Lemke to pivot from.
int pool_link_solve_from_basis(link_problem *P, double mass, double *residual) {
	int k = 0;
	int status = solve_basis(P, mass, residual, &k);
	if (status != 0)
		return status > 0;
	// The kept basis is set aside (in the matrix's column starts, not built yet): Lemke starts
	// from it when no mend solves the step.
	int *kept = P->m.col_start;
	memcpy(kept, P->m.basis, sizeof(int) * (size_t)P->L);
	double qmax = 0.0;
	for (int j = 0; j < P->L; ++j)
		qmax = fmax(qmax, fabs(P->m.q[j]));
	for (int mend = 0; mend < POOL_LINK_WARM_MENDS && status == 0; ++mend) {
		const double *y = P->m.S + (size_t)k * (size_t)k;
		if (!mend_basis(P, P->m.basic, k, y, POOL_LEMKE_RESIDUAL_MAX * (1.0 + qmax)))
			break;
		status = solve_basis(P, mass, residual, &k);
	}
	if (status > 0)
		return 1;
	memcpy(P->m.basis, kept, sizeof(int) * (size_t)P->L);
	return 0;
}
