// The least squares machinery of pool-fit: GSL's trust region (Levenberg-Marquardt with More's
// scaling) on the residuals and Jacobian of residuals.c, with the last evaluation cached (GSL asks
// for the residuals and then the Jacobian at the same point) and optionally one coordinate held
// fixed (the profile intervals, profile.c). Small problems go to gsl_multifit_nlinear with the
// dense Jacobian (QR); large ones (several shots sharing a table) to gsl_multilarge_nlinear with
// J^T J built from the Jacobian's blocks (Cholesky), whose cost is linear in the shots.
#ifndef POOL_TOOLS_FIT_LEAST_SQUARES_H
#define POOL_TOOLS_FIT_LEAST_SQUARES_H

#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_multilarge_nlinear.h>

#include "fit.h"

typedef struct fit_ls {
	fit_problem problem;     ///< the problem as minimised now (its horizon changes by stage)
	fit_worker *workers;
	int max_iterations;      ///< per minimisation
	double *x;               ///< scratch, p
	double *anchor;          ///< where the current minimisation started (problem.anchor)
	bool blocks;             ///< the normal equations by blocks (gsl_multilarge_nlinear), else dense
	fit_jacobian_blocks jac; ///< the last Jacobian
	double *dense;           ///< the last Jacobian, n x p (dense path only)
	double *normal;          ///< scratch: J^T J (p x p)
	double *gradient;        ///< scratch: J^T f (p)
	size_t *nonzero;         ///< scratch: p indices
	double *cached_x;        ///< the x of the last residual evaluation (p)
	double *cached_f;        ///< its residual rows (n)
	uint64_t *cached_sig;    ///< its shots' collision signatures
	bool cached;
	pool_result error;       ///< the library's failure during the last minimisation, or POOL_OK
	int fixed;               ///< the coordinate held fixed, or -1
	gsl_multifit_nlinear_workspace *w, *w_reduced; ///< p and p - 1 unknowns (dense path)
	gsl_multilarge_nlinear_workspace *lw, *lw_reduced; ///< the same (blocks path)
} fit_ls;

/// Allocates the workspaces and workers for pb. Returns 0, or -1 when out of memory.
int fit_ls_create(fit_ls *ls, const fit_problem *pb, int max_iterations);
void fit_ls_free(fit_ls *ls);

/// Residual rows at x (cached), into ls->cached_f. Returns 0, or -1 (ls->error says why).
int fit_ls_evaluate(fit_ls *ls, const double *x);

/// The Jacobian at x into ls->jac (and ls->dense on the dense path). Returns 0 or -1.
int fit_ls_jacobian(fit_ls *ls, const double *x);

/// (J^T J)^-1 at x (p x p, internal units, without sigma^2). Returns 0 or -1 (ls->error).
int fit_ls_covariance(fit_ls *ls, const double *x, gsl_matrix *cov);

/// Minimises from x (updated to the minimum), x[fixed] held (fixed < 0: all free). *cost: the sum
/// of squares of all rows there; *iterations adds the driver's. Returns the driver's GSL status,
/// or -1 when the library failed (ls->error).
int fit_ls_minimize(fit_ls *ls, double *x, int fixed, size_t *iterations, double *cost);

/// Sum of squares of n numbers.
double fit_sum_squares(const double *f, size_t n);

#endif
