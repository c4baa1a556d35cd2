// GSL's nonlinear least squares on the simulated tracks (least_squares.h).
#include "least_squares.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

// The driver's stopping tests (GSL's names): a step below FIT_XTOL relative to the parameters, or
// a scaled gradient below FIT_GTOL. Both far below what 1 mm of track noise can resolve, so the
// minimum is reached to rounding before the standard errors are read off.
#define FIT_XTOL 1e-10
#define FIT_GTOL 1e-10
#define FIT_FTOL 0.0
// The most parameters solved by QR (one shot's strike and a few table parameters: every test's
// single-shot and three-shot fits); more go to the modified Cholesky solver (fit_ls_create).
#define FIT_QR_MAX_PARAMETERS 16

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
	const size_t p = (size_t)pb->p, n = pb->n;
	ls->x = malloc(p * sizeof *ls->x);
	ls->anchor = malloc(p * sizeof *ls->anchor);
	ls->jac = malloc(n * p * sizeof *ls->jac);
	ls->cached_x = malloc(p * sizeof *ls->cached_x);
	ls->cached_f = malloc(n * sizeof *ls->cached_f);
	ls->cached_sig = malloc((size_t)pb->shot_count * sizeof *ls->cached_sig);
	gsl_multifit_nlinear_parameters params = gsl_multifit_nlinear_default_parameters();
	params.trs = gsl_multifit_nlinear_trs_lm;
	params.scale = gsl_multifit_nlinear_scale_more;
	// QR is robust when parameters are nearly degenerate, but factorising the dense n x p Jacobian
	// costs n p^2 with GSL's unblocked Householder steps: above FIT_QR_MAX_PARAMETERS (several
	// shots sharing a table) the modified Cholesky of J^T J, which GSL perturbs where it is
	// near singular, found the same 5-shot fit (23 parameters) in 56 s where QR took 95 s.
	params.solver = p > FIT_QR_MAX_PARAMETERS ? gsl_multifit_nlinear_solver_mcholesky : gsl_multifit_nlinear_solver_qr;
	if (ls->x && ls->anchor && ls->jac && ls->cached_x && ls->cached_f && ls->cached_sig) {
		ls->w = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, p);
		ls->w_reduced = p > 1 ? gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, n, p - 1) : NULL;
	}
	if (!ls->w || (p > 1 && !ls->w_reduced) || fit_workers_create(pb, pb->threads, &ls->workers) != 0) {
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
	fit_workers_free(ls->workers, ls->problem.threads);
	free(ls->x);
	free(ls->anchor);
	free(ls->jac);
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
	pool_result r = fit_jacobian(&ls->problem, x, ls->cached_f, ls->cached_sig, ls->workers, ls->jac);
	if (r != POOL_OK) {
		ls->error = r;
		return -1;
	}
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
				gsl_matrix_set(J, i, k++, ls->jac[i * p + j]);
	return GSL_SUCCESS;
}

int fit_ls_minimize(fit_ls *ls, double *x, int fixed, size_t *iterations, double *cost) {
	const size_t p = (size_t)ls->problem.p, n = ls->problem.n;
	gsl_multifit_nlinear_workspace *w = fixed >= 0 ? ls->w_reduced : ls->w;
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
	gsl_multifit_nlinear_fdf fdf = {.f = f_callback, .df = df_callback, .n = n, .p = m, .params = ls};
	int info = 0;
	status = gsl_multifit_nlinear_init(start, &fdf, w);
	if (status == GSL_SUCCESS)
		status = gsl_multifit_nlinear_driver((size_t)ls->max_iterations, FIT_XTOL, FIT_GTOL, FIT_FTOL, NULL, NULL,
		                                     &info, w);
	gsl_vector_free(start);
	// GSL reports a start it cannot improve on (no progress in the first iteration) as the
	// iteration limit; it is a minimum to rounding, as a converged fit is.
	if (status == GSL_EMAXITER && gsl_multifit_nlinear_niter(w) < (size_t)ls->max_iterations)
		status = GSL_SUCCESS;
	*iterations += gsl_multifit_nlinear_niter(w);
	expand(ls, gsl_multifit_nlinear_position(w));
	memcpy(x, ls->x, p * sizeof *x);
	*cost = fit_sum_squares(gsl_multifit_nlinear_residual(w)->data, n);
	ls->fixed = -1;
	return ls->error != POOL_OK ? -1 : status;
}
