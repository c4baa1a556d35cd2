// Lexicographic Lemke: the linear complementarity problem of a LINK step (docs/physics.md "LINK").
//   find z >= 0 with w = M z + q >= 0 and z'w = 0,  M dense n x n, row-major.
// Lemke's complementary pivoting with the covering vector e = (1, ..., 1) terminates on a
// copositive-plus M (the friction LCP's is) when degenerate ratio tests are broken
// lexicographically; it then either solves the LCP or ends on a secondary ray, which for a
// copositive-plus M proves the LCP infeasible. No allocation: the caller passes a workspace of
// pool_lemke_workspace_bytes(n).
#ifndef POOL_LEMKE_H
#define POOL_LEMKE_H

#include <stddef.h>

/// Relative complementarity residual above which a solve is reported as failed (docs/physics.md:
/// "check the complementarity residual of every solve"): with w = M z + q computed from M and q,
/// max_i max(-w_i, min(z_i, w_i)) divided by 1 + max_i (|q_i| + sum_j |M_ij z_j|), the size of
/// the terms w is summed from (so a large z is not held to a tighter standard than rounding
/// allows). The returned z is >= 0 exactly (rounding below zero is clamped).
#define POOL_LEMKE_RESIDUAL_MAX 1e-10

/// How a solve ended.
typedef enum pool_lemke_status {
	POOL_LEMKE_SOLVED = 0,     ///< z solves the LCP; residual <= POOL_LEMKE_RESIDUAL_MAX
	POOL_LEMKE_RAY = 1,        ///< secondary ray: no solution (M not copositive-plus, or infeasible)
	POOL_LEMKE_MAX_PIVOTS = 2, ///< pivot budget exhausted
	POOL_LEMKE_RESIDUAL = 3,   ///< finished, but the residual check failed (ill-conditioned M)
	POOL_LEMKE_BAD_INPUT = 4,  ///< n < 0, NULL arrays, non-finite M or q
} pool_lemke_status;

/// What a solve did.
typedef struct pool_lemke_stats {
	int pivots;      ///< complementary pivots taken (0 when the warm start was already a solution)
	int warm;        ///< 1 when the solve started from the warm-start basis (it solved the problem
	                 ///< directly, pivots 0, or a few pivots from it did) rather than from scratch
	double residual; ///< relative complementarity residual of the returned z
} pool_lemke_stats;

/// Bytes of workspace a problem of size n needs: about 28 n^2 (18 MB at n = 800); 0 when n < 0
/// or n > 20000.
size_t pool_lemke_workspace_bytes(int n);

/// Solves the LCP (M, q) of size n into z[0..n). `basis` (optional, n ints) is a warm start on
/// entry and the solution's complementary basis on exit: basis[i] = 1 when z_i is basic
/// (may be > 0), 0 when w_i is; when the entry basis gives z >= 0, w >= 0 it is returned without
/// pivoting (a LINK step's contacts rarely change between steps): the basis is solved directly
/// and accepted when its z (rounding below zero clamped) passes the residual check. A regular
/// basis that does not is the start of Lemke's pivots (covering vector B 1, lemke.c), up to 2
/// pivots per basic z; failing that, Lemke runs from scratch. Any answer passes the same
/// residual check. basis is written on POOL_LEMKE_SOLVED and POOL_LEMKE_RESIDUAL only. On any
/// other status z holds the last iterate (not a solution). max_pivots <= 0 means a default of
/// 50 n + 100. workspace: pool_lemke_workspace_bytes(n) bytes aligned for double (as malloc
/// gives); its contents on entry do not matter. stats may be NULL. n = 0 is solved (nothing to
/// do; the pointers are not read). Deterministic: the same input gives the same z, bit for bit.
pool_lemke_status pool_lemke_solve(int n, const double *M, const double *q, double *z, int *basis, int max_pivots,
                                   void *workspace, pool_lemke_stats *stats);

/// pool_lemke_solve with M in compressed columns: column j's nonzeros are val[t] in rows
/// row[t] for t in [start[j], start[j + 1]), rows strictly ascending, start[0] = 0 (n + 1
/// starts). The same answer, bit for bit, as the dense M with those entries; the solver reads
/// the arrays in place, so a sparse M (a LINK step's: each contact couples only with the
/// contacts of its two balls) is never formed densely. POOL_LEMKE_BAD_INPUT for malformed
/// columns (a row out of range or not ascending, a non-finite value) as for a NULL array.
pool_lemke_status pool_lemke_solve_columns(int n, const int *start, const int *row, const double *val, const double *q,
                                           double *z, int *basis, int max_pivots, void *workspace,
                                           pool_lemke_stats *stats);

#endif
