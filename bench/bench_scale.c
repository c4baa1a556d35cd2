// pool-bench-scale: libpool's cost per event against the number of balls, with the schedule's
// all-pairs search and with the broadphase grid, on the scale scenes (tools/common/scale_scene.h:
// a gas of balls, a quarter of them rolling, or a break, 16 balls per standard table area).
// Runs alternate between the two searches, and each pair of runs must give the same events bit
// for bit (a hash of every event and state). Prints median and minimum time per shot and per
// event, events per shot, and the machine. Instructions per event: run it under
//   valgrind --tool=callgrind --toggle-collect=pool_sim_run pool-bench-scale --balls N --runs 1 --mode M
// and divide the collected instructions by the events printed.
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/pool.h>

#include "bench_util.h"
#include "scale_scene.h"
#include "schedule.h"
#include "world.h"

static uint64_t hash_bytes(uint64_t h, const void *p, size_t n) {
	const unsigned char *c = p;
	for (size_t i = 0; i < n; ++i)
		h = (h ^ c[i]) * 0x100000001B3ull;
	return h;
}

// Every event (time, kind, rail, pocket, balls) and the states after it, and the final states.
static uint64_t hash_shot(const pool_sim *sim) {
	uint64_t h = 0xCBF29CE484222325ull;
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	for (int k = 0; k < count; ++k) {
		const pool_event *e = &events[k];
		h = hash_bytes(h, &e->time, sizeof e->time);
		const int fields[4] = {(int)e->type, (int)e->rail, (int)e->pocket, e->ball_count};
		h = hash_bytes(h, fields, sizeof fields);
		const pool_ball_state *s = pool_sim_event_states(sim, e);
		for (int b = 0; b < e->ball_count; ++b)
			h = hash_bytes(h, &s[b], sizeof s[b]);
	}
	const pool_ball_state *final = pool_sim_balls(sim);
	for (int b = 0; b < pool_sim_ball_count(sim); ++b)
		h = hash_bytes(h, &final[b], sizeof final[b]);
	return h;
}

typedef struct scene {
	pool_sim_def def;
	pool_ball_state *balls;
	int n;
	bool has_strike;
	pool_strike strike;
} scene;

// One shot with the given search; its time (s), events and hash.
static int run(pool_sim *sim, const scene *s, pool_broadphase_mode mode, double *seconds, int *events, uint64_t *hash) {
	if (pool_sim_reset(sim, &s->def, NULL) != POOL_OK)
		return -1;
	pool_schedule_set_broadphase(sim, mode);
	for (int i = 0; i < s->n; ++i)
		if (pool_sim_add_ball(sim, &s->balls[i], NULL) != POOL_OK)
			return -1;
	if (s->has_strike && pool_sim_strike(sim, 0, &s->strike, NULL) != POOL_OK)
		return -1;
	const double t0 = pool_bench_now_s();
	const pool_result r = pool_sim_run(sim);
	*seconds = pool_bench_now_s() - t0;
	if (r != POOL_OK)
		return -1;
	pool_sim_events(sim, events);
	*hash = hash_shot(sim);
	return 0;
}

static int parse_list(const char *text, int *out, int max) {
	int count = 0;
	for (const char *p = text; *p && count < max;) {
		char *end;
		const long v = strtol(p, &end, 10);
		if (end == p || v < 2 || v > POOL_SCALE_MAX_BALLS)
			return -1;
		out[count++] = (int)v;
		p = *end == ',' ? end + 1 : end;
		if (*end && *end != ',')
			return -1;
	}
	return count;
}

int main(int argc, char **argv) {
	int sizes[16] = {16, 64, 256, 1024, 4096}, n_sizes = 5, runs = 5;
	const char *family = "gas", *modes = "both", *models = "default";
	double window = 2.0;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			printf("usage: pool-bench-scale [--balls 16,64,256,1024,4096] [--family gas|break] [--runs N]\n"
			       "                        [--time S] [--mode both|all-pairs|grid] [--models default|thesis]\n"
			       "Times whole shots of the scale scenes (tools/common/scale_scene.h) with the schedule's\n"
			       "all-pairs search and with the broadphase grid, alternately, and checks that both give the\n"
			       "same events bit for bit. Prints median and minimum time per shot and per event, events\n"
			       "per shot, and the machine. Defaults: gas, 5 runs of each search, 2 s of simulated time,\n"
			       "the library's default models (thesis: the 2012 work's, as pool-compare --scale runs).\n");
			return 0;
		}
		if (!v) {
			fprintf(stderr, "pool-bench-scale: %s: missing value or unknown argument (see --help)\n", a);
			return 2;
		}
		if (!strcmp(a, "--balls")) {
			n_sizes = parse_list(v, sizes, 16);
			if (n_sizes <= 0) {
				fprintf(stderr, "pool-bench-scale: --balls: ball counts in [2, %d], comma-separated\n", POOL_SCALE_MAX_BALLS);
				return 2;
			}
		} else if (!strcmp(a, "--family")) {
			family = v;
		} else if (!strcmp(a, "--runs")) {
			runs = atoi(v);
			if (runs <= 0) {
				fprintf(stderr, "pool-bench-scale: --runs: must be > 0\n");
				return 2;
			}
		} else if (!strcmp(a, "--time")) {
			window = atof(v);
			if (!(window > 0.0)) {
				fprintf(stderr, "pool-bench-scale: --time: must be > 0 s\n");
				return 2;
			}
		} else if (!strcmp(a, "--mode")) {
			modes = v;
			if (strcmp(v, "both") && strcmp(v, "all-pairs") && strcmp(v, "grid")) {
				fprintf(stderr, "pool-bench-scale: --mode: both, all-pairs or grid\n");
				return 2;
			}
		} else if (!strcmp(a, "--models")) {
			models = v;
			pool_models m;
			if (pool_models_preset(v, &m) != POOL_OK) {
				fprintf(stderr, "pool-bench-scale: --models: unknown model set '%s' (default, thesis)\n", v);
				return 2;
			}
		} else {
			fprintf(stderr, "pool-bench-scale: unknown argument '%s' (see --help)\n", a);
			return 2;
		}
		++i;
	}
	char model[256];
	printf("machine: %s, %ld cores online; family %s, models %s, %g s simulated, %d runs per search\n",
	       pool_bench_cpu_model(model, sizeof model), pool_bench_cpus_online(), family, models, window, runs);
	const pool_broadphase_mode list[2] = {POOL_BROADPHASE_ALL_PAIRS, POOL_BROADPHASE_GRID};
	const int first = !strcmp(modes, "grid"), last = !strcmp(modes, "all-pairs") ? 0 : 1;
	pool_sim *sim = NULL;
	int status = 0;
	for (int k = 0; k < n_sizes && !status; ++k) {
		scene s;
		s.n = sizes[k];
		s.def = pool_default_sim_def();
		pool_models_preset(models, &s.def.models);
		s.def.max_time = window;
		s.balls = malloc(sizeof *s.balls * (size_t)s.n);
		char err[256];
		if (!s.balls || pool_scale_scene(family, s.n, &s.def.params, &s.def.table, s.balls, &s.has_strike, &s.strike, err,
		                                 sizeof err)) {
			fprintf(stderr, "pool-bench-scale: %s\n", s.balls ? err : "out of memory");
			free(s.balls);
			return 2;
		}
		if (!sim && pool_sim_create(&s.def, &sim, NULL) != POOL_OK)
			return 1;
		double *t[2] = {malloc(sizeof(double) * (size_t)runs), malloc(sizeof(double) * (size_t)runs)};
		int events = 0;
		uint64_t hash[2] = {0, 0};
		for (int r = 0; r < runs && !status; ++r)
			for (int m = first; m <= last; ++m) {
				int ev;
				uint64_t h;
				if (run(sim, &s, list[m], &t[m][r], &ev, &h)) {
					fprintf(stderr, "pool-bench-scale: %s %d: the shot failed\n", family, s.n);
					status = 1;
					break;
				}
				if ((r > 0 || m > first) && (h != hash[first] || ev != events)) {
					fprintf(stderr, "pool-bench-scale: %s %d: the %s search gave other events (%d against %d)\n", family,
					        s.n, m ? "grid" : "all-pairs", ev, events);
					status = 1;
				}
				hash[m] = h;
				events = ev;
			}
		for (int m = first; m <= last && !status; ++m) {
			const pool_bench_summary sum = pool_bench_summarise(t[m], (size_t)runs);
			printf("%-6s %5d balls  %-9s  events/shot %7d  shot median %10.3f ms  min %10.3f ms  per event median "
			       "%7.3f us  min %7.3f us\n",
			       family, s.n, m ? "grid" : "all-pairs", events, 1e3 * sum.median, 1e3 * sum.min,
			       1e6 * sum.median / events, 1e6 * sum.min / events);
		}
		if (first == 0 && last == 1 && !status)
			printf("%-6s %5d balls  same events bit for bit with both searches (hash %016llx)\n", family, s.n,
			       (unsigned long long)hash[0]);
		fflush(stdout);
		free(t[0]);
		free(t[1]);
		free(s.balls);
	}
	pool_sim_destroy(sim);
	return status;
}
