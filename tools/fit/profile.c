// Standard errors and 95 % intervals of a fit.
//
// The covariance sigma^2 (J^T J)^-1 at the minimum is right where the tracks' cost is a parabola
// in the parameters, which is most of the time. It is not where an event changes order near the
// minimum: a side spin that dies just before the first collision or survives just past it puts a
// kink in the cost (steep on one side, flat on the other), and the minimum often sits on it. The
// profile interval does not assume a parabola: a value of parameter j is inside when the cost,
// minimised over all the other parameters with j held there, rises less than q^2 sigma^2 above
// the best (the likelihood-ratio interval; q the 97.5 % quantile). The search starts at the
// covariance's prediction and brackets the crossing, so a parabola costs 3 or 4 fits a side.
#include "profile.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

// Bracketing: the step doubles at most this many times from the covariance's half-width (a
// parameter the tracks barely fix), then this many secant steps on sqrt(cost rise), which is
// linear in the parameter for a parabola.
#define PROFILE_EXPANSIONS 6
#define PROFILE_STEPS 5
// Iterations of each fit of the others: it starts at the covariance's prediction, and the cost
// needs only PROFILE_TOLERANCE of q^2 sigma^2, not the minimum to rounding.
#define PROFILE_ITERATIONS 10
// The crossing is found once the cost rise is within this share of q^2 sigma^2.
#define PROFILE_TOLERANCE 0.02

/// The values as reported: the cue speed where the vector holds the launch speed (fit.h), phi
/// in (-pi, pi]; and T, the derivatives of the reported values by the vector's (p x p).
static void reported(const fit_problem *pb, const double *x, double *values, gsl_matrix *T) {
	gsl_matrix_set_identity(T);
	for (int j = 0; j < pb->p; ++j) {
		int shot, k;
		fit_param_of(pb, j, &shot, &k);
		values[j] = x[j];
		if (shot >= 0 && k == FIT_PHI)
			values[j] = remainder(x[j], 2.0 * 3.14159265358979323846);
		if (shot < 0 || k != FIT_SPEED || pb->cue_speed)
			continue;
		const pool_params *params = &pb->shots[shot].scenario.def.params;
		double v[FIT_SHOT_PARAMS];
		fit_shot_values(pb, x, shot, v);
		values[j] = v[FIT_SPEED];
		double g = fit_launch_gain(params, v[FIT_THETA], v[FIT_A], v[FIT_B]);
		gsl_matrix_set(T, (size_t)j, (size_t)j, 1.0 / g);
		// V = u / g(theta, a, b): the offsets' and elevation's share, by central differences.
		for (int q = 0, i = pb->table_free + shot * pb->shot_free; q < FIT_SHOT_PARAMS; ++q) {
			if (!pb->free_shot[q])
				continue;
			if (q == FIT_THETA || q == FIT_A || q == FIT_B) {
				double h = 1e-6 * fit_shot_params[q].scale, up[FIT_SHOT_PARAMS], down[FIT_SHOT_PARAMS];
				memcpy(up, v, sizeof up);
				memcpy(down, v, sizeof down);
				up[q] += h;
				down[q] -= h;
				double dg = (fit_launch_gain(params, up[FIT_THETA], up[FIT_A], up[FIT_B]) -
				             fit_launch_gain(params, down[FIT_THETA], down[FIT_A], down[FIT_B])) / (2 * h);
				gsl_matrix_set(T, (size_t)j, (size_t)i, -x[j] * dg / (g * g));
			}
			++i;
		}
	}
}

/// (J^T J)^-1 at x (internal units, without sigma^2) into cov.
static int covariance(fit_ls *ls, const double *x, gsl_matrix *cov) { return fit_ls_covariance(ls, x, cov); }

/// Wald estimates at x: reported values, standard errors, value +- q se; correlations when corr.
/// shown receives the covariance (without sigma^2) of the reported values.
static int wald(const fit_problem *pb, const double *x, const gsl_matrix *cov, double sigma, double q,
                fit_estimate *est, double *corr, gsl_matrix *shown) {
	const size_t p = (size_t)pb->p;
	gsl_matrix *T = gsl_matrix_alloc(p, p), *TC = gsl_matrix_alloc(p, p);
	double *values = malloc(p * sizeof *values);
	int status = T && TC && values ? 0 : -1;
	if (status == 0) {
		reported(pb, x, values, T);
		gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, T, cov, 0.0, TC);
		gsl_blas_dgemm(CblasNoTrans, CblasTrans, 1.0, TC, T, 0.0, shown);
		for (size_t j = 0; j < p; ++j) {
			fit_estimate *e = &est[j];
			e->value = values[j];
			e->se = sigma * sqrt(gsl_matrix_get(shown, j, j));
			e->ci_low = e->value - q * e->se;
			e->ci_high = e->value + q * e->se;
			for (size_t k = 0; corr && k < p; ++k) {
				double d = sqrt(gsl_matrix_get(shown, j, j) * gsl_matrix_get(shown, k, k));
				corr[j * p + k] = d > 0.0 ? gsl_matrix_get(shown, j, k) / d : (j == k);
			}
		}
	}
	gsl_matrix_free(T);
	gsl_matrix_free(TC);
	free(values);
	return status;
}

/// One side of parameter j's profile interval: the reported value of j where the cost,
/// minimised over the others, reaches target. best: the minimum (cost c0); dir: how the others
/// follow j to first order (cov's column j over cov_jj); step: the covariance's half-width.
static int profile_side(fit_ls *ls, const double *best, double c0, int j, double side, const double *dir,
                        double step, double target, double *bound, double *scratch) {
	const fit_problem *pb = &ls->problem;
	const size_t p = (size_t)pb->p;
	double *x = scratch, *value = scratch + p;
	gsl_matrix *T = gsl_matrix_alloc(p, p);
	if (!T)
		return -1;
	const double rise = target - c0;
	// g(d) = sqrt(cost rise) - sqrt(rise): 0 at the crossing, linear in d for a parabola.
	double lo = 0.0, g_lo = -sqrt(rise), hi = 0.0, g_hi = 0.0, d = step;
	bool bracketed = false;
	int status = 0;
	for (int k = 0; k < PROFILE_EXPANSIONS + PROFILE_STEPS + 1; ++k) {
		for (size_t i = 0; i < p; ++i)
			x[i] = best[i] + side * d * dir[i];
		size_t iterations = 0;
		double cost = 0.0;
		if (fit_ls_minimize(ls, x, j, &iterations, &cost) < 0) {
			status = -1;
			break;
		}
		double g = sqrt(fmax(cost - c0, 0.0)) - sqrt(rise);
		if (fabs(cost - target) <= PROFILE_TOLERANCE * rise) {
			lo = d; // found
			bracketed = false;
			break;
		}
		if (g < 0.0) {
			lo = d, g_lo = g;
		} else {
			hi = d, g_hi = g, bracketed = true;
		}
		if (!bracketed) {
			if (k >= PROFILE_EXPANSIONS)
				break; // the tracks barely fix j: report as far as was searched
			d *= 2.0;
			continue;
		}
		// Secant inside the bracket, kept off its ends.
		double next = lo - g_lo * (hi - lo) / (g_hi - g_lo);
		double margin = 0.05 * (hi - lo);
		d = fmin(fmax(next, lo + margin), hi - margin);
	}
	if (status == 0) {
		double end = bracketed ? lo - g_lo * (hi - lo) / (g_hi - g_lo) : lo;
		for (size_t i = 0; i < p; ++i)
			x[i] = best[i] + side * end * dir[i];
		reported(pb, x, value, T);
		*bound = value[j];
	}
	gsl_matrix_free(T);
	return status;
}

/// An interval ends where the parameter's admissible values do (fit_param_info, the tip offsets
/// within FIT_TIP_LIMIT R): an alternative minimum whose Wald interval is wide (a side spin the
/// tracks cannot see, held only by the tether) is "anywhere it can be", not beyond.
static void clamp_interval(const fit_problem *pb, int j, fit_estimate *e) {
	int shot, k;
	const fit_param_info *info = fit_param_of(pb, j, &shot, &k);
	double lo = info->lo, hi = info->hi;
	if (shot >= 0 && (k == FIT_A || k == FIT_B)) {
		const double limit = FIT_TIP_LIMIT * pb->shots[shot].scenario.def.params.ball_radius;
		lo = fmax(lo, -limit);
		hi = fmin(hi, limit);
	}
	e->ci_low = fmax(e->ci_low, lo);
	e->ci_high = fmin(e->ci_high, hi);
}

int fit_intervals(fit_ls *ls, const fit_intervals_options *o, fit_solution *out, const double *minima,
                  const double *costs, int count) {
	const fit_problem *pb = &ls->problem;
	const size_t p = (size_t)pb->p;
	ls->problem.horizon = INFINITY;
	const double q = o->normal ? gsl_cdf_ugaussian_Pinv(0.975) : gsl_cdf_tdist_Pinv(0.975, (double)out->dof);
	gsl_matrix *cov = gsl_matrix_alloc(p, p), *T = gsl_matrix_alloc(p, p), *shown = gsl_matrix_alloc(p, p);
	double *start = malloc(p * sizeof *start), *values = malloc(p * sizeof *values);
	double *dir = malloc(p * sizeof *dir), *scratch = malloc(2 * p * sizeof *scratch);
	fit_estimate *alt = malloc(p * sizeof *alt);
	int status = cov && T && shown && start && values && dir && scratch && alt ? 0 : -1;
	if (status == 0) { // the start, as reported
		fit_start_vector(pb, start);
		reported(pb, start, values, T);
		for (size_t j = 0; j < p; ++j)
			out->est[j].initial = values[j];
	}
	if (status == 0 && fit_ls_evaluate(ls, out->x) == 0) {
		out->rss = fit_sum_squares(ls->cached_f, pb->n_obs);
		out->rms = sqrt(out->rss / (double)pb->n_obs);
		for (int s = 0, row = 0; s < pb->shot_count; row += 2 * (int)pb->shots[s].obs_count, ++s)
			out->shot_rms[s] = sqrt(fit_sum_squares(ls->cached_f + row, 2 * (size_t)pb->shots[s].obs_count) /
			                        (2.0 * (double)pb->shots[s].obs_count));
	} else {
		status = -1;
	}
	if (status == 0 && covariance(ls, out->x, cov) != 0)
		status = -1;
	if (status == 0)
		status = wald(pb, out->x, cov, o->sigma, q, out->est, out->correlation, shown);
	const double c0 = fit_sum_squares(ls->cached_f, pb->n);
	const double target = c0 + q * q * o->sigma * o->sigma;
	out->profiled = o->profile == FIT_INTERVALS_PROFILE || (o->profile == FIT_INTERVALS_AUTO && pb->p <= FIT_PROFILE_MAX_PARAMS);
	// The profiles hold the cue speed, not the launch speed, fixed: the speed's interval is the
	// cue speed's, and the vector is then the reported values (phi unwrapped).
	double *best = malloc(p * sizeof *best);
	if (!best)
		status = -1;
	else
		memcpy(best, out->x, p * sizeof *best);
	for (int j = 0; status == 0 && j < pb->p; ++j) {
		int shot, k;
		fit_param_of(pb, j, &shot, &k);
		if (shot >= 0 && k == FIT_SPEED)
			best[j] = out->est[j].value;
	}
	ls->problem.cue_speed = true;
	const int iterations = ls->max_iterations;
	ls->max_iterations = PROFILE_ITERATIONS;
	for (int j = 0; status == 0 && out->profiled && j < pb->p; ++j) {
		double cjj = gsl_matrix_get(shown, (size_t)j, (size_t)j);
		for (size_t i = 0; i < p; ++i)
			dir[i] = cjj > 0.0 ? gsl_matrix_get(shown, i, (size_t)j) / cjj : (i == (size_t)j);
		double step = q * o->sigma * sqrt(cjj), up = 0.0, down = 0.0;
		if (!(step > 0.0))
			continue; // j does not act on the tracks at all: nothing to profile
		if (profile_side(ls, best, c0, j, 1.0, dir, step, target, &up, scratch) != 0 ||
		    profile_side(ls, best, c0, j, -1.0, dir, step, target, &down, scratch) != 0) {
			status = -1;
			break;
		}
		out->est[j].ci_low = fmin(up, down);
		out->est[j].ci_high = fmax(up, down);
	}
	ls->problem.cue_speed = false;
	ls->max_iterations = iterations;
	ls->cached = false;
	// Other minima the tracks cannot tell from the best (a cost rise below q^2 sigma^2): each
	// parameter's profile interval reaches them, so the reported interval spans their intervals.
	for (int k = 0; status == 0 && k < count; ++k) {
		const double *xk = minima + (size_t)k * p;
		if (costs[k] > target || memcmp(xk, out->x, p * sizeof *xk) == 0)
			continue;
		reported(pb, xk, values, T);
		bool distinct = false;
		for (size_t j = 0; j < p; ++j)
			distinct = distinct || fabs(values[j] - out->est[j].value) > out->est[j].se;
		if (!distinct)
			continue;
		if (covariance(ls, xk, cov) != 0) {
			status = -1;
			break;
		}
		if (wald(pb, xk, cov, o->sigma, q, alt, NULL, shown) != 0) {
			status = -1;
			break;
		}
		out->alternatives++;
		for (size_t j = 0; j < p; ++j) {
			out->est[j].ci_low = fmin(out->est[j].ci_low, alt[j].ci_low);
			out->est[j].ci_high = fmax(out->est[j].ci_high, alt[j].ci_high);
		}
	}
	for (int j = 0; status == 0 && j < pb->p; ++j)
		clamp_interval(pb, j, &out->est[j]);
	gsl_matrix_free(cov);
	gsl_matrix_free(T);
	gsl_matrix_free(shown);
	free(start);
	free(values);
	free(dir);
	free(scratch);
	free(alt);
	free(best);
	return status;
}
