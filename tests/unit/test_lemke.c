// Lexicographic Lemke (lemke.h): every answer is checked here from M and q alone (w = M z + q in
// long double), never with the solver's own numbers.
//   - random frictional-contact LCPs with the LINK structure (lemke_friction_lcp.h) for K = 1 to
//     20 contacts (three clusters each), then K = 30, 40, 50, 65, 80, 100 (one each): the sizes a
//     LINK step meets, then a stride up to 100, within ~30 s of a Debug+ASan build on 2 cores;
//   - the degenerate variants: mu = 0, b = 0, repeated contacts, one shared normal, contacts
//     with zero rows, and all of them at once;
//   - small copositive-plus LCPs (n <= 8) against brute force over all 2^n complementary bases:
//     Lemke must solve exactly those that have a solution (for copositive-plus M a ray proves
//     infeasibility);
//   - the warm start, bad input, non-copositive M, the pivot budget, and determinism.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "lemke.h"
#include "lemke_friction_lcp.h"

/// Acceptance of an answer, relative to the size of the terms summed in w = M z + q (its
/// rounding scale): w_i >= -TL_TOL scale, sum z_i |w_i| <= TL_TOL scale sum z_i (z'w = 0 to 1e-10
/// relative), z_i >= 0 exactly (the solver clamps rounding).
#define TL_TOL 1e-10

/// Brute force's tolerance on z_S >= 0 and w >= 0, relative to the same scale: a basis whose
/// values are that close to feasible is taken as a solution. Random problems sit far from this
/// boundary (the generator's seeds are fixed).
#define TL_BRUTE_TOL 1e-9

/// Warm and cold answers of a problem with a unique solution agree to this, relative to max |z|.
#define TL_SAME 1e-12

typedef struct tl_check {
	double neg_w;  ///< max(-w_i) / scale
	double compl;  ///< sum z_i |w_i| / (scale sum z_i)
	double scale;
	int neg_z;     ///< some z_i < 0
} tl_check;

static tl_check tl_verify(int n, const double *M, const double *q, const double *z) {
	tl_check c = {0, 0, 0, 0};
	long double zsum = 0, cw = 0;
	long double *w = malloc((size_t)n * sizeof *w);
	for (int i = 0; i < n; ++i) {
		long double sum = q[i], size = fabsl((long double)q[i]);
		for (int j = 0; j < n; ++j) {
			long double t = (long double)M[(size_t)i * (size_t)n + (size_t)j] * z[j];
			sum += t;
			size += fabsl(t);
		}
		w[i] = sum;
		if ((double)size > c.scale)
			c.scale = (double)size;
		if (z[i] < 0 || !(z[i] == z[i]))
			c.neg_z = 1;
		zsum += z[i];
	}
	double scale = c.scale > 0 ? c.scale : 1.0;
	for (int i = 0; i < n; ++i) {
		if ((double)(-w[i]) / scale > c.neg_w)
			c.neg_w = (double)(-w[i]) / scale;
		cw += (long double)z[i] * fabsl(w[i]);
	}
	c.compl = zsum > 0 ? (double)(cw / (scale * zsum)) : 0.0;
	free(w);
	return c;
}

static int tl_is_solution(int n, const double *M, const double *q, const double *z) {
	tl_check c = tl_verify(n, M, q, z);
	return !c.neg_z && c.neg_w <= TL_TOL && c.compl <= TL_TOL;
}

// Solves and asserts an independently verified solution. Returns the stats.
static pool_lemke_stats tl_solve_ok(int n, const double *M, const double *q, double *z, int *basis, const char *what) {
	void *ws = malloc(pool_lemke_workspace_bytes(n));
	pool_lemke_stats st;
	pool_lemke_status s = pool_lemke_solve(n, M, q, z, basis, 0, ws, &st);
	free(ws);
	tl_check c = tl_verify(n, M, q, z);
	if (s != POOL_LEMKE_SOLVED || c.neg_z || c.neg_w > TL_TOL || c.compl > TL_TOL)
		print_error("%s (n = %d): status %d, pivots %d, residual %.3g; -w %.3g, z'w %.3g, z<0 %d\n", what, n, s,
		            st.pivots, st.residual, c.neg_w, c.compl, c.neg_z);
	assert_int_equal(s, POOL_LEMKE_SOLVED);
	assert_false(c.neg_z);
	assert_true(c.neg_w <= TL_TOL);
	assert_true(c.compl <= TL_TOL);
	assert_true(st.residual <= POOL_LEMKE_RESIDUAL_MAX);
	return st;
}

typedef struct tl_friction {
	int K, n;
	double *A, *b;
	flcp_dir *dirs;
} tl_friction;

static tl_friction tl_friction_make_changed(int K, uint64_t seed, int flags, double v_change) {
	tl_friction f = {K, 16 * K, NULL, NULL, NULL};
	f.A = malloc((size_t)f.n * (size_t)f.n * sizeof *f.A);
	f.b = malloc((size_t)f.n * sizeof *f.b);
	f.dirs = malloc((size_t)(15 * K) * sizeof *f.dirs);
	flcp_generate(K, flcp_balls_for(K), seed, flags, v_change, f.A, f.b, f.dirs, NULL);
	return f;
}

static tl_friction tl_friction_make(int K, uint64_t seed, int flags) {
	return tl_friction_make_changed(K, seed, flags, 0.0);
}

static void tl_friction_free(tl_friction *f) {
	free(f->A);
	free(f->b);
	free(f->dirs);
}

static void tl_friction_case(int K, uint64_t seed, int flags) {
	tl_friction f = tl_friction_make(K, seed, flags);
	double *z = malloc((size_t)f.n * sizeof *z);
	char what[96];
	snprintf(what, sizeof what, "friction LCP K = %d seed %llu flags %d", K, (unsigned long long)seed, flags);
	tl_solve_ok(f.n, f.A, f.b, z, NULL, what);
	free(z);
	tl_friction_free(&f);
}

static void test_friction_random(void **state) {
	(void)state;
	for (int K = 1; K <= 20; ++K)
		for (uint64_t seed = 0; seed < 3; ++seed)
			tl_friction_case(K, 1000 * (uint64_t)K + seed, 0);
	const int stride[] = {30, 40, 50, 65, 80, 100};
	for (size_t i = 0; i < sizeof stride / sizeof *stride; ++i)
		tl_friction_case(stride[i], 7, 0);
}

static void test_friction_degenerate(void **state) {
	(void)state;
	const int flags[] = {FLCP_MU_ZERO,     FLCP_B_ZERO, FLCP_REPEATED, FLCP_SAME_NORMAL, FLCP_GHOST,
	                     FLCP_REPEATED | FLCP_SAME_NORMAL, FLCP_MU_ZERO | FLCP_SAME_NORMAL | FLCP_GHOST,
	                     FLCP_MU_ZERO | FLCP_B_ZERO | FLCP_REPEATED | FLCP_SAME_NORMAL | FLCP_GHOST};
	const int sizes[] = {1, 2, 3, 6, 12, 25};
	for (size_t f = 0; f < sizeof flags / sizeof *flags; ++f)
		for (size_t s = 0; s < sizeof sizes / sizeof *sizes; ++s)
			for (uint64_t seed = 0; seed < 2; ++seed)
				tl_friction_case(sizes[s], 77 + seed, flags[f]);
}

// b = 0: z = 0 without a pivot (every w = 0 is already feasible).
static void test_friction_b_zero(void **state) {
	(void)state;
	tl_friction f = tl_friction_make(10, 3, FLCP_B_ZERO);
	double *z = malloc((size_t)f.n * sizeof *z);
	pool_lemke_stats st = tl_solve_ok(f.n, f.A, f.b, z, NULL, "b = 0");
	assert_int_equal(st.pivots, 0);
	for (int i = 0; i < f.n; ++i)
		assert_true(z[i] == 0.0);
	free(z);
	tl_friction_free(&f);
}

// --- small LCPs against brute force ---

static flcp_rng tl_rng = {20240611};

static double tl_uniform(double lo, double hi) { return flcp_uniform(&tl_rng, lo, hi); }

// Is there a complementary basis S with z_S = -M_SS^-1 q_S >= 0 and w >= 0? (long double
// Gaussian elimination with partial pivoting over all 2^n subsets)
static int tl_brute_force(int n, const double *M, const double *q) {
	long double a[8][9];
	int S[8];
	for (unsigned mask = 0; mask < (1u << n); ++mask) {
		int k = 0;
		for (int j = 0; j < n; ++j)
			if (mask & (1u << j))
				S[k++] = j;
		for (int r = 0; r < k; ++r) {
			for (int c = 0; c < k; ++c)
				a[r][c] = M[S[r] * n + S[c]];
			a[r][k] = -q[S[r]];
		}
		int singular = 0;
		for (int c = 0; c < k && !singular; ++c) {
			int p = c;
			for (int r = c + 1; r < k; ++r)
				if (fabsl(a[r][c]) > fabsl(a[p][c]))
					p = r;
			if (fabsl(a[p][c]) < 1e-14L) {
				singular = 1;
				break;
			}
			for (int t = 0; t <= k; ++t) {
				long double x = a[c][t];
				a[c][t] = a[p][t];
				a[p][t] = x;
			}
			for (int r = 0; r < k; ++r)
				if (r != c) {
					long double f = a[r][c] / a[c][c];
					for (int t = c; t <= k; ++t)
						a[r][t] -= f * a[c][t];
				}
		}
		if (singular)
			continue;
		double z[8] = {0};
		for (int r = 0; r < k; ++r)
			z[S[r]] = (double)(a[r][k] / a[r][r]);
		tl_check c = tl_verify(n, M, q, z);
		int ok = 1;
		double scale = c.scale > 0 ? c.scale : 1.0;
		for (int j = 0; j < n; ++j)
			ok &= z[j] >= -TL_BRUTE_TOL * scale;
		if (ok && c.neg_w <= TL_BRUTE_TOL)
			return 1;
	}
	return 0;
}

enum { TL_PSD_SKEW, TL_POSITIVE, TL_FRICTION_2D, TL_SINGULAR_PSD, TL_ZERO_ROW, TL_CLASSES };
static const char *const tl_class_name[] = {"PSD + skew", "positive", "2D friction", "singular PSD", "zero row"};

// A random copositive-plus M of the given class, and q.
static int tl_small_problem(int cls, double *M, double *q) {
	int n = 1 + (int)(flcp_next(&tl_rng) % 8);
	double B[8][8];
	switch (cls) {
	case TL_PSD_SKEW:     // B'B + (S - S'): PSD, not symmetric
	case TL_SINGULAR_PSD: // B has rank < n: infeasible q occur
	case TL_ZERO_ROW: {
		int rank = cls == TL_SINGULAR_PSD ? 1 + (int)(flcp_next(&tl_rng) % (unsigned)n) : n;
		for (int r = 0; r < 8; ++r)
			for (int c = 0; c < 8; ++c)
				B[r][c] = r < rank ? tl_uniform(-1, 1) : 0.0;
		for (int i = 0; i < n; ++i)
			for (int j = 0; j < n; ++j) {
				double s = 0;
				for (int r = 0; r < 8; ++r)
					s += B[r][i] * B[r][j];
				M[i * n + j] = s;
			}
		if (cls == TL_PSD_SKEW)
			for (int i = 0; i < n; ++i)
				for (int j = i + 1; j < n; ++j) {
					double s = tl_uniform(-1, 1);
					M[i * n + j] += s;
					M[j * n + i] -= s;
				}
		if (cls == TL_ZERO_ROW) { // one row of the PSD M zeroed: copositive? not needed, brute force decides
			int r = (int)(flcp_next(&tl_rng) % (unsigned)n);
			for (int j = 0; j < n; ++j)
				M[r * n + j] = M[j * n + r] = 0.0; // row and column: still PSD
		}
		break;
	}
	case TL_POSITIVE: // strictly copositive, not PSD in general: always solvable
		for (int i = 0; i < n * n; ++i)
			M[i] = tl_uniform(0.01, 1);
		break;
	case TL_FRICTION_2D: { // one or two planar contacts: [beta+, beta-, fn] per contact, then lambda
		int K = n >= 8 ? 2 : 1;
		n = 4 * K;
		double g[8][3]; // wrench rows (planar: vx, vy, omega) for 3 K directions
		for (int c = 0; c < K; ++c) {
			double a = tl_uniform(0, 6.283185307179586), nx = cos(a), ny = sin(a), R = tl_uniform(0.5, 1.5);
			double dirs[3][2] = {{-ny, nx}, {ny, -nx}, {nx, ny}};
			for (int d = 0; d < 3; ++d) {
				double *row = g[3 * c + d];
				row[0] = dirs[d][0];
				row[1] = dirs[d][1];
				row[2] = -R * (nx * dirs[d][1] - ny * dirs[d][0]);
			}
		}
		double winv[3] = {tl_uniform(0.5, 2), 0, tl_uniform(0.5, 5)};
		winv[1] = winv[0];
		memset(M, 0, (size_t)(n * n) * sizeof *M);
		int nd = 3 * K;
		for (int i = 0; i < nd; ++i)
			for (int j = 0; j < nd; ++j) {
				double s = 0;
				for (int l = 0; l < 3; ++l)
					s += g[i][l] * winv[l] * g[j][l];
				M[i * n + j] = s;
			}
		for (int c = 0; c < K; ++c) {
			int lam = nd + c;
			double mu = tl_uniform(0, 1);
			for (int d = 0; d < 2; ++d) {
				M[(3 * c + d) * n + lam] = 1.0;
				M[lam * n + 3 * c + d] = -1.0;
			}
			M[lam * n + 3 * c + 2] = mu;
		}
		for (int i = 0; i < nd; ++i)
			q[i] = tl_uniform(-1, 1);
		for (int c = 0; c < K; ++c)
			q[nd + c] = 0.0;
		return n;
	}
	}
	for (int i = 0; i < n; ++i)
		q[i] = tl_uniform(-1, 1);
	return n;
}

static void test_small_against_brute_force(void **state) {
	(void)state;
	double M[64], q[8], z[8];
	_Alignas(16) unsigned char ws[8192];
	assert_true(pool_lemke_workspace_bytes(8) <= sizeof ws);
	for (int cls = 0; cls < TL_CLASSES; ++cls) {
		int solvable = 0, infeasible = 0;
		for (int trial = 0; trial < 400; ++trial) {
			int n = tl_small_problem(cls, M, q);
			int brute = tl_brute_force(n, M, q);
			pool_lemke_stats st;
			pool_lemke_status s = pool_lemke_solve(n, M, q, z, NULL, 0, ws, &st);
			if ((s == POOL_LEMKE_SOLVED) != brute || (s != POOL_LEMKE_SOLVED && s != POOL_LEMKE_RAY)) {
				print_error("%s trial %d n = %d: brute force %d, Lemke status %d\n", tl_class_name[cls], trial, n,
				            brute, s);
				for (int i = 0; i < n; ++i) {
					for (int j = 0; j < n; ++j)
						print_error("%.17g ", M[i * n + j]);
					print_error("| %.17g\n", q[i]);
				}
			}
			if (brute) {
				assert_int_equal(s, POOL_LEMKE_SOLVED);
				assert_true(tl_is_solution(n, M, q, z));
				++solvable;
			} else {
				assert_int_equal(s, POOL_LEMKE_RAY);
				++infeasible;
			}
		}
		print_message("%-13s %3d solvable, %3d infeasible (brute force)\n", tl_class_name[cls], solvable, infeasible);
		if (cls == TL_POSITIVE || cls == TL_PSD_SKEW)
			assert_int_equal(infeasible, 0); // strictly copositive / PSD with full-rank B: always solvable
		if (cls == TL_SINGULAR_PSD)
			assert_true(infeasible > 0); // the class does exercise rays
	}
}

// --- warm start ---

// M = B'B + skew + I (positive definite: unique solution), n = 60.
static void tl_pd_problem(int n, double *M, double *q) {
	double *B = malloc((size_t)(n * n) * sizeof *B);
	for (int i = 0; i < n * n; ++i)
		B[i] = tl_uniform(-1, 1);
	for (int i = 0; i < n; ++i) {
		for (int j = 0; j < n; ++j) {
			double s = i == j ? 1.0 : 0.0;
			for (int r = 0; r < n; ++r)
				s += B[r * n + i] * B[r * n + j];
			M[i * n + j] = s;
		}
		q[i] = tl_uniform(-n, n);
	}
	for (int i = 0; i < n; ++i)
		for (int j = i + 1; j < n; ++j) {
			double s = tl_uniform(-2, 2);
			M[i * n + j] += s;
			M[j * n + i] -= s;
		}
	free(B);
}

static double tl_max_diff(int n, const double *a, const double *b) {
	double d = 0, m = 0;
	for (int i = 0; i < n; ++i) {
		d = fmax(d, fabs(a[i] - b[i]));
		m = fmax(m, fabs(a[i]));
	}
	return m > 0 ? d / m : d;
}

// Solve, change q a little, solve again from the basis: the warm start must be taken (no pivot)
// and give the cold solve's answer. scale_only: q is multiplied by 1 + 1e-7 (the LCP is
// homogeneous: the same basis stays feasible even when degenerate); else each q_i changes by a
// relative 1e-7 sin(3 i), which keeps the basis of a nondegenerate solution.
static void tl_warm_case(int n, double *M, double *q, const char *what, int scale_only) {
	double *z = malloc((size_t)n * sizeof *z), *zc = malloc((size_t)n * sizeof *zc);
	int *basis = calloc((size_t)n, sizeof *basis); // no warm start for the first solve
	pool_lemke_stats st = tl_solve_ok(n, M, q, z, basis, what);
	assert_int_equal(st.warm, 0);
	int basic = 0;
	for (int i = 0; i < n; ++i)
		basic += basis[i];
	for (int i = 0; i < n; ++i)
		q[i] *= 1.0 + 1e-7 * (scale_only ? 1.0 : sin(3.0 * i));
	pool_lemke_stats warm = tl_solve_ok(n, M, q, z, basis, what);
	pool_lemke_stats cold = tl_solve_ok(n, M, q, zc, NULL, what);
	double diff = tl_max_diff(n, zc, z);
	print_message("%s: %d basic, cold %d pivots, warm %d (%d pivots), max |z_warm - z_cold| / max |z| = %.2g\n", what,
	              basic, cold.pivots, warm.warm, warm.pivots, diff);
	assert_int_equal(cold.warm, 0);
	assert_int_equal(warm.warm, 1);
	assert_int_equal(warm.pivots, 0);
	assert_true(diff <= TL_SAME);
	free(z);
	free(zc);
	free(basis);
}

static void test_warm_start(void **state) {
	(void)state;
	enum { N = 60 };
	double *M = malloc(N * N * sizeof *M), *q = malloc(N * sizeof *q);
	tl_pd_problem(N, M, q);
	tl_warm_case(N, M, q, "positive definite n = 60", 0);
	free(M);
	free(q);
	// The friction LCP's solutions are degenerate (zero basic variables), so a generic change of
	// q can make the old basis infeasible (the cold solve then runs: checked in
	// test_warm_start_changed); a change of scale keeps it.
	const int sizes[] = {5, 20, 50};
	for (size_t i = 0; i < sizeof sizes / sizeof *sizes; ++i) {
		char what[64];
		snprintf(what, sizeof what, "friction K = %d", sizes[i]);
		tl_friction f = tl_friction_make(sizes[i], 11, 0);
		tl_warm_case(f.n, f.A, f.b, what, 1);
		tl_friction_free(&f);
	}
}

// The next step's friction LCP: same contacts, velocities changed by 1e-6 relative (the old
// basis still solves it) and by 3e-2 (contacts change roles: the old basis is repaired by a few
// pivots). Either way the answer is a solution, found from the old basis in all but a few, with
// far fewer pivots than solving each step cold. (b itself must not be perturbed freely: with
// more friction directions than ball degrees of freedom, a b outside the range of J^T's image
// can make the LCP infeasible.)
static void test_warm_start_changed(void **state) {
	(void)state;
	const double changes[2] = {1e-6, 3e-2};
	for (int c = 0; c < 2; ++c) {
		int used = 0, tried = 0, warm_pivots = 0, cold_pivots = 0;
		for (int K = 2; K <= 30; K += 4)
			for (uint64_t seed = 0; seed < 3; ++seed) {
				tl_friction f = tl_friction_make(K, 300 + seed, 0);
				double *z = malloc((size_t)f.n * sizeof *z);
				int *basis = calloc((size_t)f.n, sizeof *basis);
				tl_solve_ok(f.n, f.A, f.b, z, basis, "warm start, first step");
				tl_friction next = tl_friction_make_changed(K, 300 + seed, 0, changes[c]);
				memcpy(f.b, next.b, (size_t)f.n * sizeof *f.b);
				tl_friction_free(&next);
				pool_lemke_stats st = tl_solve_ok(f.n, f.A, f.b, z, basis, "warm start, next step");
				pool_lemke_stats cold = tl_solve_ok(f.n, f.A, f.b, z, NULL, "cold start, next step");
				used += st.warm;
				warm_pivots += st.pivots;
				cold_pivots += cold.pivots;
				++tried;
				free(z);
				free(basis);
				tl_friction_free(&f);
			}
		print_message("velocities changed by %g: warm start used in %d of %d, %d pivots (cold: %d)\n", changes[c], used,
		              tried, warm_pivots, cold_pivots);
		assert_true(used >= tried * 9 / 10);
		assert_true(warm_pivots * 5 < cold_pivots);
	}
}

// A positive definite M (unique solution) and a q changed by 30 %: the old basis no longer
// solves it, and Lemke pivots from it (covering vector B 1, lemke.c warm_pivots). For a P-matrix
// that always ends on the solution (a principal pivot transform of a P-matrix is one, and in
// the basis's coordinates the covering vector is all ones), in fewer pivots than from scratch.
static void test_warm_pivots(void **state) {
	(void)state;
	enum { N = 60 };
	double *M = malloc(N * N * sizeof *M), *q = malloc(N * sizeof *q), z[N], zc[N];
	int basis[N], repaired = 0, warm_pivots = 0, cold_pivots = 0;
	for (int trial = 0; trial < 10; ++trial) {
		tl_pd_problem(N, M, q);
		tl_solve_ok(N, M, q, z, basis, "pd, first");
		for (int i = 0; i < N; ++i)
			q[i] += 0.3 * tl_uniform(-N, N);
		pool_lemke_stats warm = tl_solve_ok(N, M, q, z, basis, "pd, from the old basis");
		pool_lemke_stats cold = tl_solve_ok(N, M, q, zc, NULL, "pd, cold");
		assert_int_equal(warm.warm, 1);
		assert_true(tl_max_diff(N, zc, z) <= TL_SAME);
		repaired += warm.pivots > 0;
		warm_pivots += warm.pivots;
		cold_pivots += cold.pivots;
	}
	print_message("q changed 30 %%: %d of 10 bases repaired by pivots, %d pivots (cold: %d)\n", repaired, warm_pivots,
	              cold_pivots);
	assert_true(repaired >= 8); // the change does spoil the basis
	assert_true(warm_pivots < cold_pivots);
	free(M);
	free(q);
}

// A basis that does not solve the problem (or is singular) is not taken as the answer: pivots
// from it or the cold solve find one that does.
static void test_warm_start_wrong_basis(void **state) {
	(void)state;
	tl_friction f = tl_friction_make(8, 5, 0);
	double *z = malloc((size_t)f.n * sizeof *z);
	int *basis = malloc((size_t)f.n * sizeof *basis);
	for (int i = 0; i < f.n; ++i)
		basis[i] = 1; // z all basic: singular (the lambda block of M is zero)
	pool_lemke_stats st = tl_solve_ok(f.n, f.A, f.b, z, basis, "all-basic warm start");
	assert_int_equal(st.warm, 0);
	for (int i = 0; i < f.n; ++i)
		basis[i] = i % 3 == 0;
	st = tl_solve_ok(f.n, f.A, f.b, z, basis, "arbitrary warm start");
	assert_true(st.pivots > 0);
	free(z);
	free(basis);
	tl_friction_free(&f);
}

// --- bad input, non-copositive M, budget, determinism ---

static void test_bad_input(void **state) {
	(void)state;
	double M[4] = {2, 1, 1, 2}, q[2] = {-1, -1}, z[2] = {0};
	_Alignas(16) unsigned char ws[512];
	assert_true(pool_lemke_workspace_bytes(2) <= sizeof ws - 1);
	assert_int_equal(pool_lemke_workspace_bytes(-1), 0);
	assert_int_equal(pool_lemke_workspace_bytes(1 << 30), 0);
	pool_lemke_stats st;
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws, &st), POOL_LEMKE_SOLVED);
	assert_int_equal(pool_lemke_solve(-1, M, q, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	assert_int_equal(pool_lemke_solve(0, NULL, NULL, NULL, NULL, 0, NULL, &st), POOL_LEMKE_SOLVED); // empty LCP
	assert_int_equal(st.pivots, 0);
	assert_int_equal(pool_lemke_solve(2, NULL, q, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	assert_int_equal(pool_lemke_solve(2, M, NULL, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	assert_int_equal(pool_lemke_solve(2, M, q, NULL, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, NULL, &st), POOL_LEMKE_BAD_INPUT);
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws + 1, &st), POOL_LEMKE_BAD_INPUT); // misaligned
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws, NULL), POOL_LEMKE_SOLVED);     // stats optional
	M[3] = NAN;
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	M[3] = INFINITY;
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	M[3] = 2;
	q[1] = -INFINITY;
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	q[1] = NAN;
	assert_int_equal(pool_lemke_solve(2, M, q, z, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
	// huge entries: finite, so solved or reported, never a crash or a wrong "solved"
	double H[4] = {1e300, -1e300, 1e300, 1e-300}, qh[2] = {-1e300, -1};
	pool_lemke_status s = pool_lemke_solve(2, H, qh, z, NULL, 0, ws, &st);
	if (s == POOL_LEMKE_SOLVED)
		assert_true(st.residual <= POOL_LEMKE_RESIDUAL_MAX);
}

// Non-copositive M: a ray is a correct answer; whatever comes back, SOLVED means a solution.
static void test_not_copositive(void **state) {
	(void)state;
	double M1[4] = {-1, 0, 0, -1}, q1[2] = {-1, -1}, z[8];
	_Alignas(16) unsigned char ws[8192];
	pool_lemke_stats st;
	assert_int_equal(pool_lemke_solve(2, M1, q1, z, NULL, 0, ws, &st), POOL_LEMKE_RAY); // w = -z - 1 < 0
	double M[64], q[8];
	int solved = 0, rays = 0;
	for (int trial = 0; trial < 300; ++trial) {
		int n = 1 + (int)(flcp_next(&tl_rng) % 8);
		for (int i = 0; i < n * n; ++i)
			M[i] = tl_uniform(-1, 1);
		for (int i = 0; i < n; ++i)
			q[i] = tl_uniform(-1, 1);
		pool_lemke_status s = pool_lemke_solve(n, M, q, z, NULL, 0, ws, &st);
		assert_true(s == POOL_LEMKE_SOLVED || s == POOL_LEMKE_RAY || s == POOL_LEMKE_MAX_PIVOTS ||
		            s == POOL_LEMKE_RESIDUAL);
		if (s == POOL_LEMKE_SOLVED) {
			assert_true(tl_is_solution(n, M, q, z));
			++solved;
		}
		rays += s == POOL_LEMKE_RAY;
	}
	print_message("random general M: %d solved, %d rays of 300\n", solved, rays);
}

static void test_pivot_budget(void **state) {
	(void)state;
	tl_friction f = tl_friction_make(10, 2, 0);
	double *z = malloc((size_t)f.n * sizeof *z);
	void *ws = malloc(pool_lemke_workspace_bytes(f.n));
	pool_lemke_stats st;
	assert_int_equal(pool_lemke_solve(f.n, f.A, f.b, z, NULL, 3, ws, &st), POOL_LEMKE_MAX_PIVOTS);
	assert_int_equal(st.pivots, 3);
	assert_int_equal(pool_lemke_solve(f.n, f.A, f.b, z, NULL, 0, ws, &st), POOL_LEMKE_SOLVED);
	assert_true(st.pivots > 3);
	free(ws);
	free(z);
	tl_friction_free(&f);
}

static void test_deterministic(void **state) {
	(void)state;
	tl_friction f = tl_friction_make(30, 9, 0);
	double *z1 = malloc((size_t)f.n * sizeof *z1), *z2 = malloc((size_t)f.n * sizeof *z2);
	void *ws = malloc(pool_lemke_workspace_bytes(f.n));
	pool_lemke_stats s1, s2;
	assert_int_equal(pool_lemke_solve(f.n, f.A, f.b, z1, NULL, 0, ws, &s1), POOL_LEMKE_SOLVED);
	memset(ws, 0xA5, pool_lemke_workspace_bytes(f.n)); // the workspace's old contents do not matter
	assert_int_equal(pool_lemke_solve(f.n, f.A, f.b, z2, NULL, 0, ws, &s2), POOL_LEMKE_SOLVED);
	assert_memory_equal(z1, z2, (size_t)f.n * sizeof *z1);
	assert_int_equal(s1.pivots, s2.pivots);
	free(ws);
	free(z1);
	free(z2);
	tl_friction_free(&f);
}

// The same problems by columns (pool_lemke_solve_columns): the same answer and path, bit for bit,
// as the dense M, cold and warm; malformed columns are refused.
static void test_columns(void **state) {
	(void)state;
	const int sizes[] = {3, 10, 30};
	for (size_t c = 0; c < sizeof sizes / sizeof *sizes; ++c) {
		tl_friction f = tl_friction_make(sizes[c], 40 + c, 0);
		const int n = f.n;
		int *start = malloc((size_t)(n + 1) * sizeof *start), *row = malloc((size_t)n * (size_t)n * sizeof *row);
		double *val = malloc((size_t)n * (size_t)n * sizeof *val);
		int t = 0;
		for (int j = 0; j < n; ++j) {
			start[j] = t;
			for (int i = 0; i < n; ++i)
				if (f.A[i * n + j] != 0.0) {
					row[t] = i;
					val[t++] = f.A[i * n + j];
				}
		}
		start[n] = t;
		double *z1 = malloc((size_t)n * sizeof *z1), *z2 = malloc((size_t)n * sizeof *z2);
		int *b1 = calloc((size_t)n, sizeof *b1), *b2 = calloc((size_t)n, sizeof *b2);
		void *ws = malloc(pool_lemke_workspace_bytes(n));
		for (int warm = 0; warm < 2; ++warm) { // cold, then from the basis of the cold solve
			pool_lemke_stats s1, s2;
			assert_int_equal(pool_lemke_solve(n, f.A, f.b, z1, b1, 0, ws, &s1), POOL_LEMKE_SOLVED);
			assert_int_equal(pool_lemke_solve_columns(n, start, row, val, f.b, z2, b2, 0, ws, &s2), POOL_LEMKE_SOLVED);
			assert_memory_equal(z1, z2, (size_t)n * sizeof *z1);
			assert_memory_equal(b1, b2, (size_t)n * sizeof *b1);
			assert_int_equal(s1.pivots, s2.pivots);
			assert_int_equal(s1.warm, warm);
			assert_int_equal(s2.warm, warm);
		}
		pool_lemke_stats st;
		if (t >= 2 && start[1] - start[0] >= 2) {
			const int keep = row[0];
			row[0] = row[1]; // not ascending
			assert_int_equal(pool_lemke_solve_columns(n, start, row, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
			row[0] = n; // out of range
			assert_int_equal(pool_lemke_solve_columns(n, start, row, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
			row[0] = keep;
		}
		const double keep_val = val[0];
		val[0] = NAN;
		assert_int_equal(pool_lemke_solve_columns(n, start, row, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
		val[0] = keep_val;
		start[0] = 1;
		assert_int_equal(pool_lemke_solve_columns(n, start, row, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
		start[0] = 0;
		const int keep_start = start[1];
		start[1] = start[2] + 1; // a column ending after the next one's end
		if (n > 2)
			assert_int_equal(pool_lemke_solve_columns(n, start, row, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
		start[1] = keep_start;
		assert_int_equal(pool_lemke_solve_columns(n, NULL, row, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
		assert_int_equal(pool_lemke_solve_columns(n, start, NULL, val, f.b, z2, NULL, 0, ws, &st), POOL_LEMKE_BAD_INPUT);
		free(ws);
		free(z1);
		free(z2);
		free(b1);
		free(b2);
		free(start);
		free(row);
		free(val);
		tl_friction_free(&f);
	}
}

int main(void) {
	const struct CMUnitTest tests[] = {
	    cmocka_unit_test(test_friction_random),
	    cmocka_unit_test(test_friction_degenerate),
	    cmocka_unit_test(test_friction_b_zero),
	    cmocka_unit_test(test_small_against_brute_force),
	    cmocka_unit_test(test_warm_start),
	    cmocka_unit_test(test_warm_start_changed),
	    cmocka_unit_test(test_warm_pivots),
	    cmocka_unit_test(test_warm_start_wrong_basis),
	    cmocka_unit_test(test_bad_input),
	    cmocka_unit_test(test_not_copositive),
	    cmocka_unit_test(test_pivot_budget),
	    cmocka_unit_test(test_deterministic),
	    cmocka_unit_test(test_columns),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
