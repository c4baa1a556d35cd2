// The Jacobian's block structure (fit.h, fit_jacobian_blocks): shot s's residual rows depend on
// the table's free parameters and on shot s's strike alone, so J^T J has a dense table corner,
// one dense diagonal block per shot and the table-shot couplings, and nothing between two shots'
// strikes. Built row by row from the blocks, it costs n_obs width^2 operations, linear in the
// number of shots, where GSL's dense path (dsyrk on n x p) costs n p^2.
#include <string.h>

#include "fit.h"

/// The first parameter of shot s's strike in x.
static int shot_first(const fit_problem *pb, int s) { return pb->table_free + s * pb->shot_free; }

/// x's index of block column c on shot s.
static int param_of_column(const fit_problem *pb, int s, int c) {
	return c < pb->table_free ? c : shot_first(pb, s) + c - pb->table_free;
}

void fit_jacobian_dense(const fit_problem *pb, const fit_jacobian_blocks *J, double *dense) {
	const size_t p = (size_t)pb->p, width = (size_t)fit_jacobian_width(pb);
	memset(dense, 0, pb->n * p * sizeof *dense);
	size_t i = 0;
	for (int s = 0; s < pb->shot_count; ++s)
		for (long r = 0; r < 2 * pb->shots[s].obs_count; ++r, ++i)
			for (size_t c = 0; c < width; ++c)
				dense[i * p + (size_t)param_of_column(pb, s, (int)c)] = J->rows[i * width + c];
	memcpy(dense + pb->n_obs * p, J->penalty, p * p * sizeof *dense);
}

void fit_jacobian_normal(const fit_problem *pb, const fit_jacobian_blocks *J, const double *f, double *JTJ,
                         double *g, size_t *nonzero) {
	const size_t p = (size_t)pb->p, width = (size_t)fit_jacobian_width(pb);
	if (JTJ)
		memset(JTJ, 0, p * p * sizeof *JTJ);
	if (g)
		memset(g, 0, p * sizeof *g);
	int index[FIT_TABLE_PARAMS + FIT_SHOT_PARAMS];
	size_t i = 0;
	for (int s = 0; s < pb->shot_count; ++s) {
		for (size_t c = 0; c < width; ++c)
			index[c] = param_of_column(pb, s, (int)c);
		for (long r = 0; r < 2 * pb->shots[s].obs_count; ++r, ++i) {
			const double *row = J->rows + i * width;
			for (size_t a = 0; a < width; ++a) {
				if (row[a] == 0.0)
					continue; // (beyond the horizon every row is zero)
				const size_t ja = (size_t)index[a];
				if (g)
					g[ja] += row[a] * f[i];
				for (size_t b = a; JTJ && b < width; ++b)
					JTJ[ja * p + (size_t)index[b]] += row[a] * row[b];
			}
		}
	}
	// The penalty rows: each is nonzero in a shot's tip offsets or one table parameter at most, so
	// only their nonzero entries are multiplied (nonzero: room for p indices).
	for (size_t r = 0; r < p; ++r) {
		const double *row = J->penalty + r * p;
		size_t count = 0;
		for (size_t j = 0; j < p; ++j)
			if (row[j] != 0.0)
				nonzero[count++] = j;
		for (size_t a = 0; a < count; ++a) {
			const size_t ja = nonzero[a];
			if (g)
				g[ja] += row[ja] * f[pb->n_obs + r];
			for (size_t b = a; JTJ && b < count; ++b)
				JTJ[ja * p + nonzero[b]] += row[ja] * row[nonzero[b]];
		}
	}
	// Each shot's block columns ascend in x, so every product above landed in the upper triangle;
	// mirror it.
	for (size_t a = 0; JTJ && a < p; ++a)
		for (size_t b = a + 1; b < p; ++b)
			JTJ[b * p + a] = JTJ[a * p + b];
}
