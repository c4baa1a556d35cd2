// The fit: several starts of the least squares (least_squares.c), the best minimum, its standard
// errors, and 95 % intervals that are honest where the tracks' cost is not a parabola (profile.c)
// or has other minima that fit as well.
#define _POSIX_C_SOURCE 200809L
#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "fit.h"
#include "least_squares.h"
#include "profile.h"
#include "splitmix.h"

// The first horizon (s of tracks): about the time a shot's first collision takes, so the first
// stage sees the struck ball alone and fixes its direction and speed. Each stage sees this much
// more: 1.3 keeps each new stretch short enough that a spin the earlier stages could not see (a
// side spin shows only at a cushion) is found before the balls' paths diverge; doubling the
// horizon left 1 trial in 10 in another minimum (docs/commands.md "pool-fit").
#define FIT_FIRST_HORIZON 0.25
#define FIT_HORIZON_GROWTH 1.3
// Iterations of a stage before the last: it only has to bring the iterate near enough for the
// next, longer one.
#define FIT_STAGE_ITERATIONS 100
// Starts near the best minimum: tip offsets (and t0, theta, by the same share of their scales)
// moved by this (m), phi by this sd (rad, 0.05 degree), the other parameters by this relative sd.
#define FIT_POLISH_TIP 5e-4
#define FIT_POLISH_PHI 8.7e-4
#define FIT_POLISH_RELATIVE 0.01
// A fit whose rms is above this many times the tracks' own noise (fit_track_noise) is in a wrong
// minimum: a converged one is within a few per cent of it (the rms's own sampling error is
// 1/sqrt(2n), 2 % at 1,000 observations, and the noise estimate's a few per cent). A cushion shot
// fitted with the default cushion's two parameters stopped 17 % above it (mu_cushion_mathavan at
// 4.4 of a true 0.18), which the earlier 1.3 let pass. Retries start from random points near
// the start: phi within this sd (rad, 1 degree), speeds and table parameters within this relative
// sd, tip offsets uniform within this share of the radius either way.
#define FIT_RETRY_RATIO 1.15
#define FIT_RETRY_PHI 0.0174533
#define FIT_RETRY_RELATIVE 0.1
#define FIT_RETRY_TIP 0.4
// Starts along the covariance's longest axes, once the starts are done (axis_starts): this many
// axes, each way, at these multiples of the axis's standard deviation, for fits of up to
// FIT_PROFILE_MAX_PARAMS parameters. Under the default cushion the Levenberg-Marquardt iteration
// can stop where its trust region collapsed rather than at a minimum (its step test holds), and
// a minimum of another tip offset can lie a few hundred standard deviations away along the
// long axis while the rms cannot tell (a 1.03 mm fit 167 sigma^2 above the truth's cost):
// 3 sigma finds the first, 300 the second, 30 what lies between.
#define FIT_AXIS_COUNT 2
#define FIT_AXIS_ROUNDS 2
static const double fit_axis_steps[] = {3.0, 30.0, 300.0};
#define FIT_AXIS_STEPS ((int)(sizeof fit_axis_steps / sizeof fit_axis_steps[0]))
#define FIT_AXIS_STARTS (FIT_AXIS_ROUNDS * FIT_AXIS_COUNT * 2 * FIT_AXIS_STEPS)

static double now_s(void) {
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/// A uniform deviate in (0, 1) from a splitmix64 stream (the random starts need no more).
static double uniform(uint64_t *state) {
	return pool_splitmix_uniform(state);
}

/// A standard normal deviate (Box-Muller).
static double normal(uint64_t *state) {
	double u = uniform(state), v = uniform(state);
	return sqrt(-2.0 * log(u)) * cos(6.283185307179586 * v);
}

/// The given starting points: the problem's start (each shot's scenario strike, or its track
/// guess), and the track guesses where a scenario gave a strike too. Returns how many.
static int given_starts(const fit_problem *pb, double *starts) {
	fit_start_vector(pb, starts);
	bool differs = false;
	double *second = starts + pb->p;
	memcpy(second, starts, (size_t)pb->p * sizeof *second);
	for (int s = 0; s < pb->shot_count; ++s) {
		const fit_shot *sh = &pb->shots[s];
		double phi, speed;
		if (!sh->scenario.has_strike || !fit_guess_from_tracks(sh, &sh->scenario.def.params, &phi, &speed))
			continue;
		int j = pb->table_free + s * pb->shot_free;
		for (int k = 0; k < FIT_SHOT_PARAMS; ++k) {
			if (!pb->free_shot[k])
				continue;
			if (k == FIT_PHI && phi != second[j])
				second[j] = phi, differs = true;
			if (k == FIT_SPEED) { // the vector holds the launch speed (fit.h)
				const pool_strike *st = &sh->scenario.strike;
				double u = speed * fit_launch_gain(&sh->scenario.def.params, st->theta, st->a, st->b);
				if (u != second[j])
					second[j] = u, differs = true;
			}
			++j;
		}
	}
	return 1 + differs;
}

/// Start k after the given ones, near the best minimum x: the tip offsets of every shot moved by
/// +-FIT_POLISH_TIP (a up, a down, b up, b down), then random steps of every parameter. A minimum
/// over all the tracks can have neighbours that fit as well (a side spin that dies just before a
/// collision or just after it); these starts look for them.
static void polish_start(const fit_problem *pb, const double *x, int k, uint64_t *rng, double *out) {
	memcpy(out, x, (size_t)pb->p * sizeof *out);
	for (int j = 0; j < pb->p; ++j) {
		int shot, index;
		const fit_param_info *info = fit_param_of(pb, j, &shot, &index);
		if (k < 4) {
			if (shot >= 0 && index == (k < 2 ? FIT_A : FIT_B))
				out[j] += k % 2 ? -FIT_POLISH_TIP : FIT_POLISH_TIP;
			continue;
		}
		double z = normal(rng);
		if (shot >= 0 && index == FIT_PHI)
			out[j] += FIT_POLISH_PHI * z;
		else if (shot >= 0 && (index == FIT_A || index == FIT_B || index == FIT_T0 || index == FIT_THETA))
			out[j] += FIT_POLISH_TIP / 1e-3 * info->scale * z;
		else
			out[j] *= exp(FIT_POLISH_RELATIVE * z);
	}
	fit_clamp(pb, out, out);
}

/// A retry's start: a random point near the start x.
static void retry_start(const fit_problem *pb, const double *x, uint64_t *rng, double *out) {
	memcpy(out, x, (size_t)pb->p * sizeof *out);
	for (int j = 0; j < pb->p; ++j) {
		int shot, index;
		fit_param_of(pb, j, &shot, &index);
		if (shot >= 0 && index == FIT_PHI)
			out[j] += FIT_RETRY_PHI * normal(rng);
		else if (shot >= 0 && (index == FIT_A || index == FIT_B)) {
			double R = pb->shots[shot].scenario.def.params.ball_radius;
			out[j] = FIT_RETRY_TIP * R * (2.0 * uniform(rng) - 1.0);
		} else if (!(shot >= 0 && (index == FIT_T0 || index == FIT_THETA)))
			out[j] *= exp(FIT_RETRY_RELATIVE * normal(rng));
	}
	fit_clamp(pb, out, out);
}

/// One start from x0 (overwritten by its minimum): over the growing horizon when staged, else
/// over all the tracks at once. Returns the last stage's GSL status or -1 (ls->error).
static int run_start(fit_ls *ls, double *x0, bool staged, size_t *iterations, double *cost) {
	const fit_problem *pb = &ls->problem;
	double last = pb->shots[0].obs[pb->shots[0].obs_count - 1].t;
	for (int s = 1; s < pb->shot_count; ++s)
		last = fmax(last, pb->shots[s].obs[pb->shots[s].obs_count - 1].t);
	*iterations = 0;
	// A growing horizon: each stage starts where the previous one ended, so the iterate's
	// collision sequence follows the observed one a stage at a time.
	for (double horizon = FIT_FIRST_HORIZON;; horizon *= FIT_HORIZON_GROWTH) {
		ls->problem.horizon = staged && horizon < last ? horizon : INFINITY;
		const int limit = ls->max_iterations;
		if (isfinite(ls->problem.horizon) && ls->max_iterations > FIT_STAGE_ITERATIONS)
			ls->max_iterations = FIT_STAGE_ITERATIONS;
		int status = fit_ls_minimize(ls, x0, -1, iterations, cost);
		ls->max_iterations = limit;
		if (status < 0 || !isfinite(ls->problem.horizon))
			return status;
	}
}

/// Each shot's strike fitted alone, the table held at its start (a small problem per shot), into
/// x, the start otherwise: a start for the joint fit near its minimum, whatever the number of
/// shots. Returns 0, or the failing fit's status.
static int shot_by_shot(const fit_problem *pb, const fit_options *o, double *x) {
	fit_start_vector(pb, x);
	for (int s = 0; s < pb->shot_count; ++s) {
		fit_problem one = *pb;
		one.shots = &pb->shots[s];
		one.shot_count = 1;
		memset(one.free_table, 0, sizeof one.free_table);
		one.table_free = 0;
		one.p = pb->shot_free;
		one.n_obs = 2 * (size_t)pb->shots[s].obs_count;
		one.n = one.n_obs + (size_t)one.p;
		fit_options quiet = *o;
		quiet.quiet = true;
		quiet.profile = FIT_INTERVALS_WALD; // only the values are wanted
		// No retries: they restart while the rms is above the tracks' noise, which a shot fitted
		// with the table held at a wrong start cannot reach (all 8 ran on every shot, for nothing).
		quiet.retries = 0;
		quiet.no_axis_starts = true; // a start for the joint fit needs no more
		fit_solution sol;
		int status = fit_solve(&one, &quiet, &sol);
		if (status)
			return status;
		if (!o->quiet)
			fprintf(stderr, "%s: shot %d alone: %d starts, rms %.3g m, %.3f s\n", FIT_PROGRAM, s, sol.starts, sol.rms,
			        sol.seconds);
		// The shot's values, in the joint vector's slots (the launch speed is the same quantity
		// in both: the table's fixed parameters do not enter it).
		memcpy(x + pb->table_free + s * pb->shot_free, sol.x, (size_t)pb->shot_free * sizeof *x);
		fit_solution_free(&sol);
	}
	return 0;
}

/// Starts along the longest axes of the covariance at the best minimum (FIT_AXIS_COUNT axes, each
/// way, FIT_AXIS_STEPS distances), each minimised over all the tracks; a lower minimum becomes the
/// best and the axes are taken again there (FIT_AXIS_ROUNDS at most). Every minimum joins
/// starts/costs (from index *count on, room for FIT_AXIS_STARTS), so the intervals can span
/// those that fit as well. Returns 0, or -1 (ls->error, or memory).
static int axis_starts(fit_ls *ls, double *starts, double *costs, int *count, int *best, int *iterations,
                       bool *converged) {
	const fit_problem *pb = &ls->problem;
	const size_t p = (size_t)pb->p;
	gsl_matrix *cov = gsl_matrix_alloc(p, p), *axes = gsl_matrix_alloc(p, p);
	gsl_vector *lengths = gsl_vector_alloc(p);
	gsl_eigen_symmv_workspace *eigen = gsl_eigen_symmv_alloc(p);
	int status = cov && axes && lengths && eigen ? 0 : -1;
	for (int round = 0; status == 0 && round < FIT_AXIS_ROUNDS; ++round) {
		const int centre = *best;
		const double sigma2 = costs[centre] / (double)((long)pb->n_obs - pb->p);
		if (fit_ls_covariance(ls, starts + (size_t)centre * p, cov) != 0) {
			status = -1;
			break;
		}
		gsl_eigen_symmv(cov, lengths, axes, eigen);
		gsl_eigen_symmv_sort(lengths, axes, GSL_EIGEN_SORT_VAL_DESC);
		for (int axis = 0; status == 0 && axis < FIT_AXIS_COUNT && axis < (int)p; ++axis)
			for (int k = 0; status == 0 && k < 2 * FIT_AXIS_STEPS; ++k) {
				const double sd = sqrt(fmax(gsl_vector_get(lengths, (size_t)axis), 0.0) * sigma2);
				const double d = (k % 2 ? -1.0 : 1.0) * fit_axis_steps[k / 2] * sd;
				double *x0 = starts + (size_t)*count * p;
				for (size_t j = 0; j < p; ++j)
					x0[j] = starts[(size_t)centre * p + j] + d * gsl_matrix_get(axes, j, (size_t)axis);
				fit_clamp(pb, x0, x0);
				size_t used = 0;
				ls->problem.horizon = INFINITY;
				int gsl_status = fit_ls_minimize(ls, x0, -1, &used, &costs[*count]);
				if (gsl_status < 0) {
					status = -1;
					break;
				}
				if (costs[*count] < costs[*best]) {
					*best = *count;
					*iterations = (int)used;
					*converged = gsl_status == GSL_SUCCESS;
				}
				++*count;
			}
		if (*best == centre)
			break; // a minimum along its own axes
	}
	gsl_matrix_free(cov);
	gsl_matrix_free(axes);
	gsl_vector_free(lengths);
	if (eigen)
		gsl_eigen_symmv_free(eigen);
	return status;
}

void fit_solution_free(fit_solution *s) {
	free(s->x);
	free(s->est);
	free(s->correlation);
	free(s->shot_rms);
	memset(s, 0, sizeof *s);
}

static int fail(fit_ls *ls) {
	fprintf(stderr, "%s: %s\n", FIT_PROGRAM, ls->error != POOL_OK ? pool_result_str(ls->error) : "out of memory");
	return POOL_EXIT_INTERNAL;
}

int fit_solve(const fit_problem *pb, const fit_options *o, fit_solution *out) {
	const double started = now_s();
	gsl_set_error_handler_off(); // GSL's default handler aborts; errors come back as statuses here
	const size_t p = (size_t)pb->p;
	memset(out, 0, sizeof *out);
	out->p = pb->p;
	out->x = malloc(p * sizeof *out->x);
	out->est = calloc(p, sizeof *out->est);
	out->correlation = calloc(p * p, sizeof *out->correlation);
	out->shot_rms = calloc((size_t)pb->shot_count, sizeof *out->shot_rms);
	const int start_count = o->starts < 1 ? 1 : o->starts, retries = o->retries > 0 ? o->retries : 0;
	double *starts = malloc((size_t)(start_count + retries + FIT_AXIS_STARTS + 3) * p * sizeof *starts);
	double *costs = malloc((size_t)(start_count + retries + FIT_AXIS_STARTS) * sizeof *costs);
	fit_ls ls;
	bool ready = out->x && out->est && out->correlation && out->shot_rms && starts && costs;
	if (!ready || fit_ls_create(&ls, pb, o->max_iterations) != 0) {
		free(starts);
		free(costs);
		fit_solution_free(out);
		fprintf(stderr, "%s: out of memory\n", FIT_PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	// A fit of several shots, or of the table's parameters, starts from each shot fitted alone
	// (the table held at its start), over the growing horizon like the others: early stages fix
	// what the strikes already agree on, later ones the table, whose wrong start can have bent
	// some shot's own fit. The other staged starts follow only when it ends worse than the
	// tracks' noise.
	// (With no strike parameter free there is nothing to fit shot by shot: the table alone.)
	const bool joint = (pb->shot_count > 1 || pb->table_free > 0) && pb->shot_free > 0;
	int status = 0, best = -1, given = 0;
	if (joint && (status = shot_by_shot(pb, o, starts)) == 0)
		given = 1;
	if (status == 0)
		given += given_starts(pb, starts + (size_t)given * p);
	if (given > start_count)
		given = start_count;
	uint64_t rng = o->seed;
	out->track_noise = fit_track_noise(pb->shots, pb->shot_count);
	const double enough = FIT_RETRY_RATIO * FIT_RETRY_RATIO * out->track_noise * out->track_noise * (double)pb->n_obs;
	double *origin = malloc(p * sizeof *origin);
	if (!origin)
		status = fail(&ls);
	else
		fit_start_vector(pb, origin);
	for (int k = 0; status == 0 && k < start_count + retries; ++k) {
		double *x0 = starts + (size_t)k * p;
		const bool retry = k >= start_count, prefit = joint && k == 0;
		if (retry && !(costs[best] > enough)) // (a NAN noise: no retries)
			break;
		if (joint && k > 0 && k < given && !(costs[best] > enough)) {
			costs[k] = INFINITY; // the shot-by-shot start fits: no staged start needed
			out->starts = k + 1;
			continue;
		}
		if (retry)
			retry_start(pb, origin, &rng, x0);
		else if (k >= given) // near the best so far
			polish_start(pb, starts + (size_t)best * p, k - given, &rng, x0);
		size_t iterations = 0;
		int gsl_status = run_start(&ls, x0, k < given || retry, &iterations, &costs[k]);
		if (gsl_status < 0) {
			status = fail(&ls);
			break;
		}
		if (!o->quiet)
			fprintf(stderr, "%s: start %d of %d (%s): %zu iterations, rms %.3g m%s\n", FIT_PROGRAM, k + 1,
			        start_count, retry ? "retry" : prefit ? "shot by shot" : k < given ? "staged" : "near the best", iterations,
			        sqrt(fit_sum_squares(ls.cached_f, pb->n_obs) / (double)pb->n_obs),
			        gsl_status == GSL_SUCCESS ? "" : gsl_status == GSL_EMAXITER ? " (iteration limit)" : " (stopped)");
		if (best < 0 || costs[k] < costs[best]) {
			best = k;
			out->iterations = (int)iterations;
			out->converged = gsl_status == GSL_SUCCESS;
			out->best_start = k;
		}
		out->starts = k + 1;
	}
	if (status == 0 && best >= 0 && pb->p <= FIT_PROFILE_MAX_PARAMS && !o->no_axis_starts) {
		int count = out->starts;
		if (axis_starts(&ls, starts, costs, &count, &best, &out->iterations, &out->converged) != 0)
			status = fail(&ls);
		if (best >= out->starts)
			out->best_start = best;
		out->starts = count;
	}
	if (status == 0) {
		memcpy(out->x, starts + (size_t)best * p, p * sizeof *out->x);
		out->dof = (long)pb->n_obs - pb->p;
		out->sigma_given = o->sigma > 0.0;
		out->sigma = out->sigma_given ? o->sigma : sqrt(costs[best] / (double)out->dof);
		fit_intervals_options io = {.sigma = out->sigma, .normal = out->sigma_given, .profile = o->profile};
		if (fit_intervals(&ls, &io, out, starts, costs, out->starts) != 0)
			status = fail(&ls);
	}
	fit_ls_free(&ls);
	free(starts);
	free(costs);
	free(origin);
	out->seconds = now_s() - started;
	if (status) {
		fit_solution_free(out);
		return status;
	}
	return 0;
}
