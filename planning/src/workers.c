// The search's worker threads: one simulation each, reused for every shot it runs; tasks are
// claimed from a shared counter and write only their own results, so what a search finds does
// not depend on which thread ran what.
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "aim_internal.h"

double aim_now(void) {
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int aim_workers_create(aim_search *s) {
	long threads = s->def->threads;
	if (threads <= 0) {
		long cpus = sysconf(_SC_NPROCESSORS_ONLN);
		threads = cpus > 0 ? cpus : 1;
	}
	s->threads = (int)threads;
	s->workers = calloc((size_t)threads, sizeof *s->workers);
	if (!s->workers)
		return -1;
	for (int k = 0; k < s->threads; ++k)
		if (!(s->workers[k].states = calloc((size_t)s->def->ball_count, sizeof *s->workers[k].states)))
			return -1;
	return 0;
}

void aim_workers_free(aim_search *s) {
	for (int k = 0; s->workers && k < s->threads; ++k) {
		pool_sim_destroy(s->workers[k].sim);
		free(s->workers[k].states);
	}
	free(s->workers);
	s->workers = NULL;
}

typedef struct parallel {
	aim_search *s;
	long count;
	atomic_long next;
	aim_task fn;
	void *ctx;
} parallel;

typedef struct parallel_arg {
	parallel *job;
	aim_worker *w;
} parallel_arg;

static void *run(void *arg) {
	parallel_arg *a = arg;
	for (long i; (i = atomic_fetch_add(&a->job->next, 1)) < a->job->count;)
		a->job->fn(a->job->s, a->w, i, a->job->ctx);
	return NULL;
}

void aim_parallel(aim_search *s, long count, aim_task fn, void *ctx) {
	parallel job = {.s = s, .count = count, .fn = fn, .ctx = ctx};
	atomic_init(&job.next, 0);
	long threads = s->threads < count ? s->threads : count;
	pthread_t *ids = threads > 1 ? calloc((size_t)threads, sizeof *ids) : NULL;
	parallel_arg *args = threads > 1 ? calloc((size_t)threads, sizeof *args) : NULL;
	long started = 0;
	for (long k = 1; ids && args && k < threads; ++k) {
		args[k] = (parallel_arg){&job, &s->workers[k]};
		if (pthread_create(&ids[k], NULL, run, &args[k]) != 0)
			break; // the others (and this thread) take the rest
		started = k;
	}
	parallel_arg here = {&job, &s->workers[0]};
	run(&here);
	for (long k = 1; k <= started; ++k)
		pthread_join(ids[k], NULL);
	free(ids);
	free(args);
}
