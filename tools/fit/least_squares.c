// GSL's nonlinear least squares on the simulated tracks (least_squares.h).
#include "least_squares.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

// The driver's stopping tests (GSL's names): a step below FIT_XTOL relative to the parameters, or
// a scaled gradient below FIT_GTOL. Both far below what 1 mm of track noise can resolve, so the
// minimum is reached to rounding before the standard errors are read off.
#define FIT_XTOL 1e-10
#define FIT_GTOL 1e-10
#define FIT_FTOL 0.0

double fit_sum_squares(const double *f, size_t n) {
	double s = 0.0;
	for (size_t i = 0; i < n; ++i)
		s += f[i] * f[i];
	return s;
}

int fit_ls_create(fit_ls *ls, const fit_problem *pb, int max_iterations) {
	memset(ls, 0, sizeof *ls);
	ls->problem = *pb;
	ls->max_iterations = max_iterations;
	ls->fixed = -1;
	const size_t p = (size_t)pb->p, n = pb->n, width = (size_t)fit_jacobian_width(pb);
	// The dense path factorises the n x p Jacobian by QR, robust when parameters are nearly
	// degenerate; each step costs n p^2 (GSL's unblocked Householder steps, or dsyrk for J^T J),
	// which is quadratic in the shots of a joint fit: there J^T J comes from the blocks instead.
	ls->blocks = pb->linear == FIT_LINEAR_BLOCKS || (pb->linear == FIT_LINEAR_AUTO && pb->p > FIT_DENSE_MAX_PARAMS);
	ls->x = malloc(p * sizeof *ls->x);
	ls->anchor = malloc(p * sizeof *ls->anchor);
	ls->jac.rows = malloc((pb->n_obs * width > 0 ? pb->n_obs * width : 1) * sizeof *ls->jac.rows);
	ls->jac.penalty = malloc(p * p * sizeof *ls->jac.penalty);
	ls->dense = ls->blocks ? NULL : malloc(n * p * sizeof *ls->dense);
	ls->normal = malloc(p * p * sizeof *ls->normal);
	ls->gradient = malloc(p * sizeof *ls->gradient);
	ls->nonzero = malloc(p * sizeof *ls->nonzero);
	ls->cached_x = malloc(p * sizeof *ls->cached_x);
	ls->cached_f = malloc(n * sizeof *ls->cached_f);
	ls->cached_sig = malloc((size_t)pb->shot_count * sizeof *ls->cached_sig);
	bool ready = ls->x && ls->anchor && ls->jac.rows && ls->jac.penalty && (ls->blocks || ls->dense) && ls->normal &&
	             ls->gradient && ls->nonzero && ls->cached_x && ls->cached_f && ls->cached_sig;
	if (ready && ls->blocks) {
		gsl_multilarge_nlinear_parameters params = gsl_multilarge_nlinear_default_parameters();
		params.trs = gsl_multilarge_nlinear_trs_lm;
		params.scale = gsl_multilarge_nlinear_scale_more;
		// Modified Cholesky: GSL perturbs J^T J + mu D^T D where it is near singular.
		params.solver = gsl_multilarge_nlinear_solver_mcholesky;
		ls->lw = gsl_multilarge_nlinear_alloc(gsl_multilarge_nlinear_trust, &params, n, p);
		ls->lw_reduced = p > 1 ? gsl_multilarge_nlinear_alloc(gsl_multilarge_nlinear_trust, &params, n, p - 1) : NULL;
		ready = ls->lw && (p <= 1 || ls->lw_reduced);
	} else if (ready) {
		gsl_multifit_nlinear_parameters params = gsl_multifit_nlinear_default_parameters();
		params.trs = gsl_multifit_nlinear_trs_lm;
		params.scale = gsl_multifit_nlinear_scale_more;
		params.solver = gsl_multifit_nlinear_solver_qr;
		ls->w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, p);
		ls->w_reduced = p > 1 ? gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, p - 1) : NULL;
		ready = ls->w && (p <= 1 || ls->w_reduced);
	}
	if (!ready || fit_workers_create(pb, pb->threads, &ls->workers) != 0) {
		fit_ls_free(ls);
		return -1;
	}
	return 0;
}

void fit_ls_free(fit_ls *ls) {
	if (ls->w)
		gsl_multifit_nlinear_free(ls->w);
	if (ls->w_reduced)
		gsl_multifit_nlinear_free(ls->w_reduced);
	if (ls->lw)
		gsl_multilarge_nlinear_free(ls->lw);
	if (ls->lw_reduced)
		gsl_multilarge_nlinear_free(ls->lw_reduced);
	fit_workers_free(ls->workers, ls->problem.threads);
	free(ls->x);
	free(ls->anchor);
	free(ls->jac.rows);
	free(ls->jac.penalty);
	free(ls->dense);
	free(ls->normal);
	free(ls->gradient);
	free(ls->nonzero);
	free(ls->cached_x);
	free(ls->cached_f);
	free(ls->cached_sig);
	memset(ls, 0, sizeof *ls);
}

int fit_ls_evaluate(fit_ls *ls, const double *x) {
	size_t p = (size_t)ls->problem.p;
	if (ls->cached && memcmp(ls->cached_x, x, p * sizeof *x) == 0)
		return 0;
	pool_result r = fit_residuals(&ls->problem, x, ls->workers, ls->cached_f, ls->cached_sig);
	if (r != POOL_OK) {
		ls->error = r;
		ls->cached = false;
		return -1;
	}
	memcpy(ls->cached_x, x, p * sizeof *x);
	ls->cached = true;
	return 0;
}

int fit_ls_jacobian(fit_ls *ls, const double *x) {
	if (fit_ls_evaluate(ls, x) != 0)
		return -1;
	pool_result r = fit_jacobian(&ls->problem, x, ls->cached_f, ls->cached_sig, ls->workers, &ls->jac);
	if (r != POOL_OK) {
		ls->error = r;
		return -1;
	}
	if (ls->dense)
		fit_jacobian_dense(&ls->problem, &ls->jac, ls->dense);
	return 0;
}

int fit_ls_covariance(fit_ls *ls, const double *x, gsl_matrix *cov) {
	if (fit_ls_jacobian(ls, x) != 0)
		return -1;
	const size_t p = (size_t)ls->problem.p;
	if (ls->dense) {
		gsl_matrix_view J = gsl_matrix_view_array(ls->dense, ls->problem.n, p);
		gsl_multifit_nlinear_covar(&J.matrix, 0.0, cov);
		return 0;
	}
	// The inverse of J^T J, equilibrated first (its diagonal made 1: a tip offset's column is
	// 1e3 times a speed's), by Cholesky; modified Cholesky where it is not positive definite to
	// rounding (it is, with the tether of fit_penalty_rows).
	fit_jacobian_normal(&ls->problem, &ls->jac, ls->cached_f, ls->normal, NULL, ls->nonzero);
	double *d = ls->gradient;
	for (size_t j = 0; j < p; ++j)
		d[j] = ls->normal[j * p + j] > 0.0 ? 1.0 / sqrt(ls->normal[j * p + j]) : 1.0;
	for (size_t a = 0; a < p; ++a)
		for (size_t b = 0; b < p; ++b)
			gsl_matrix_set(cov, a, b, d[a] * ls->normal[a * p + b] * d[b]);
	gsl_matrix *copy = gsl_matrix_alloc(p, p);
	gsl_permutation *perm = gsl_permutation_alloc(p);
	if (!copy || !perm) {
		gsl_matrix_free(copy);
		gsl_permutation_free(perm);
		ls->error = POOL_ERR_OUT_OF_MEMORY;
		return -1;
	}
	gsl_matrix_memcpy(copy, cov);
	if (gsl_linalg_cholesky_decomp1(cov) == GSL_SUCCESS) {
		gsl_linalg_cholesky_invert(cov);
	} else {
		gsl_linalg_mcholesky_decomp(copy, perm, NULL);
		gsl_linalg_mcholesky_invert(copy, perm, cov);
	}
	for (size_t a = 0; a < p; ++a)
		for (size_t b = 0; b < p; ++b)
			gsl_matrix_set(cov, a, b, d[a] * gsl_matrix_get(cov, a, b) * d[b]);
	gsl_matrix_free(copy);
	gsl_permutation_free(perm);
	return 0;
}

/// The full vector from GSL's (without the fixed coordinate, whose value ls->x keeps).
static void expand(fit_ls *ls, const gsl_vector *v) {
	for (size_t i = 0, j = 0; j < (size_t)ls->problem.p; ++j)
		if ((int)j != ls->fixed)
			ls->x[j] = gsl_vector_get(v, i++);
}

static int f_callback(const gsl_vector *v, void *params, gsl_vector *f) {
	fit_ls *ls = params;
	expand(ls, v);
	if (fit_ls_evaluate(ls, ls->x) != 0)
		return GSL_EFAILED;
	for (size_t i = 0; i < f->size; ++i)
		gsl_vector_set(f, i, ls->cached_f[i]);
	return GSL_SUCCESS;
}

static int df_callback(const gsl_vector *v, void *params, gsl_matrix *J) {
	fit_ls *ls = params;
	expand(ls, v);
	if (fit_ls_jacobian(ls, ls->x) != 0)
		return GSL_EFAILED;
	const size_t p = (size_t)ls->problem.p;
	for (size_t i = 0; i < J->size1; ++i)
		for (size_t j = 0, k = 0; j < p; ++j)
			if ((int)j != ls->fixed)
				gsl_matrix_set(J, i, k++, ls->dense[i * p + j]);
	return GSL_SUCCESS;
}

/// The blocks path's Jacobian callback: GSL asks for v = J^T u (u = f at x, by the trust
/// region's calls) and J^T J, here from the blocks, without the fixed coordinate's row and column.
static int df_blocks_callback(CBLAS_TRANSPOSE_t trans, const gsl_vector *v_in, const gsl_vector *u, void *params,
                              gsl_vector *v, gsl_matrix *JTJ) {
	fit_ls *ls = params;
	expand(ls, v_in);
	if (fit_ls_jacobian(ls, ls->x) != 0)
		return GSL_EFAILED;
	const fit_problem *pb = &ls->problem;
	const size_t p = (size_t)pb->p;
	if (v && trans != CblasTrans)
		return GSL_EINVAL; // (the trust region with a direct solver only asks for J^T u)
	bool u_is_f = true;
	for (size_t i = 0; u && u_is_f && i < u->size; ++i)
		u_is_f = gsl_vector_get(u, i) == ls->cached_f[i];
	const double *f = ls->cached_f;
	double *copy = NULL;
	if (u && !u_is_f) {
		if (!(copy = malloc(u->size * sizeof *copy)))
			return GSL_ENOMEM;
		for (size_t i = 0; i < u->size; ++i)
			copy[i] = gsl_vector_get(u, i);
		f = copy;
	}
	fit_jacobian_normal(pb, &ls->jac, f, JTJ ? ls->normal : NULL, v ? ls->gradient : NULL, ls->nonzero);
	free(copy);
	for (size_t a = 0, ka = 0; a < p; ++a) {
		if ((int)a == ls->fixed)
			continue;
		if (v)
			gsl_vector_set(v, ka, ls->gradient[a]);
		for (size_t b = 0, kb = 0; JTJ && b < p; ++b)
			if ((int)b != ls->fixed)
				gsl_matrix_set(JTJ, ka, kb++, ls->normal[a * p + b]);
		++ka;
	}
	return GSL_SUCCESS;
}

int fit_ls_minimize(fit_ls *ls, double *x, int fixed, size_t *iterations, double *cost) {
	const size_t p = (size_t)ls->problem.p, n = ls->problem.n;
	ls->fixed = fixed;
	ls->error = POOL_OK;
	ls->cached = false; // the problem's horizon may have changed
	memcpy(ls->x, x, p * sizeof *x);
	memcpy(ls->anchor, x, p * sizeof *x);
	ls->problem.anchor = ls->anchor;
	size_t m = fixed >= 0 ? p - 1 : p;
	gsl_vector *start = gsl_vector_alloc(m > 0 ? m : 1);
	if (!start) {
		ls->error = POOL_ERR_OUT_OF_MEMORY;
		return -1;
	}
	for (size_t j = 0, i = 0; j < p; ++j)
		if ((int)j != fixed)
			gsl_vector_set(start, i++, x[j]);
	int status = GSL_SUCCESS;
	if (m == 0) { // nothing left to move
		if (fit_ls_evaluate(ls, x) != 0)
			status = -1;
		else
			*cost = fit_sum_squares(ls->cached_f, n);
		gsl_vector_free(start);
		ls->fixed = -1;
		return status;
	}
	int info = 0;
	size_t done = 0;
	const gsl_vector *position, *residual;
	if (ls->blocks) {
		gsl_multilarge_nlinear_workspace *lw = fixed >= 0 ? ls->lw_reduced : ls->lw;
		gsl_multilarge_nlinear_fdf fdf = {.f = f_callback, .df = df_blocks_callback, .n = n, .p = m, .params = ls};
		status = gsl_multilarge_nlinear_init(start, &fdf, lw);
		if (status == GSL_SUCCESS)
			status = gsl_multilarge_nlinear_driver((size_t)ls->max_iterations, FIT_XTOL, FIT_GTOL, FIT_FTOL, NULL, NULL,
			                                       &info, lw);
		done = gsl_multilarge_nlinear_niter(lw);
		position = gsl_multilarge_nlinear_position(lw);
		residual = gsl_multilarge_nlinear_residual(lw);
	} else {
		gsl_multifit_nlinear_workspace *w = fixed >= 0 ? ls->w_reduced : ls->w;
		gsl_multifit_nlinear_fdf fdf = {.f = f_callback, .df = df_callback, .n = n, .p = m, .params = ls};
		status = gsl_multifit_nlinear_init(start, &fdf, w);
		if (status == GSL_SUCCESS)
			status = gsl_multifit_nlinear_driver((size_t)ls->max_iterations, FIT_XTOL, FIT_GTOL, FIT_FTOL, NULL, NULL,
			                                     &info, w);
		done = gsl_multifit_nlinear_niter(w);
		position = gsl_multifit_nlinear_position(w);
		residual = gsl_multifit_nlinear_residual(w);
	}
	gsl_vector_free(start);
	// GSL reports a start it cannot improve on (no progress in the first iteration) as the
	// iteration limit; it is a minimum to rounding, as a converged fit is.
	if (status == GSL_EMAXITER && done < (size_t)ls->max_iterations)
		status = GSL_SUCCESS;
	*iterations += done;
	expand(ls, position);
	memcpy(x, ls->x, p * sizeof *x);
	*cost = fit_sum_squares(residual->data, n);
	ls->fixed = -1;
	return ls->error != POOL_OK ? -1 : status;
}
