// Simulated tracks against observed ones, and their derivatives.
//
// Residuals are matched in time: at each observed instant, the simulated position minus the
// observed one. A position at a fixed time is a continuous function of the parameters as long as
// the shot's collision sequence stays the same (a collision that comes earlier moves the balls
// continuously; a grazing hit starts from a zero impulse), so the least squares sees a smooth
// problem almost everywhere. What is not continuous is a change of the sequence itself (a ball
// that now hits a cushion instead of dropping in a pocket, the cue ball meeting another ball
// first). The Jacobian's differences therefore never straddle one: each side's collision
// sequence is compared with the current iterate's, and a side that changed it is not used.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "fit.h"

// Difference step, relative to each parameter's typical change (fit_param_info.scale). Positions
// are closed forms of the parameters between events, exact to rounding (1e-16 of a metre's
// worth), and event times come from root finders good to about 1e-12 s, so a step of 1e-5 of the
// scale keeps both the rounding (1e-16 / 1e-5) and the truncation (1e-10) errors of a central
// difference far below the 1e-3 m noise of measured tracks.
#define FIT_DIFF_STEP 1e-5
// A side that changed the collision sequence is retried with steps this much smaller, so many times.
#define FIT_DIFF_SHRINK 0.01
#define FIT_DIFF_TRIES 3
// s simulated beyond the horizon, so a shot cut there still reaches it when t0 moves a little.
#define FIT_HORIZON_MARGIN 0.05
// m per scale: a tether of each parameter to the point its minimisation started from. A
// parameter the tracks do not see yet (a side spin before anything is hit) leaves a column of
// zeros in the Jacobian, and the trust region's linear systems are then singular: its steps are
// rejected and the fit stalls where it started. The tether makes the system regular and costs
// (1e-6 m)^2 per scale of change, nothing against one track residual of 1e-3 m; its share of the
// covariance is as small (a parameter the tracks do see has J^T J above 1e2 per scale^2).
#define FIT_RIDGE 1e-6
// Weight of a penalty row per scale of violation: leaving the admissible range by one scale
// (e.g. 0.01 of friction) costs 1e6 m^2, more than any track residual can gain.
#define FIT_PENALTY_WEIGHT 1e3

// ---- parameter values -------------------------------------------------------------------------

void fit_penalty_rows(const fit_problem *pb, const double *x, double *rows) {
	double *c = malloc((size_t)pb->p * sizeof *c);
	if (!c) { // cannot happen in practice (p doubles); a zero penalty only loses the ranges' pull
		memset(rows, 0, (size_t)pb->p * sizeof *rows);
		return;
	}
	fit_clamp(pb, x, c);
	for (int j = 0; j < pb->p; ++j) {
		int shot, index;
		const fit_param_info *info = fit_param_of(pb, j, &shot, &index);
		rows[j] = FIT_PENALTY_WEIGHT * (x[j] - c[j]) / info->scale;
		if (pb->anchor)
			rows[j] += FIT_RIDGE * (x[j] - pb->anchor[j]) / info->scale;
	}
	free(c);
}

// ---- one shot ---------------------------------------------------------------------------------

/// FNV-1a over the words of the collision sequence.
static uint64_t mix(uint64_t h, int64_t word) {
	for (int k = 0; k < 8; ++k) {
		h ^= (uint64_t)((word >> (8 * k)) & 0xff);
		h *= 1099511628211ULL;
	}
	return h;
}

static uint64_t collision_signature(const pool_sim *sim) {
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	uint64_t h = 14695981039346656037ULL;
	for (int e = 0; e < count; ++e) {
		const pool_event *ev = &events[e];
		if (ev->type != POOL_EVENT_BALL_BALL && ev->type != POOL_EVENT_BALL_CUSHION &&
		    ev->type != POOL_EVENT_POCKET && ev->type != POOL_EVENT_OFF_TABLE && ev->type != POOL_EVENT_LINK_BEGIN)
			continue;
		h = mix(h, ev->type);
		h = mix(h, ev->rail);
		h = mix(h, ev->pocket);
		const pool_ball_state *after = pool_sim_event_states(sim, ev);
		for (int k = 0; k < ev->ball_count; ++k)
			h = mix(h, after[k].id);
	}
	return h;
}

pool_result fit_shot_residuals(const fit_problem *pb, int shot, const double *x, fit_worker *w, double *rows,
                               uint64_t *signature) {
	const fit_shot *sh = &pb->shots[shot];
	pool_scenario sc = sh->scenario;
	fit_table_values(pb, x, &sc.def.params);
	double v[FIT_SHOT_PARAMS];
	fit_shot_values(pb, x, shot, v);
	sc.has_strike = false;
	if (isfinite(pb->horizon) && pb->horizon - v[FIT_T0] + FIT_HORIZON_MARGIN < sc.def.max_time)
		sc.def.max_time = fmax(pb->horizon - v[FIT_T0] + FIT_HORIZON_MARGIN, FIT_HORIZON_MARGIN);
	pool_error err;
	pool_result r = pool_scenario_setup(&sc, &w->sim, &err);
	if (r != POOL_OK)
		return r;
	pool_strike strike = {v[FIT_SPEED], v[FIT_PHI], v[FIT_THETA], v[FIT_A], v[FIT_B]};
	r = pool_sim_strike(w->sim, sh->ball, &strike, &err);
	if (r == POOL_OK)
		r = pool_sim_run(w->sim);
	if (r != POOL_OK)
		return r;
	*signature = collision_signature(w->sim);
	const double end = pool_sim_end_time(w->sim);
	double at = NAN;
	for (long i = 0; i < sh->obs_count; ++i) {
		const fit_observation *o = &sh->obs[i];
		if (o->t > pb->horizon) { // beyond the horizon (observations are sorted by time)
			memset(rows + 2 * i, 0, 2 * (size_t)(sh->obs_count - i) * sizeof *rows);
			break;
		}
		double t = fmin(fmax(o->t - v[FIT_T0], 0.0), end); // before the strike the balls are where they start
		if (t != at) { // observations share instants: one evaluation per instant
			r = pool_sim_state_at(w->sim, t, w->states);
			if (r != POOL_OK)
				return r;
			at = t;
		}
		rows[2 * i] = w->states[o->ball].pos.x - o->x;
		rows[2 * i + 1] = w->states[o->ball].pos.y - o->y;
	}
	return POOL_OK;
}

// ---- workers ----------------------------------------------------------------------------------

int fit_workers_create(const fit_problem *pb, long count, fit_worker **out) {
	int balls = 1;
	for (int s = 0; s < pb->shot_count; ++s)
		if (pb->shots[s].scenario.ball_count > balls)
			balls = pb->shots[s].scenario.ball_count;
	fit_worker *w = calloc((size_t)count, sizeof *w);
	if (!w)
		return -1;
	for (long k = 0; k < count; ++k) {
		w[k].states = calloc((size_t)balls, sizeof *w[k].states);
		if (!w[k].states) {
			fit_workers_free(w, count);
			return -1;
		}
	}
	*out = w;
	return 0;
}

void fit_workers_free(fit_worker *w, long count) {
	for (long k = 0; w && k < count; ++k) {
		pool_sim_destroy(w[k].sim);
		free(w[k].states);
	}
	free(w);
}

/// Tasks 0 .. count - 1 run by fn on the workers' threads; each task writes only its own output.
typedef struct parallel {
	long count;
	atomic_long next;
	atomic_int failed; ///< the first failing pool_result (0 while none)
	void (*fn)(struct parallel *job, long task, fit_worker *w);
	void *ctx;
} parallel;

typedef struct parallel_arg {
	parallel *job;
	fit_worker *w;
} parallel_arg;

static void *parallel_main(void *arg) {
	parallel_arg *a = arg;
	for (long t; (t = atomic_fetch_add(&a->job->next, 1)) < a->job->count;)
		a->job->fn(a->job, t, a->w);
	return NULL;
}

static pool_result run_parallel(parallel *job, fit_worker *workers, long threads) {
	atomic_init(&job->next, 0);
	atomic_init(&job->failed, 0);
	if (threads > job->count)
		threads = job->count;
	if (threads < 1)
		threads = 1;
	pthread_t *ids = calloc((size_t)threads, sizeof *ids);
	parallel_arg *args = calloc((size_t)threads, sizeof *args);
	if (!ids || !args)
		threads = 1; // run everything here
	long started = 0;
	for (long k = 1; k < threads; ++k) {
		args[k] = (parallel_arg){job, &workers[k]};
		if (pthread_create(&ids[k], NULL, parallel_main, &args[k]) != 0)
			break;
		started = k;
	}
	parallel_arg here = {job, &workers[0]};
	parallel_main(&here);
	for (long k = 1; k <= started; ++k)
		pthread_join(ids[k], NULL);
	free(ids);
	free(args);
	return (pool_result)atomic_load(&job->failed);
}

static void record_failure(parallel *job, pool_result r) {
	int expected = 0;
	if (r != POOL_OK)
		atomic_compare_exchange_strong(&job->failed, &expected, (int)r);
}

// ---- all residuals ----------------------------------------------------------------------------

typedef struct residual_job {
	const fit_problem *pb;
	const double *x;
	double *f;
	uint64_t *signatures;
	const size_t *offset; ///< first row of each shot
} residual_job;

static void residual_task(parallel *job, long shot, fit_worker *w) {
	residual_job *c = job->ctx;
	record_failure(job, fit_shot_residuals(c->pb, (int)shot, c->x, w, c->f + c->offset[shot], &c->signatures[shot]));
}

static size_t *row_offsets(const fit_problem *pb) {
	size_t *offset = malloc((size_t)pb->shot_count * sizeof *offset);
	if (offset)
		for (int s = 0, row = 0; s < pb->shot_count; row += 2 * (int)pb->shots[s].obs_count, ++s)
			offset[s] = (size_t)row;
	return offset;
}

pool_result fit_residuals(const fit_problem *pb, const double *x, fit_worker *workers, double *f,
                          uint64_t *signatures) {
	size_t *offset = row_offsets(pb);
	if (!offset)
		return POOL_ERR_OUT_OF_MEMORY;
	residual_job c = {pb, x, f, signatures, offset};
	parallel job = {.count = pb->shot_count, .fn = residual_task, .ctx = &c};
	pool_result r = run_parallel(&job, workers, pb->threads);
	fit_penalty_rows(pb, x, f + pb->n_obs);
	free(offset);
	return r;
}

// ---- the Jacobian -----------------------------------------------------------------------------

int fit_jacobian_width(const fit_problem *pb) { return pb->table_free + pb->shot_free; }

int fit_jacobian_column(const fit_problem *pb, int j) {
	return j < pb->table_free ? j : pb->table_free + (j - pb->table_free) % pb->shot_free;
}

/// One task: parameter j on shot s.
typedef struct jacobian_job {
	const fit_problem *pb;
	const double *x;
	const uint64_t *signatures;
	fit_jacobian_blocks *J;
	const size_t *offset;
	const double *base;       ///< the residual rows at x (n)
	int *task_param, *task_shot;
	double **scratch;         ///< per worker: x (p), rows + and - (2 * the largest shot's rows)
	fit_worker *workers;
} jacobian_job;

static void jacobian_task(parallel *job, long task, fit_worker *w) {
	jacobian_job *c = job->ctx;
	const fit_problem *pb = c->pb;
	int j = c->task_param[task], s = c->task_shot[task];
	int shot, index;
	const fit_param_info *info = fit_param_of(pb, j, &shot, &index);
	double *xs = c->scratch[w - c->workers];
	double *plus = xs + pb->p, *minus = plus + 2 * pb->shots[s].obs_count;
	size_t rows = 2 * (size_t)pb->shots[s].obs_count;
	const double *base = c->base + c->offset[s];
	const size_t width = (size_t)fit_jacobian_width(pb);
	double *column = c->J->rows + c->offset[s] * width + (size_t)fit_jacobian_column(pb, j);
	memcpy(xs, c->x, (size_t)pb->p * sizeof *xs);
	// (Far from zero the step grows with the value, so it stays far above the value's rounding.)
	double h = FIT_DIFF_STEP * fmax(info->scale, 1e-3 * fabs(c->x[j]));
	for (int attempt = 0; attempt < FIT_DIFF_TRIES; ++attempt, h *= FIT_DIFF_SHRINK) {
		uint64_t sp = 0, sm = 0;
		xs[j] = c->x[j] + h;
		pool_result r = fit_shot_residuals(pb, s, xs, w, plus, &sp);
		xs[j] = c->x[j] - h;
		if (r == POOL_OK)
			r = fit_shot_residuals(pb, s, xs, w, minus, &sm);
		if (r != POOL_OK) {
			record_failure(job, r);
			return;
		}
		bool up = sp == c->signatures[s], down = sm == c->signatures[s];
		bool last = attempt == FIT_DIFF_TRIES - 1;
		if (!up && !down && !last)
			continue; // both sides cross an event change: closer
		for (size_t i = 0; i < rows; ++i) {
			double d = up && down ? (plus[i] - minus[i]) / (2 * h)
			         : up         ? (plus[i] - base[i]) / h
			         : down       ? (base[i] - minus[i]) / h
			                      : (plus[i] - minus[i]) / (2 * h);
			column[i * width] = d;
		}
		return;
	}
}

pool_result fit_jacobian(const fit_problem *pb, const double *x, const double *base, const uint64_t *signatures,
                         fit_worker *workers, fit_jacobian_blocks *J) {
	const size_t p = (size_t)pb->p;
	memset(J->rows, 0, pb->n_obs * (size_t)fit_jacobian_width(pb) * sizeof *J->rows);
	memset(J->penalty, 0, p * p * sizeof *J->penalty);
	size_t *offset = row_offsets(pb);
	// Each shot's rows move only with the table's parameters and the shot's own: a task is one
	// parameter on one shot, so a Jacobian costs 2 (table_free + shot_free) simulations per shot.
	long tasks = (long)pb->shot_count * fit_jacobian_width(pb);
	int *task_param = malloc((size_t)tasks * sizeof *task_param);
	int *task_shot = malloc((size_t)tasks * sizeof *task_shot);
	long most = 0;
	for (int s = 0; s < pb->shot_count; ++s)
		most = pb->shots[s].obs_count > most ? pb->shots[s].obs_count : most;
	double **scratch = calloc((size_t)pb->threads, sizeof *scratch);
	pool_result r = offset && task_param && task_shot && scratch ? POOL_OK : POOL_ERR_OUT_OF_MEMORY;
	for (long k = 0; r == POOL_OK && k < pb->threads; ++k)
		if (!(scratch[k] = malloc((p + 4 * (size_t)most) * sizeof **scratch)))
			r = POOL_ERR_OUT_OF_MEMORY;
	if (r == POOL_OK) {
		long t = 0;
		for (int j = 0; j < pb->p; ++j) {
			int shot, index;
			fit_param_of(pb, j, &shot, &index);
			for (int s = 0; s < pb->shot_count; ++s)
				if (shot < 0 || shot == s) {
					task_param[t] = j;
					task_shot[t++] = s;
				}
		}
		jacobian_job c = {pb, x, signatures, J, offset, base, task_param, task_shot, scratch, workers};
		parallel job = {.count = tasks, .fn = jacobian_task, .ctx = &c};
		r = run_parallel(&job, workers, pb->threads);
	}
	if (r == POOL_OK) { // the penalty rows, by the same differences (no simulation)
		double *xs = malloc(p * sizeof *xs), *plus = malloc(p * sizeof *plus), *minus = malloc(p * sizeof *minus);
		if (xs && plus && minus) {
			memcpy(xs, x, p * sizeof *xs);
			for (size_t j = 0; j < p; ++j) {
				int shot, index;
				double h = FIT_DIFF_STEP * fmax(fit_param_of(pb, (int)j, &shot, &index)->scale, 1e-3 * fabs(x[j]));
				xs[j] = x[j] + h;
				fit_penalty_rows(pb, xs, plus);
				xs[j] = x[j] - h;
				fit_penalty_rows(pb, xs, minus);
				xs[j] = x[j];
				for (size_t i = 0; i < p; ++i)
					J->penalty[i * p + j] = (plus[i] - minus[i]) / (2 * h);
			}
		} else {
			r = POOL_ERR_OUT_OF_MEMORY;
		}
		free(xs);
		free(plus);
		free(minus);
	}
	for (long k = 0; scratch && k < pb->threads; ++k)
		free(scratch[k]);
	free(scratch);
	free(task_param);
	free(task_shot);
	free(offset);
	return r;
}
