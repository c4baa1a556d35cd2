// pool-fit's intervals: standard errors from the covariance at the best minimum, and 95 %
// intervals from the profile of the tracks' cost (or from the covariance alone), spanning the
// other minima that fit as well.
#ifndef POOL_TOOLS_FIT_PROFILE_H
#define POOL_TOOLS_FIT_PROFILE_H

#include "fit.h"
#include "least_squares.h"

typedef struct fit_intervals_options {
	double sigma;   ///< m, the position noise (given, or estimated at the best minimum)
	bool normal;    ///< sigma was given: normal quantiles, else Student's t with the residual's dof
	fit_interval_kind profile;
} fit_intervals_options;

/// Fills out (whose x is the best minimum, and dof, sigma) with the residual's figures, the
/// values as reported, standard errors, correlations and 95 % intervals. minima[k] (p each) with
/// their costs are every start's minimum: those that fit as well as the best and are distinct
/// from it widen the intervals (out->alternatives). Returns 0, or -1 (ls->error, or memory).
int fit_intervals(fit_ls *ls, const fit_intervals_options *o, fit_solution *out, const double *minima,
                  const double *costs, int count);

#endif
