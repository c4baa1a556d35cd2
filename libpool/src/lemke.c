// Lexicographic Lemke for the LINK step's LCP (lemke.h, docs/physics.md "LINK").
//
// The system is  w - M z - e z0 = q,  w, z, z0 >= 0,  w'z = 0,  e = (1, ..., 1). A basis B holds
// n of the 2n + 1 columns [I | A], A = [-M | -e]; the basic values are x_B = B^-1 q.
//
// Why not a tableau: a full tableau (or an explicit n x n B^-1) costs 2 n^2 multiply-adds per
// pivot, 1.3 M at K = 50 contacts (n = 800), and the friction LCP takes 15 to 30 pivots per
// contact (counted: ~800 at K = 50, the same path as a long-double dense tableau). But most of
// B is unit columns, one per basic w_i. Let C be the basic columns of A (z_j or z0, k of them)
// and R the rows whose w is nonbasic (k of them too). With the rows ordered (W, R),
//     B = | I  A_WC |      B^-1 = | I  -A_WC G |      G = A_RC^-1  (k x k),
//         | 0  A_RC |             | 0   G      |
// so the solver keeps G explicitly, A_RC itself, and M in compressed columns (built once per
// solve). A pivot costs about 3 k^2 + (nonzeros of the basic columns): the entering column's
// direction d = B^-1 a (d_C = G a_R, d_W = a_W - A_WC d_C), the ratio test over the n + k basic
// variables, and one rank-1 update of G. The four pivot kinds are (a column of A or a w
// entering) x (a basic w or a basic column leaving): G grows by a border, has a row or a column
// replaced, or loses a row and a column. A LINK cluster keeps few variables basic (per touching
// contact the normal impulse, lambda and one or two of the 14 friction directions: k ~ n / 6)
// and the friction columns of M are sparse (a contact couples only with the contacts of its two
// balls), so a pivot costs a few percent of a tableau pivot: K = 50 solves in ~15 ms where a
// dense prototype took 50 ms (pool-bench-lemke).
//
// Accuracy: rank-1 updates of an inverse lose digits at small pivots. Every LEMKE_CHECK_PIVOTS
// pivots, and after any small pivot, the direction is checked against A_RC (a_R - A_RC d_C);
// when it has drifted G is rebuilt by Gauss-Jordan (k^3) and the basic values recomputed. (A
// rebuild every 100 pivots instead cost 20% of the time and still let 1 in 100 K = 50 problems
// go wrong between rebuilds.) At the end the complementary basis is solved again with one step
// of iterative refinement and the residual is checked from M and q themselves.
//
// Degeneracy: the ratio test takes the rows whose ratio ties (within LEMKE_TIE_REL of the basic
// values' scale) and breaks the tie lexicographically on the rows of [x_B, B^-1] divided by the
// pivot column, the rule under which Lemke cannot cycle and so terminates on a copositive-plus M
// (Cottle, Pang & Stone, The Linear Complementarity Problem, 4.4 and 4.9). The friction LCP is
// very degenerate (a sticking contact has all its unused friction directions at w = 0). Columns
// of B^-1 that belong to a basic w are unit vectors and cost nothing; the others are computed
// for the tied rows only. z0 leaves (ending the solve) whenever it may: when it ties, and when
// leaving at its own ratio would take no other basic variable below -LEMKE_Z0_SLACK of the
// basic values' scale (in an ill-conditioned basis the two ratios can be too close to order in
// double precision; the final solve and the residual check then decide).
//
// Warm start: the complementary basis named by `basis` is solved directly and accepted when its
// z (negative rounding clamped to 0) passes the same residual check as any answer. When it is
// regular but infeasible, the pivots start from it (warm_pivots): a next LINK step whose contacts
// changed roles (a contact starting to slide, a sticking force crossing a corner of the
// polyhedral cone) is repaired in a few pivots where a cold start takes 15 to 30 per contact.
#include "lemke.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/// G is rebuilt when a direction's residual |a_R - A_RC d_C| (or the basic values' |q_R - A_RC
/// x_C|) exceeds LEMKE_DRIFT_MAX times a bound on the size of the terms summed (see drift):
/// each rank-1 update adds rounding times the pivot's growth, and a drifted G makes ties and
/// signs unreliable (the ratio test resolves ties at 1e-12). A fresh G's residual is ~1e-16 of
/// that bound; rebuilding costs k^3.
#define LEMKE_DRIFT_MAX 1e-13

/// The direction's residual is checked every LEMKE_CHECK_PIVOTS pivots, and on the pivot after
/// one whose pivot element was below LEMKE_SMALL_PIVOT of max |d| (where G can lose digits at
/// once); the basic values' every 2 LEMKE_CHECK_PIVOTS. Between checks drift grows by rounding
/// only (measured: ~1e-15 per pivot), and a check costs as much as computing d_C.
#define LEMKE_CHECK_PIVOTS 4
#define LEMKE_SMALL_PIVOT 1e-3

/// A direction entry d_i takes part in the ratio test only when d_i > LEMKE_PIVOT_REL max|d|.
/// Near-degenerate rows (x_i and d_i both rounding-sized) otherwise win the ratio test with a
/// ratio of noise over noise, and their pivot makes the basis near singular: with 1e-11 and
/// 1e-9, 1 in 200 random K = 50 friction LCPs ended on a singular basis; with 1e-8 none of 1800
/// (K = 1 to 50, with the degenerate variants). Skipping an entry lets x_i fall by at most
/// theta d_i, 1e-8 of the step's effect on the largest basic value, usually far less.
#define LEMKE_PIVOT_REL 1e-8

/// When no entry passes LEMKE_PIVOT_REL, entries above LEMKE_PIVOT_MIN_REL max|d| are used
/// before a ray is declared: a resting LINK cluster (velocities ~1e-20) reached false rays with
/// only 1e-8-sized entries left positive.
#define LEMKE_PIVOT_MIN_REL 1e-13

/// Rows whose value after the ratio test's step, x_i - theta d_i, is within LEMKE_TIE_REL of the
/// basic values' scale of zero tie with the minimum: rounding makes exact ties (degenerate
/// vertices of the friction LCP) inexact by some ulps of the values involved.
#define LEMKE_TIE_REL 1e-12

/// z0 leaves at its own ratio when no basic variable would go below -LEMKE_Z0_SLACK times the
/// basic values' scale: ten times under the residual the answer must meet.
#define LEMKE_Z0_SLACK 1e-11

/// Two lexicographic entries tie when they differ by less than LEMKE_LEX_TIE_REL of the largest
/// among the tied rows (same reason as LEMKE_TIE_REL).
#define LEMKE_LEX_TIE_REL 1e-11

/// Gauss-Jordan treats a pivot below this fraction of its column's largest entry as zero: the
/// basis is singular (the warm start is then not used; during pivoting the solve fails).
#define LEMKE_SINGULAR_REL 1e-14

/// Pivots per basic variable of the warm basis that warm_pivots may take before the solve
/// starts cold instead (a cold start takes about 2 per unknown of a contact that ends basic).
#define LEMKE_WARM_PIVOTS_PER_BASIC 2

/// Largest n: keeps n^2 and the workspace's size within size_t and int arithmetic everywhere.
#define LEMKE_N_MAX 20000

typedef struct lemke {
	int n, k;         // k: basic columns of A = rows with a nonbasic w
	const double *q;
	const double *dense; // M row-major when the caller gave it so (entries then read directly), else NULL
	double *G;        // A_RC^-1, k x k, leading dimension n: G[slot_c * n + slot_r]
	double *ARC;      // A_RC itself, k x k, leading dimension n: ARC[slot_r * n + slot_c]
	const int *mstart; // M by columns: column j is mval/mrow[mstart[j] .. mstart[j + 1]), rows
	const int *mrow;   // ascending (the caller's arrays, or the workspace's copy of a dense M)
	const double *mval;
	int *R;           // R[slot_r] = row whose w is nonbasic
	int *C;           // C[slot_c] = column of A (j < n: z_j, n: z0)
	int *rowslot;     // row i -> slot_r, or -1 when w_i is basic
	int *colslot;     // column c -> slot_c, or -1 (n + 1 entries)
	double *x;        // basic values: x[i] of basic w_i (0 for rows in R), x[n + s] of slot s
	double *d;        // direction B^-1 a of the entering column, same layout
	double *v;        // A_iC G of a leaving row (scratch, k)
	double *ar;       // a_R (scratch, k)
	double *lexval;   // lexicographic values of the tied rows (scratch)
	int *cand;        // tied rows (scratch)
	int *perm;        // Gauss-Jordan's row interchanges (scratch)
	double *cover;    // the covering vector d: z0's column of A is -d (e, or B 1 from a warm basis)
	int *mstart_store, *mrow_store; // the workspace's compressed columns of a dense M
	double *mval_store;
	int rebuilds;     // times G was rebuilt because it had drifted
	double amax;      // max(1, max |M_ij|): the largest entry of A
	double dmax;      // max |d| of the last ratio test
} lemke;

// --- workspace ---

static size_t round16(size_t b) { return (b + 15u) & ~(size_t)15u; }

static size_t doubles_for(size_t n) { return 3 * n * n + 8 * n + 2; }
static size_t ints_for(size_t n) { return n * n + 7 * n + 4; }

size_t pool_lemke_workspace_bytes(int n) {
	if (n < 0 || n > LEMKE_N_MAX)
		return 0;
	return round16(doubles_for((size_t)n) * sizeof(double)) + round16(ints_for((size_t)n) * sizeof(int));
}

static void carve(lemke *L, void *workspace) {
	size_t n = (size_t)L->n;
	double *d = workspace;
	L->G = d, d += n * n;
	L->ARC = d, d += n * n;
	L->mval_store = d, d += n * n;
	L->x = d, d += 2 * n;
	L->d = d, d += 2 * n;
	L->v = d, d += n;
	L->ar = d, d += n;
	L->cover = d, d += n;
	L->lexval = d;
	int *i = (int *)((char *)workspace + round16(doubles_for(n) * sizeof(double)));
	L->mrow_store = i, i += n * n;
	L->mstart_store = i, i += n + 1;
	L->R = i, i += n;
	L->C = i, i += n;
	L->rowslot = i, i += n;
	L->colslot = i, i += n + 1;
	L->cand = i, i += n;
	L->perm = i;
}

// Checks a dense M and q are finite and stores M by columns in the workspace. Returns -1 on a
// non-finite entry.
static int load_dense(lemke *L, const double *M) {
	int n = L->n;
	int *start = L->mstart_store, *count = start + 1;
	double amax = 1.0;
	memset(start, 0, (size_t)(n + 1) * sizeof *start);
	for (int i = 0; i < n; ++i) {
		if (!isfinite(L->q[i]))
			return -1;
		const double *row = M + (size_t)i * (size_t)n;
		for (int j = 0; j < n; ++j) {
			if (!isfinite(row[j]))
				return -1;
			count[j] += row[j] != 0.0;
			amax = fabs(row[j]) > amax ? fabs(row[j]) : amax;
		}
	}
	L->amax = amax;
	for (int j = 0; j < n; ++j) // start[j + 1] = end of column j; fill from the starts
		start[j + 1] += start[j];
	int *next = L->cand;
	memcpy(next, start, (size_t)n * sizeof *next);
	for (int i = 0; i < n; ++i) {
		const double *row = M + (size_t)i * (size_t)n;
		for (int j = 0; j < n; ++j)
			if (row[j] != 0.0) {
				int t = next[j]++;
				L->mrow_store[t] = i;
				L->mval_store[t] = row[j];
			}
	}
	L->mstart = start;
	L->mrow = L->mrow_store;
	L->mval = L->mval_store;
	return 0;
}

// Checks compressed columns (starts from 0 and never decreasing, rows inside [0, n) and strictly
// ascending in each column, finite values) and q. Returns -1 on anything else.
static int load_columns(lemke *L, const int *start, const int *row, const double *val) {
	int n = L->n;
	double amax = 1.0;
	if (start[0] != 0)
		return -1;
	for (int i = 0; i < n; ++i)
		if (!isfinite(L->q[i]))
			return -1;
	for (int j = 0; j < n; ++j) {
		if (start[j + 1] < start[j] || start[j + 1] - start[j] > n)
			return -1;
		for (int t = start[j]; t < start[j + 1]; ++t) {
			if (row[t] < 0 || row[t] >= n || (t > start[j] && row[t] <= row[t - 1]) || !isfinite(val[t]))
				return -1;
			amax = fabs(val[t]) > amax ? fabs(val[t]) : amax;
		}
	}
	L->amax = amax;
	L->mstart = start;
	L->mrow = row;
	L->mval = val;
	return 0;
}

// Dot product with four partial sums (a fixed order: deterministic; about twice as fast as one).
static inline double dot(const double *a, const double *b, int k) {
	double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
	int p = 0;
	for (; p + 4 <= k; p += 4) {
		s0 += a[p] * b[p];
		s1 += a[p + 1] * b[p + 1];
		s2 += a[p + 2] * b[p + 2];
		s3 += a[p + 3] * b[p + 3];
	}
	for (; p < k; ++p)
		s0 += a[p] * b[p];
	return (s0 + s1) + (s2 + s3);
}

// --- columns of A = [-M | -d] ---

// M_ic: read from a dense M, else a binary search of column c's rows (a column of a LINK
// step's M has at most a few hundred).
static inline double entry_of_M(const lemke *L, int i, int c) {
	if (L->dense)
		return L->dense[(size_t)i * (size_t)L->n + (size_t)c];
	int lo = L->mstart[c], hi = L->mstart[c + 1];
	while (lo < hi) {
		const int mid = lo + (hi - lo) / 2;
		if (L->mrow[mid] < i)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < L->mstart[c + 1] && L->mrow[lo] == i ? L->mval[lo] : 0.0;
}

static inline double entry_of_A(const lemke *L, int i, int c) {
	return c == L->n ? -L->cover[i] : -entry_of_M(L, i, c);
}

// y[0..n) += f * A[:, c]
static void add_column(const lemke *L, int c, double f, double *y) {
	if (c == L->n) {
		for (int i = 0; i < L->n; ++i)
			y[i] -= f * L->cover[i];
		return;
	}
	const int *row = L->mrow;
	const double *val = L->mval;
	for (int t = L->mstart[c]; t < L->mstart[c + 1]; ++t)
		y[row[t]] -= f * val[t];
}

// d_W = (a_W, from column c, or 0 when c < 0) - A_WC d_C; the rows in R get 0.
static void direction_w(lemke *L, int c) {
	double *dw = L->d;
	memset(dw, 0, (size_t)L->n * sizeof *dw);
	if (c >= 0)
		add_column(L, c, 1.0, dw);
	for (int s = 0; s < L->k; ++s)
		if (L->d[L->n + s] != 0.0)
			add_column(L, L->C[s], -L->d[L->n + s], dw);
	for (int p = 0; p < L->k; ++p)
		dw[L->R[p]] = 0.0;
}

// Direction of column c of A entering: d_C = G a_R, then d_W.
static void direction_of_column(lemke *L, int c) {
	int k = L->k;
	size_t n = (size_t)L->n;
	for (int p = 0; p < k; ++p)
		L->ar[p] = entry_of_A(L, L->R[p], c);
	for (int s = 0; s < k; ++s)
		L->d[n + (size_t)s] = dot(L->G + (size_t)s * n, L->ar, k);
	direction_w(L, c);
}

// Direction of w_j entering (row j in R, slot p): a = e_j, so d_C = G[:, p] and d_W = -A_WC d_C.
static void direction_of_w(lemke *L, int p) {
	size_t n = (size_t)L->n;
	for (int s = 0; s < L->k; ++s)
		L->d[n + (size_t)s] = L->G[(size_t)s * n + (size_t)p];
	direction_w(L, -1);
}

// v = A_iC G: row i of A over the basic columns, times G.
static void row_times_G(lemke *L, int i) {
	int k = L->k;
	size_t n = (size_t)L->n;
	double *v = L->v;
	memset(v, 0, (size_t)k * sizeof *v);
	for (int s = 0; s < k; ++s) {
		double f = entry_of_A(L, i, L->C[s]);
		if (f == 0.0)
			continue;
		const double *g = L->G + (size_t)s * n;
		for (int p = 0; p < k; ++p)
			v[p] += f * g[p];
	}
}

// --- the four pivots: G, the slots and the entering value ---
// x has already moved to x - theta d; the entering variable takes the value theta.

// Column c enters, basic w_i leaves: G grows by a border; the pivot is s = d_i.
static void pivot_column_for_w(lemke *L, int c, int i, double theta) {
	int k = L->k;
	size_t n = (size_t)L->n;
	double s = L->d[i];
	row_times_G(L, i);
	const double *u = L->d + n, *v = L->v;
	for (int r = 0; r < k; ++r) {
		double *g = L->G + (size_t)r * n;
		double f = u[r] / s;
		if (f != 0.0)
			for (int p = 0; p < k; ++p)
				g[p] += f * v[p];
		g[k] = -f;
	}
	double *last = L->G + (size_t)k * n;
	for (int p = 0; p < k; ++p)
		last[p] = -v[p] / s;
	last[k] = 1.0 / s;
	double *arow = L->ARC + (size_t)k * n;
	for (int t = 0; t < k; ++t) {
		arow[t] = entry_of_A(L, i, L->C[t]);
		L->ARC[(size_t)t * n + (size_t)k] = L->ar[t];
	}
	arow[k] = entry_of_A(L, i, c);
	L->R[k] = i;
	L->rowslot[i] = k;
	L->C[k] = c;
	L->colslot[c] = k;
	L->x[i] = 0.0;
	L->x[n + (size_t)k] = theta;
	L->k = k + 1;
}

// Column c enters, the basic column in slot q0 leaves: row q0 of G is replaced (G' = E G).
static void pivot_column_for_column(lemke *L, int c, int q0, double theta) {
	int k = L->k;
	size_t n = (size_t)L->n;
	const double *u = L->d + n;
	double *g0 = L->G + (size_t)q0 * n;
	double inv = 1.0 / u[q0];
	for (int p = 0; p < k; ++p)
		g0[p] *= inv;
	for (int r = 0; r < k; ++r) {
		if (r == q0 || u[r] == 0.0)
			continue;
		double *g = L->G + (size_t)r * n;
		double f = u[r];
		for (int p = 0; p < k; ++p)
			g[p] -= f * g0[p];
	}
	L->colslot[L->C[q0]] = -1;
	L->C[q0] = c;
	L->colslot[c] = q0;
	L->x[n + (size_t)q0] = theta;
	for (int p = 0; p < k; ++p)
		L->ARC[(size_t)p * n + (size_t)q0] = L->ar[p];
}

// w_j (row j, slot p0) enters, basic w_i leaves: column p0 of G is replaced (row j -> row i).
static void pivot_w_for_w(lemke *L, int j, int i, double theta) {
	int k = L->k, p0 = L->rowslot[j];
	size_t n = (size_t)L->n;
	row_times_G(L, i);
	double *v = L->v;
	double inv = 1.0 / v[p0];
	for (int p = 0; p < k; ++p)
		v[p] *= inv;
	for (int r = 0; r < k; ++r) {
		double *g = L->G + (size_t)r * n;
		double f = g[p0];
		if (f == 0.0)
			continue;
		for (int p = 0; p < k; ++p)
			g[p] -= f * v[p];
		g[p0] = f * inv;
	}
	L->R[p0] = i;
	L->rowslot[i] = p0;
	L->rowslot[j] = -1;
	L->x[i] = 0.0;
	L->x[j] = theta;
	double *arow = L->ARC + (size_t)p0 * n;
	for (int t = 0; t < k; ++t)
		arow[t] = entry_of_A(L, i, L->C[t]);
}

// w_j (row j, slot p0) enters, the basic column in slot q0 leaves: G loses row q0 and column p0
// (the inverse of A_RC without its row p0 and column q0 is G_{-q0,-p0} - G_{-q0,p0} G_{q0,-p0} /
// G_{q0,p0}), then the last slots move into the holes.
static void pivot_w_for_column(lemke *L, int j, int q0, double theta) {
	int k = L->k, p0 = L->rowslot[j], last = k - 1;
	size_t n = (size_t)L->n;
	double *g0 = L->G + (size_t)q0 * n;
	double inv = 1.0 / g0[p0];
	for (int r = 0; r < k; ++r) {
		if (r == q0)
			continue;
		double *g = L->G + (size_t)r * n;
		double f = g[p0] * inv;
		if (f != 0.0)
			for (int p = 0; p < k; ++p)
				g[p] -= f * g0[p];
	}
	L->colslot[L->C[q0]] = -1;
	if (q0 != last) { // the last C slot becomes slot q0 (a row of G)
		memcpy(g0, L->G + (size_t)last * n, (size_t)k * sizeof *g0);
		L->C[q0] = L->C[last];
		L->colslot[L->C[q0]] = q0;
		L->x[n + (size_t)q0] = L->x[n + (size_t)last];
		for (int p = 0; p < k; ++p) // and column q0 of A_RC
			L->ARC[(size_t)p * n + (size_t)q0] = L->ARC[(size_t)p * n + (size_t)last];
	}
	if (p0 != last) { // the last R slot becomes slot p0 (a column of G)
		for (int r = 0; r < last; ++r) {
			double *g = L->G + (size_t)r * n;
			g[p0] = g[last];
		}
		L->R[p0] = L->R[last];
		L->rowslot[L->R[p0]] = p0;
		memcpy(L->ARC + (size_t)p0 * n, L->ARC + (size_t)last * n, (size_t)last * sizeof(double));
	}
	L->rowslot[j] = -1;
	L->x[n + (size_t)last] = 0.0;
	L->x[j] = theta;
	L->k = last;
}

// --- rebuilding G ---

// Inverts the k x k matrix a (leading dimension ld) in place: Gauss-Jordan with partial
// pivoting. Returns -1 when it is numerically singular (a is then garbage).
static int invert_in_place(double *a, int k, size_t ld, int *perm) {
	for (int c = 0; c < k; ++c) {
		int best = c;
		double big = -1.0, colmax = 0.0;
		for (int r = 0; r < k; ++r) {
			double e = fabs(a[(size_t)r * ld + (size_t)c]);
			if (e > colmax)
				colmax = e;
			if (r >= c && e > big)
				big = e, best = r;
		}
		if (!(big > LEMKE_SINGULAR_REL * colmax) || !isfinite(big))
			return -1;
		perm[c] = best;
		double *pr = a + (size_t)best * ld;
		if (best != c) {
			double *pc = a + (size_t)c * ld;
			for (int p = 0; p < k; ++p) {
				double t = pc[p];
				pc[p] = pr[p];
				pr[p] = t;
			}
			pr = pc;
		}
		double inv = 1.0 / pr[c];
		pr[c] = 1.0;
		for (int p = 0; p < k; ++p)
			pr[p] *= inv;
		for (int r = 0; r < k; ++r) {
			double *g = a + (size_t)r * ld;
			double f = g[c];
			if (r == c || f == 0.0)
				continue;
			g[c] = 0.0;
			for (int p = 0; p < k; ++p)
				g[p] -= f * pr[p];
		}
	}
	for (int c = k - 1; c >= 0; --c) { // row interchanges of A are column interchanges of A^-1
		int o = perm[c];
		if (o == c)
			continue;
		for (int r = 0; r < k; ++r) {
			double *g = a + (size_t)r * ld;
			double t = g[c];
			g[c] = g[o];
			g[o] = t;
		}
	}
	return 0;
}

// G = A_RC^-1 from the basic columns. Returns -1 when A_RC is numerically singular (G is then
// unusable).
static int rebuild(lemke *L) {
	int k = L->k;
	size_t n = (size_t)L->n;
	for (int p = 0; p < k; ++p) // A_RC (rows p, columns s) into G; its inverse has rows s, columns p
		memcpy(L->G + (size_t)p * n, L->ARC + (size_t)p * n, (size_t)k * sizeof(double));
	return invert_in_place(L->G, k, n, L->perm);
}

// x_C from A_RC x_C = q_R (G, plus one step of iterative refinement), x_W = q_W - A_WC x_C.
static void basic_values(lemke *L) {
	int k = L->k, n = L->n;
	double *xc = L->x + n, *r = L->ar;
	for (int s = 0; s < k; ++s) {
		const double *g = L->G + (size_t)s * (size_t)n;
		double sum = 0.0;
		for (int p = 0; p < k; ++p)
			sum += g[p] * L->q[L->R[p]];
		xc[s] = sum;
	}
	for (int p = 0; p < k; ++p) {
		const double *arow = L->ARC + (size_t)p * (size_t)n;
		double sum = L->q[L->R[p]];
		for (int s = 0; s < k; ++s)
			sum -= arow[s] * xc[s];
		r[p] = sum;
	}
	for (int s = 0; s < k; ++s) {
		const double *g = L->G + (size_t)s * (size_t)n;
		double sum = 0.0;
		for (int p = 0; p < k; ++p)
			sum += g[p] * r[p];
		xc[s] += sum;
	}
	memcpy(L->x, L->q, (size_t)n * sizeof *L->x);
	for (int s = 0; s < k; ++s)
		if (xc[s] != 0.0)
			add_column(L, L->C[s], -xc[s], L->x);
	for (int p = 0; p < k; ++p)
		L->x[L->R[p]] = 0.0;
}

// Relative residual of A_RC y = target (target = a_R in ar, or the unit vector e_unit when
// unit >= 0): max |residual| / (max |target| + max |A| sum |y|), the last a bound on the size
// of the terms summed.
static double drift(const lemke *L, const double *y, const double *target, int unit) {
	int k = L->k;
	double worst = 0.0, scale = 0.0;
	for (int p = 0; p < k; ++p) {
		const double *arow = L->ARC + (size_t)p * (size_t)L->n;
		double t = unit >= 0 ? (p == unit) : target[p], r = fabs(t - dot(arow, y, k));
		worst = r > worst ? r : worst;
		scale = fabs(t) > scale ? fabs(t) : scale;
	}
	double ysum = 0.0; // the terms' size is at most max |A| sum |y|
	for (int s = 0; s < k; ++s)
		ysum += fabs(y[s]);
	scale += L->amax * ysum;
	return scale > 0.0 ? worst / scale : 0.0;
}

// The direction of the entering variable `enter` (w_j as j, z_j as n + j, z0 as 2 n), with G
// rebuilt first when the direction shows it has drifted. Returns -1 when a rebuild finds the
// basis singular.
static int direction(lemke *L, int enter, int check, int check_x) {
	int n = L->n;
	for (int attempt = 0;; ++attempt) {
		if (enter >= n)
			direction_of_column(L, enter - n);
		else
			direction_of_w(L, L->rowslot[enter]);
		if (!check)
			return 0;
		double e = drift(L, L->d + n, L->ar, enter >= n ? -1 : L->rowslot[enter]);
		if (check_x && attempt == 0) {
			for (int p = 0; p < L->k; ++p)
				L->lexval[p] = L->q[L->R[p]];
			double ex = drift(L, L->x + n, L->lexval, -1);
			e = ex > e ? ex : e;
		}
		if (e <= LEMKE_DRIFT_MAX || attempt > 0)
			return 0;
		if (rebuild(L))
			return -1;
		basic_values(L);
		++L->rebuilds;
	}
}

// --- the ratio test ---
// Basic variables are numbered id = i for a basic w_i, id = n + s for slot s.

// Entry (id, j) of B^-1 for a row j in R (slot p): G[s][p] for slot s, -A_iC G[:, p] for w_i.
static double inverse_entry(const lemke *L, int id, int p) {
	size_t n = (size_t)L->n;
	if (id >= L->n)
		return L->G[(size_t)(id - L->n) * n + (size_t)p];
	double sum = 0.0;
	for (int s = 0; s < L->k; ++s) {
		double a = entry_of_A(L, id, L->C[s]);
		if (a != 0.0)
			sum -= a * L->G[(size_t)s * n + (size_t)p];
	}
	return sum;
}

// The lexicographically smallest of the tied rows cand[0..count): compares the rows of B^-1
// divided by d, column by column.
static int lexicographic_choice(lemke *L, int count) {
	int *cand = L->cand;
	double *val = L->lexval;
	for (int j = 0; j < L->n && count > 1; ++j) {
		int p = L->rowslot[j];
		if (p < 0) { // column j of B^-1 is the unit vector of basic w_j: that row is the largest
			for (int t = 0; t < count; ++t)
				if (cand[t] == j) {
					memmove(cand + t, cand + t + 1, (size_t)(count - t - 1) * sizeof *cand);
					--count;
					break;
				}
			continue;
		}
		double vmin = INFINITY, vmax = 0.0;
		for (int t = 0; t < count; ++t) {
			val[t] = inverse_entry(L, cand[t], p) / L->d[cand[t]];
			vmin = val[t] < vmin ? val[t] : vmin;
			vmax = fabs(val[t]) > vmax ? fabs(val[t]) : vmax;
		}
		double tie = LEMKE_LEX_TIE_REL * vmax;
		int kept = 0;
		for (int t = 0; t < count; ++t)
			if (val[t] - vmin <= tie)
				cand[kept++] = cand[t];
		count = kept;
	}
	return cand[0];
}

static inline double positive(double x) { return x > 0.0 ? x : 0.0; }

// The leaving variable's id for the direction d: 0 and *leave set, or -1 when no entry of d is
// positive (a secondary ray).
static int ratio_test(lemke *L, int *leave) {
	int m = L->n + L->k;
	const double *x = L->x, *d = L->d;
	double dmax = 0.0, xscale = 0.0;
	for (int id = 0; id < m; ++id) {
		dmax = fabs(d[id]) > dmax ? fabs(d[id]) : dmax;
		xscale = fabs(x[id]) > xscale ? fabs(x[id]) : xscale;
	}
	L->dmax = dmax;
	if (!(dmax > 0.0) || !isfinite(dmax))
		return -1;
	double dtol = LEMKE_PIVOT_REL * dmax, theta = INFINITY;
	int arg = -1;
	for (int pass = 0; pass < 2 && arg < 0; ++pass) {
		if (pass == 1)
			dtol = LEMKE_PIVOT_MIN_REL * dmax;
		for (int id = 0; id < m; ++id)
			if (d[id] > dtol) {
				double r = positive(x[id]) / d[id];
				if (r < theta)
					theta = r, arg = id;
			}
	}
	if (arg < 0)
		return -1;
	// z0 leaves if it may (see the header comment). Its pivot needs only LEMKE_PIVOT_MIN_REL:
	// it ends the solve, and the final solve and residual check judge the basis it leaves.
	int z0 = L->n + L->colslot[L->n];
	if (d[z0] > LEMKE_PIVOT_MIN_REL * dmax && z0 != arg) {
		double theta0 = positive(x[z0]) / d[z0], slack = LEMKE_Z0_SLACK * xscale;
		if (theta0 <= theta) {
			*leave = z0;
			return 0;
		}
		if ((theta0 - theta) * d[arg] <= slack) {
			int ok = 1;
			for (int id = 0; id < m && ok; ++id)
				ok = x[id] - theta0 * d[id] >= -slack || id == z0;
			if (ok) {
				*leave = z0;
				return 0;
			}
		}
	}
	double tie = LEMKE_TIE_REL * xscale;
	int count = 0;
	for (int id = 0; id < m; ++id)
		if (d[id] > dtol && positive(x[id]) - theta * d[id] <= tie) {
			if (id == z0) {
				*leave = z0;
				return 0;
			}
			L->cand[count++] = id;
		}
	*leave = count == 1 ? L->cand[0] : lexicographic_choice(L, count);
	return 0;
}

// --- answers ---

// z from the basic columns (rounding below zero clamped to 0), and its residual from M and q:
// w = q + M z and the size of its terms, accumulated column by column over the nonzero z (each
// row's terms in ascending column order) into the direction's memory (free: the next pivot
// recomputes it).
static double extract(lemke *L, double *z) {
	int n = L->n;
	memset(z, 0, (size_t)n * sizeof *z);
	for (int s = 0; s < L->k; ++s)
		if (L->C[s] < n)
			z[L->C[s]] = positive(L->x[n + s]);
	double *w = L->d, *terms = L->d + n;
	for (int i = 0; i < n; ++i) {
		w[i] = L->q[i];
		terms[i] = fabs(L->q[i]);
	}
	for (int j = 0; j < n; ++j) {
		if (z[j] == 0.0)
			continue;
		for (int t = L->mstart[j]; t < L->mstart[j + 1]; ++t) {
			const double e = L->mval[t] * z[j];
			w[L->mrow[t]] += e;
			terms[L->mrow[t]] += fabs(e);
		}
	}
	double size = 0.0, res = 0.0;
	for (int i = 0; i < n; ++i) {
		double r = -w[i] > fmin(z[i], w[i]) ? -w[i] : fmin(z[i], w[i]);
		if (!(r <= res)) // NaN too
			res = r == r ? r : INFINITY;
		size = terms[i] > size ? terms[i] : size;
	}
	return res / (1.0 + size);
}

static void write_basis(const lemke *L, int *basis) {
	if (basis)
		for (int j = 0; j < L->n; ++j)
			basis[j] = L->colslot[j] >= 0;
}

static void start_all_w(lemke *L) {
	L->k = 0;
	for (int i = 0; i < L->n; ++i)
		L->rowslot[i] = -1;
	for (int c = 0; c <= L->n; ++c)
		L->colslot[c] = -1;
	if (L->n > 0)
		memcpy(L->x, L->q, (size_t)L->n * sizeof *L->x);
}

// Warm start: the complementary basis with z_j basic where basis[j] != 0. Returns 1 when it
// solves the LCP (z and *residual set); otherwise *loaded says whether the basis is regular
// (G and the basic values are then set, for warm_pivots).
static int warm_start(lemke *L, const int *basis, double *z, double *residual, int *loaded) {
	*loaded = 0;
	start_all_w(L);
	for (int j = 0; j < L->n; ++j)
		if (basis[j]) {
			int s = L->k++;
			L->R[s] = L->C[s] = j;
			L->rowslot[j] = L->colslot[j] = s;
		}
	for (int p = 0; p < L->k; ++p)
		for (int t = 0; t < L->k; ++t)
			L->ARC[(size_t)p * (size_t)L->n + (size_t)t] = entry_of_A(L, L->R[p], L->C[t]);
	if (rebuild(L))
		return 0;
	basic_values(L);
	*loaded = 1;
	*residual = extract(L, z);
	return *residual <= POOL_LEMKE_RESIDUAL_MAX;
}

// Complementary pivoting from the first pivot (z0 basic, `enter` the complement of the
// variable that left: w_j as j, z_j as n + j) until z0 leaves.
static pool_lemke_status complementary_pivots(lemke *L, int enter, int max_pivots, double *z, int *basis,
                                              pool_lemke_stats *st) {
	int n = L->n, small_pivot = 0;
	for (;;) {
		if (st->pivots >= max_pivots) {
			st->residual = extract(L, z);
			return POOL_LEMKE_MAX_PIVOTS;
		}
		int check = small_pivot || st->pivots % LEMKE_CHECK_PIVOTS == 0;
		if (direction(L, enter, check, check && st->pivots % (2 * LEMKE_CHECK_PIVOTS) == 0)) {
			st->residual = extract(L, z);
			return POOL_LEMKE_RESIDUAL;
		}
		int leave;
		if (ratio_test(L, &leave)) {
			st->residual = extract(L, z);
			return POOL_LEMKE_RAY;
		}
		double step = positive(L->x[leave]) / L->d[leave];
		small_pivot = L->d[leave] < LEMKE_SMALL_PIVOT * L->dmax;
		for (int id = 0; id < n + L->k; ++id)
			L->x[id] -= step * L->d[id];
		// the next entering variable is the complement of the leaving one; z0 leaving ends it
		int next = leave < n ? n + leave : L->C[leave - n], done = leave >= n && next == n;
		if (enter >= n) {
			if (leave < n)
				pivot_column_for_w(L, enter - n, leave, step);
			else
				pivot_column_for_column(L, enter - n, leave - n, step);
		} else {
			if (leave < n)
				pivot_w_for_w(L, enter, leave, step);
			else
				pivot_w_for_column(L, enter, leave - n, step);
		}
		++st->pivots;
		if (done)
			break; // the basis is complementary
		enter = next;
	}
	if (rebuild(L) == 0)
		basic_values(L);
	st->residual = extract(L, z);
	write_basis(L, basis);
	return st->residual <= POOL_LEMKE_RESIDUAL_MAX ? POOL_LEMKE_SOLVED : POOL_LEMKE_RESIDUAL;
}

// Lemke from the all-w basis, covering vector e.
static pool_lemke_status cold_start(lemke *L, int max_pivots, double *z, int *basis, pool_lemke_stats *st) {
	int n = L->n;
	start_all_w(L);
	for (int i = 0; i < n; ++i)
		L->cover[i] = 1.0;
	int r = 0;
	for (int i = 1; i < n; ++i)
		if (L->q[i] <= L->q[r]) // ties: the largest index is the lexicographic minimum
			r = i;
	if (L->q[r] >= 0.0) {
		st->residual = extract(L, z);
		write_basis(L, basis);
		return POOL_LEMKE_SOLVED;
	}
	// z0 enters, w_r leaves: every w rises by -q_r
	double theta = -L->q[r];
	direction_of_column(L, n);
	for (int i = 0; i < n; ++i)
		L->x[i] -= theta * L->d[i];
	pivot_column_for_w(L, n, r, theta);
	st->pivots += 1;
	return complementary_pivots(L, n + r, max_pivots, z, basis, st);
}

// Lemke from the warm start's basis B when it is regular but not feasible: the covering
// vector d = B 1 makes z0's direction in that basis -1 everywhere, so z0 = -min x_B makes
// every basic value >= 0 and the complementary pivots start there, as from the all-w basis
// (which is this with B = I, d = e). One or two pivots usually repair a basis that the
// problem's small change between two LINK steps spoiled, where a cold start takes 15 to 30
// per contact. With d not positive, Lemke's guarantees (termination on a solution or a ray
// that proves infeasibility) do not hold: the caller limits the pivots and solves cold on
// anything but a solution.
static pool_lemke_status warm_pivots(lemke *L, int max_pivots, double *z, int *basis, pool_lemke_stats *st) {
	int n = L->n, k = L->k;
	for (int i = 0; i < n; ++i)
		L->cover[i] = L->rowslot[i] < 0 ? 1.0 : 0.0;
	for (int s = 0; s < k; ++s)
		add_column(L, L->C[s], 1.0, L->cover); // A's column of z_C[s] is -M's
	for (int i = 0; i < n; ++i)
		L->amax = fabs(L->cover[i]) > L->amax ? fabs(L->cover[i]) : L->amax;
	int r = -1; // the most negative basic value (ties: the largest id, as the cold start)
	for (int id = 0; id < n + k; ++id) {
		if (id < n && L->rowslot[id] >= 0)
			continue;
		if (r < 0 || L->x[id] <= L->x[r])
			r = id;
	}
	if (r < 0 || !(L->x[r] < 0.0))
		return POOL_LEMKE_RESIDUAL; // feasible already: warm_start judged it, not a pivot's job
	double theta = -L->x[r];
	direction_of_column(L, n);
	for (int id = 0; id < n + k; ++id)
		L->x[id] -= theta * L->d[id];
	int enter;
	if (r < n) {
		pivot_column_for_w(L, n, r, theta);
		enter = n + r;
	} else {
		enter = L->C[r - n];
		pivot_column_for_column(L, n, r - n, theta);
	}
	st->pivots += 1;
	return complementary_pivots(L, enter, max_pivots, z, basis, st);
}

// The solve once M is loaded (lemke.h).
static pool_lemke_status solve_loaded(lemke *L, double *z, int *basis, int max_pivots, pool_lemke_stats *st) {
	const int n = L->n;
	if (max_pivots <= 0)
		max_pivots = 50 * n + 100;
	if (basis) {
		int loaded;
		if (warm_start(L, basis, z, &st->residual, &loaded)) {
			st->warm = 1;
			write_basis(L, basis);
			return POOL_LEMKE_SOLVED;
		}
		if (loaded && L->k > 0) { // (from no basic z, the warm pivots are the cold start's)
			const double amax = L->amax;
			const int budget = LEMKE_WARM_PIVOTS_PER_BASIC * (L->k + 1);
			const pool_lemke_status ws = warm_pivots(L, budget < max_pivots ? budget : max_pivots, z, basis, st);
			if (ws == POOL_LEMKE_SOLVED) {
				st->warm = 1;
				return ws;
			}
			L->amax = amax; // the cold start as if alone, with the pivot budget it would have
			max_pivots += st->pivots;
		}
	}
	return cold_start(L, max_pivots, z, basis, st);
}

// What both entry points check first; 1 when the solve is over (n = 0 or bad input, *status).
static int begin(int n, const double *q, const double *z, const void *workspace, pool_lemke_stats *st,
                 pool_lemke_status *status) {
	st->pivots = 0;
	st->warm = 0;
	st->residual = INFINITY;
	if (n == 0) {
		st->residual = 0.0;
		*status = POOL_LEMKE_SOLVED;
		return 1;
	}
	if (n < 0 || n > LEMKE_N_MAX || !q || !z || !workspace || (uintptr_t)workspace % _Alignof(double) != 0) {
		*status = POOL_LEMKE_BAD_INPUT;
		return 1;
	}
	return 0;
}

pool_lemke_status pool_lemke_solve(int n, const double *M, const double *q, double *z, int *basis, int max_pivots,
                                   void *workspace, pool_lemke_stats *stats) {
	pool_lemke_stats local;
	pool_lemke_stats *st = stats ? stats : &local;
	pool_lemke_status status;
	if (begin(n, q, z, workspace, st, &status))
		return status;
	if (!M)
		return POOL_LEMKE_BAD_INPUT;
	lemke L = {.n = n, .q = q, .dense = M};
	carve(&L, workspace);
	if (load_dense(&L, M))
		return POOL_LEMKE_BAD_INPUT;
	return solve_loaded(&L, z, basis, max_pivots, st);
}

pool_lemke_status pool_lemke_solve_columns(int n, const int *start, const int *row, const double *val, const double *q,
                                           double *z, int *basis, int max_pivots, void *workspace,
                                           pool_lemke_stats *stats) {
	pool_lemke_stats local;
	pool_lemke_stats *st = stats ? stats : &local;
	pool_lemke_status status;
	if (begin(n, q, z, workspace, st, &status))
		return status;
	if (!start || (start[n] > 0 && (!row || !val)))
		return POOL_LEMKE_BAD_INPUT;
	lemke L = {.n = n, .q = q};
	carve(&L, workspace);
	if (load_columns(&L, start, row, val))
		return POOL_LEMKE_BAD_INPUT;
	return solve_loaded(&L, z, basis, max_pivots, st);
}
