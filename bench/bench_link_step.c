// pool-bench-link-step: how long one LINK step (libpool/src/link_step.c: contacts, the LCP, Lemke)
// takes for clusters of 2, 3 and 16 balls. Each scene is advanced step after step as the world
// does (positions += dt v), one reused workspace; a run times a block of steps, and the time per
// step is reported as median and minimum over the runs, with the LCP's size, Lemke's pivots per
// step and the share of warm-started steps, and the machine.
//   push-2     a cue ball with follow pushing a frozen ball
//   pyramid-3  a ball resting on two touching balls (airborne mode, mu_ball 0.5 so it stands)
//   rack-16    a frozen 15-ball rack pushed by a rolling cue ball frozen to its apex
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/pool.h>

#include "bench_util.h"
#include "link_step.h"

static void *heap_alloc(size_t size, void *context) {
	(void)context;
	return malloc(size);
}
static void heap_free(void *memory, void *context) {
	(void)context;
	free(memory);
}

typedef struct scene {
	const char *name;
	pool_sim_def def;
	pool_ball_state balls[16];
	int n;
	int steps_per_run;
} scene;

static pool_ball_state ball(double x, double y, double z, double vx, double wy) {
	pool_ball_state b;
	memset(&b, 0, sizeof b);
	b.motion = POOL_MOTION_LINKED;
	b.pos.x = x;
	b.pos.y = y;
	b.pos.z = z;
	b.vel.x = vx;
	b.omega.y = wy;
	return b;
}

static void make_scenes(scene *s) {
	pool_sim_def def = pool_default_sim_def();
	def.airborne = true;
	const double R = def.params.ball_radius;
	memset(s, 0, 3 * sizeof *s);

	s[0].name = "push-2";
	s[0].def = def;
	s[0].balls[0] = ball(1.0, 0.6, R, 0.8, 2.0 * 0.8 / R);
	s[0].balls[1] = ball(1.0 + 2.0 * R, 0.6, R, 0.0, 0.0);
	s[0].n = 2;
	s[0].steps_per_run = 200;

	s[1].name = "pyramid-3";
	s[1].def = def;
	s[1].def.params.mu_ball = 0.5;
	s[1].balls[0] = ball(1.0, 0.6, R, 0.0, 0.0);
	s[1].balls[1] = ball(1.0 + 2.0 * R, 0.6, R, 0.0, 0.0);
	s[1].balls[2] = ball(1.0 + R, 0.6, R + sqrt(3.0) * R, 0.0, 0.0);
	s[1].n = 3;
	s[1].steps_per_run = 200;

	s[2].name = "rack-16";
	s[2].def = def;
	const double x0 = 1.8, y0 = 0.635;
	int k = 0;
	s[2].balls[k++] = ball(x0 - 2.0 * R, y0, R, 1.0, 1.0 / R);
	for (int row = 0; row < 5; ++row)
		for (int j = 0; j <= row; ++j)
			s[2].balls[k++] = ball(x0 + row * sqrt(3.0) * R, y0 + (j - 0.5 * row) * 2.0 * R, R, 0.0, 0.0);
	s[2].n = k;
	s[2].steps_per_run = 20;
	// Distinct ids, as in a simulation: the steps keep their warm starts by ball id.
	for (int i = 0; i < 3; ++i)
		for (int b = 0; b < s[i].n; ++b)
			s[i].balls[b].id = b;
}

// Runs `runs` blocks of steps on a copy of the scene (restarted each run); prints the summary.
static int measure(const scene *sc, int runs, double dt, double *t) {
	const pool_allocator heap = {heap_alloc, heap_free, NULL};
	pool_link_workspace ws = {0};
	long pivots = 0, warm = 0, steps = 0;
	int lcp = 0, contacts = 0;
	for (int r = 0; r < runs; ++r) {
		pool_ball_state s[16];
		memcpy(s, sc->balls, sizeof s);
		const double t0 = pool_bench_now_s();
		for (int i = 0; i < sc->steps_per_run; ++i) {
			pool_link_step_stats st;
			pool_result res = pool_link_step(&sc->def, s, sc->n, dt, &ws, &heap, &st);
			if (res != POOL_OK) {
				fprintf(stderr, "pool-bench-link-step: %s: step %d: %s\n", sc->name, i, pool_result_str(res));
				pool_link_workspace_free(&ws, &heap);
				return -1;
			}
			for (int k = 0; k < sc->n; ++k) {
				s[k].pos.x += dt * s[k].vel.x;
				s[k].pos.y += dt * s[k].vel.y;
				s[k].pos.z += dt * s[k].vel.z;
			}
			pivots += st.pivots;
			warm += st.warm;
			++steps;
			if (st.lcp_size > lcp) {
				lcp = st.lcp_size;
				contacts = st.contacts;
			}
		}
		t[r] = (pool_bench_now_s() - t0) / sc->steps_per_run;
	}
	pool_link_workspace_free(&ws, &heap);
	pool_bench_summary sum = pool_bench_summarise(t, (size_t)runs);
	printf("%-10s balls %2d  contacts %3d  LCP %4d  pivots/step %7.1f  warm %5.1f %%  median %10.1f us  min %10.1f us\n",
	       sc->name, sc->n, contacts, lcp, (double)pivots / (double)steps, 100.0 * (double)warm / (double)steps,
	       1e6 * sum.median, 1e6 * sum.min);
	fflush(stdout);
	return 0;
}

int main(int argc, char **argv) {
	int runs = 15;
	double dt = 1e-3;
	for (int i = 1; i < argc; ++i) {
		if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
			printf("usage: pool-bench-link-step [--runs N] [--dt S]\n"
			       "Times one LINK step (contacts, LCP, Lemke) on three clusters:\n"
			       "  push-2     a cue ball with follow pushing a frozen ball (200 steps a run)\n"
			       "  pyramid-3  a ball resting on two touching balls (200 steps a run)\n"
			       "  rack-16    a frozen 15-ball rack pushed by a cue ball frozen to it (20 steps a run)\n"
			       "Prints median and minimum time per step over N runs (default 15) of dt (default\n"
			       "1e-3 s) steps, the LCP size, pivots per step, warm-start share, and the machine.\n");
			return 0;
		}
		if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
			runs = atoi(argv[++i]);
			if (runs <= 0) {
				fprintf(stderr, "pool-bench-link-step: --runs: must be > 0\n");
				return 2;
			}
		} else if (strcmp(argv[i], "--dt") == 0 && i + 1 < argc) {
			dt = atof(argv[++i]);
			if (!(dt > 0.0) || !(dt <= 0.1)) {
				fprintf(stderr, "pool-bench-link-step: --dt: must be in (0, 0.1] s\n");
				return 2;
			}
		} else {
			fprintf(stderr, "pool-bench-link-step: unknown argument '%s' (see --help)\n", argv[i]);
			return 2;
		}
	}
	char model[256];
	printf("machine: %s, %ld cores online, libpool %d; dt %g s, %d runs\n", pool_bench_cpu_model(model, sizeof model),
	       pool_bench_cpus_online(), POOL_VERSION, dt, runs);
	scene scenes[3];
	make_scenes(scenes);
	double *t = malloc(sizeof(double) * (size_t)runs);
	if (!t)
		return 1;
	int failed = 0;
	for (int i = 0; i < 3; ++i)
		failed |= measure(&scenes[i], runs, dt, t) != 0;
	free(t);
	return failed ? 1 : 0;
}
