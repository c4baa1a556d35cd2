// Every sample of a study through pool-batch's shot (batch_shot.h), on several threads. Each
// worker owns one simulation, reused for every sample it claims; a sample's outcome is written
// to its own slot of the result arrays, so the arrays are the same whatever thread ran what.
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "study.h"

typedef struct run_ctx {
	const pool_scenario *layout;
	const pool_sim_def *def;
	const sens_noise *noise;
	const sens_samples *samples;
	const int *tracked;
	int tracked_count;
	sens_run *out;
	atomic_long next;      ///< next sample to claim
	atomic_long completed; ///< samples done, for the progress line
	atomic_bool out_of_memory;
} run_ctx;

typedef struct run_worker {
	run_ctx *ctx;
	pool_sim *sim;
	pool_ball_state *balls; ///< the sample's balls (noisy positions), when positions are noisy
	pool_ball_state *final;
} run_worker;

/// The pocket the ball of that id fell into during the shot, or POOL_POCKET_NONE.
static int8_t pocket_of(const pool_sim *sim, int32_t id) {
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	for (int k = 0; k < count; ++k) {
		if (events[k].type != POOL_EVENT_POCKET)
			continue;
		const pool_ball_state *after = pool_sim_event_states(sim, &events[k]);
		for (int j = 0; j < events[k].ball_count; ++j)
			if (after[j].id == id)
				return (int8_t)events[k].pocket;
	}
	return (int8_t)POOL_POCKET_NONE;
}

static void run_one(run_worker *w, long i) {
	run_ctx *c = w->ctx;
	sens_run *r = c->out;
	pool_scenario shot = *c->layout;
	shot.def = *c->def;
	int m = c->samples->position_count;
	if (m) { // this sample's ball positions
		memcpy(w->balls, c->layout->balls, (size_t)c->layout->ball_count * sizeof *w->balls);
		for (int k = 0; k < m; ++k) {
			pool_ball_state *b = &w->balls[c->noise->position_index[k]];
			b->pos.x = c->samples->positions[(i * m + k) * 2];
			b->pos.y = c->samples->positions[(i * m + k) * 2 + 1];
		}
		shot.balls = w->balls;
	}
	char error[400] = "";
	bool internal = false;
	int t = c->tracked_count;
	if (!pool_batch_shoot(&shot, &c->samples->strikes[i], &w->sim, w->final, error, sizeof error,
	                      &internal)) {
		r->stop[i] = internal ? -2 : -1;
		r->error[i] = strdup(error);
		if (!r->error[i])
			atomic_store(&c->out_of_memory, true);
		for (int k = 0; k < t; ++k) {
			r->state[i * t + k] = -1;
			r->pocket[i * t + k] = (int8_t)POOL_POCKET_NONE;
		}
		if (r->legal)
			r->legal[i] = r->outcome[i] = -1;
		return;
	}
	r->stop[i] = (int8_t)pool_sim_stop_reason(w->sim);
	pool_game_result game;
	if (r->legal) {
		// The layout's game judges the shot (the parser checked its balls; a judge that refuses
		// counts as not legal, with no outcome).
		const bool judged = pool_batch_judge(&shot, w->sim, &game);
		r->legal[i] = (int8_t)(judged && game.legal);
		r->outcome[i] = judged ? (int8_t)game.outcome : -1;
	}
	for (int k = 0; k < t; ++k) {
		const pool_ball_state *f = &w->final[c->tracked[k]];
		r->pos[(i * t + k) * 2] = f->pos.x;
		r->pos[(i * t + k) * 2 + 1] = f->pos.y;
		r->state[i * t + k] = (int8_t)f->motion;
		r->pocket[i * t + k] = f->motion == POOL_MOTION_POCKETED ? pocket_of(w->sim, f->id)
		                                                         : (int8_t)POOL_POCKET_NONE;
	}
}

static void *worker_main(void *arg) {
	run_worker *w = arg;
	run_ctx *c = w->ctx;
	for (;;) {
		long i = atomic_fetch_add(&c->next, 1);
		if (i >= c->samples->n)
			break;
		run_one(w, i);
		atomic_fetch_add(&c->completed, 1);
	}
	return NULL;
}

static double now_s(void) {
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sens_run_samples(const pool_scenario *layout, const pool_sim_def *def, const sens_noise *noise,
                     const sens_samples *samples, const int *tracked, int tracked_count,
                     long threads, bool progress, const char *label, sens_run *out) {
	memset(out, 0, sizeof *out);
	long n = samples->n;
	size_t nt = (size_t)n * (size_t)tracked_count;
	out->n = n;
	out->tracked_count = tracked_count;
	out->stop = calloc((size_t)n, sizeof *out->stop);
	out->error = calloc((size_t)n, sizeof *out->error);
	out->pos = calloc(nt * 2 + 1, sizeof *out->pos);
	out->state = calloc(nt + 1, sizeof *out->state);
	out->pocket = calloc(nt + 1, sizeof *out->pocket);
	bool game_ok = true;
	if (layout->has_game) {
		out->legal = calloc((size_t)n, sizeof *out->legal);
		out->outcome = calloc((size_t)n, sizeof *out->outcome);
		game_ok = out->legal && out->outcome;
	}
	if (threads > n)
		threads = n;
	if (threads < 1)
		threads = 1;
	run_worker *workers = calloc((size_t)threads, sizeof *workers);
	pthread_t *ids = calloc((size_t)threads, sizeof *ids);
	if (!out->stop || !out->error || !out->pos || !out->state || !out->pocket || !game_ok || !workers || !ids) {
		free(workers);
		free(ids);
		sens_run_free(out);
		return -1;
	}
	run_ctx ctx = {.layout = layout, .def = def, .noise = noise, .samples = samples,
	               .tracked = tracked, .tracked_count = tracked_count, .out = out};
	atomic_init(&ctx.next, 0);
	atomic_init(&ctx.completed, 0);
	atomic_init(&ctx.out_of_memory, false);
	int status = 0;
	long started = 0;
	for (long t = 0; t < threads && status == 0; ++t) {
		workers[t].ctx = &ctx;
		workers[t].final = calloc((size_t)layout->ball_count + 1, sizeof *workers[t].final);
		workers[t].balls = calloc((size_t)layout->ball_count + 1, sizeof *workers[t].balls);
		if (!workers[t].final || !workers[t].balls) {
			status = -1;
			break;
		}
		if (pthread_create(&ids[t], NULL, worker_main, &workers[t]) != 0) {
			if (t == 0) // no thread at all: run them here
				worker_main(&workers[t]);
			break;
		}
		started++;
	}
	if (status != 0) // stop the started workers at their next claim
		atomic_store(&ctx.next, n);
	bool shown = false;
	double start = now_s();
	while (progress && started > 0 && atomic_load(&ctx.completed) < n && status == 0) {
		struct timespec pause = {0, 250000000L};
		nanosleep(&pause, NULL);
		double t = now_s() - start;
		long done = atomic_load(&ctx.completed);
		if (t > 1.0) {
			fprintf(stderr, "\r%s: %s: %ld of %ld samples (%.0f%%), %.1f s", SENS_PROGRAM, label, done, n,
			        100.0 * (double)done / (double)n, t);
			shown = true;
		}
	}
	for (long t = 0; t < started; ++t)
		pthread_join(ids[t], NULL);
	if (shown)
		fprintf(stderr, "\r%s: %s: %ld of %ld samples (100%%), %.1f s\n", SENS_PROGRAM, label, n, n,
		        now_s() - start);
	for (long t = 0; t < threads; ++t) {
		pool_sim_destroy(workers[t].sim);
		free(workers[t].final);
		free(workers[t].balls);
	}
	free(workers);
	free(ids);
	if (status == 0 && (atomic_load(&ctx.out_of_memory) || atomic_load(&ctx.completed) < n))
		status = -1;
	if (status != 0) {
		sens_run_free(out);
		return -1;
	}
	for (long i = 0; i < n; ++i) {
		out->refused += out->stop[i] == -1;
		out->failed += out->stop[i] == -2;
	}
	return 0;
}

void sens_run_free(sens_run *r) {
	for (long i = 0; r->error && i < r->n; ++i)
		free(r->error[i]);
	free(r->error);
	free(r->stop);
	free(r->pos);
	free(r->state);
	free(r->pocket);
	free(r->legal);
	free(r->outcome);
	memset(r, 0, sizeof *r);
}
