// pool-bench-models: what the models cost. (1) One ball-cushion impact by each law (Petit's
// pool_collide, Mathavan 2010's pool_cushion_mathavan), on a fixed set of random rolling/spinning
// impacts, timed in batches: median and minimum per impact. (2) Whole breaks (frozen rack and
// 0.1 mm gap, 8 m/s) under "thesis", with each measured law added, and with the defaults: median
// and minimum per shot, and the ratio to thesis.
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/pool.h>

#include "bench_util.h"
#include "collision.h"
#include "cushion_mathavan.h"

enum { IMPACTS = 256, BATCHES = 200 };

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double urand(void) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

static volatile double sink; // keeps the results alive

// Median and minimum per impact over BATCHES batches of IMPACTS impacts.
static void time_law(const char *name, int mathavan, const pool_params *p, const pool_ball_state *in, pool_vec3 n) {
	static double t[BATCHES];
	for (int b = 0; b < BATCHES; ++b) {
		const double t0 = pool_bench_now_s();
		double acc = 0.0;
		for (int i = 0; i < IMPACTS; ++i) {
			pool_ball_state s = in[i];
			if (mathavan)
				pool_cushion_mathavan(&s, p, n, POOL_MATHAVAN_TOLERANCE);
			else
				pool_collide(&s, p->ball_radius, p->ball_mass, NULL, p->ball_radius, 0.0, n, p->e_cushion, p->mu_cushion);
			acc += s.vel.y;
		}
		t[b] = (pool_bench_now_s() - t0) / IMPACTS;
		sink = acc;
	}
	const pool_bench_summary s = pool_bench_summarise(t, BATCHES);
	printf("cushion impact  %-34s median %8.3f us  min %8.3f us\n", name, 1e6 * s.median, 1e6 * s.min);
}

static int break_shot(pool_sim *sim, const pool_sim_def *def, double gap) {
	pool_ball_state balls[16];
	const int n = pool_rack(POOL_RACK_8BALL, &def->table, &def->params, gap, balls, 16);
	if (pool_sim_reset(sim, def, NULL) != POOL_OK)
		return -1;
	for (int i = 0; i < n; ++i)
		if (pool_sim_add_ball(sim, &balls[i], NULL) != POOL_OK)
			return -1;
	const pool_strike strike = pool_break_strike(8.0);
	return pool_sim_strike(sim, 0, &strike, NULL) == POOL_OK && pool_sim_run(sim) == POOL_OK ? 0 : -1;
}

static double time_break(const char *name, const pool_sim_def *def, double gap, int runs, double baseline) {
	pool_sim *sim;
	if (pool_sim_create(def, &sim, NULL) != POOL_OK)
		return -1.0;
	double *t = malloc(sizeof *t * (size_t)runs);
	if (!t)
		return -1.0;
	int events = 0, cushions = 0;
	for (int r = 0; r < runs + 20; ++r) { // 20 warm-up runs
		const double t0 = pool_bench_now_s();
		if (break_shot(sim, def, gap)) {
			fprintf(stderr, "pool-bench-models: %s: the break failed\n", name);
			return -1.0;
		}
		if (r >= 20)
			t[r - 20] = pool_bench_now_s() - t0;
	}
	const pool_event *ev = pool_sim_events(sim, &events);
	for (int e = 0; e < events; ++e)
		cushions += ev[e].type == POOL_EVENT_BALL_CUSHION;
	const pool_bench_summary s = pool_bench_summarise(t, (size_t)runs);
	printf("break gap %-6.4g %-26s median %8.1f us  min %8.1f us  events %4d (cushion %3d)", gap * 1e3, name,
	       1e6 * s.median, 1e6 * s.min, events, cushions);
	if (baseline > 0.0)
		printf("  x%.2f of thesis", s.median / baseline);
	printf("\n");
	free(t);
	pool_sim_destroy(sim);
	return s.median;
}

int main(int argc, char **argv) {
	int runs = 1000;
	for (int i = 1; i < argc; ++i) {
		if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
			printf("usage: pool-bench-models [--runs N]\n"
			       "Times one ball-cushion impact by Petit's law and by mathavan2010 (median and\n"
			       "minimum per impact over %d batches of %d random impacts), then the 8 m/s break\n"
			       "(frozen and 0.1 mm gap) under thesis, with each measured law, with the default\n"
			       "models, N runs each (default 1000): median and minimum per shot, and the ratio\n"
			       "to thesis.\n",
			       BATCHES, IMPACTS);
			return 0;
		}
		if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
			runs = atoi(argv[++i]);
			if (runs <= 0) {
				fprintf(stderr, "pool-bench-models: --runs: must be > 0\n");
				return 2;
			}
		} else {
			fprintf(stderr, "pool-bench-models: unknown argument '%s' (see --help)\n", argv[i]);
			return 2;
		}
	}
	char model[256];
	printf("machine: %s, %ld cores online, libpool %d\n", pool_bench_cpu_model(model, sizeof model),
	       pool_bench_cpus_online(), POOL_VERSION);
	const pool_sim_def def = pool_default_sim_def();
	const pool_params *p = &def.params;
	const double R = p->ball_radius, sin_t = (def.table.cushion_height - R) / R;
	const pool_vec3 n = {0.0, -sqrt(1.0 - sin_t * sin_t), -sin_t}; // the north rail's nose normal
	static pool_ball_state in[IMPACTS];
	for (int i = 0; i < IMPACTS; ++i) { // 0.2-4 m/s, 0-80 deg in, top/back spin and side
		const double v = 0.2 + 3.8 * urand(), a = (urand() * 160.0 - 80.0) * 3.14159265358979 / 180.0;
		memset(&in[i], 0, sizeof in[i]);
		in[i].pos = (pool_vec3){1.0, def.table.width - 0.03, R};
		in[i].vel = (pool_vec3){v * sin(a), v * cos(a), 0.0};
		const double top = 2.0 * urand() - 1.0;
		in[i].omega = (pool_vec3){-top * in[i].vel.y / R, top * in[i].vel.x / R, (4.0 * urand() - 2.0) * v / R};
	}
	time_law("petit (pool_collide)", 0, p, in, n);
	char name[64];
	snprintf(name, sizeof name, "mathavan2010 (tolerance %g)", POOL_MATHAVAN_TOLERANCE);
	time_law(name, 1, p, in, n);
	for (int g = 0; g < 2; ++g) {
		const double gap = g ? 1e-4 : 0.0;
		pool_sim_def d = def;
		d.models = pool_thesis_models();
		const double base = time_break("thesis", &d, gap, runs, 0.0);
		d.models.cushion = POOL_CUSHION_MATHAVAN2010;
		time_break("thesis + mathavan2010", &d, gap, runs, base);
		d.models = pool_thesis_models();
		d.models.ball_ball_friction = POOL_BALL_FRICTION_ALCIATORE;
		time_break("thesis + alciatore", &d, gap, runs, base);
		time_break("default models", &def, gap, runs, base);
		d = def;
		d.models.squirt = POOL_SQUIRT_ENDMASS;
		time_break("default + endmass", &d, gap, runs, base);
	}
	return 0;
}
