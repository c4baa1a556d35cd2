// pool-bench-models: what the models cost. (1) One ball-cushion impact by each law (Petit's
// pool_collide, Mathavan 2010's pool_cushion_mathavan, and the fixed-step reference it is judged
// by at its old 128 steps), on a fixed set of random spinning impacts and one of rolling balls
// without side, and Mathavan's on rolling balls at single incidences (0, 10, 20, 30, 55, 80
// degrees), timed in batches: median and minimum per impact. (2) Whole breaks (frozen rack and
// 0.1 mm gap, 8 m/s) under "thesis", with each measured law added, and with the defaults: median
// and minimum per shot, and the ratio to thesis. --accuracy N instead: libpool's Mathavan
// integration against the reference at 8,192 and 65,536 steps over N random impacts (0.1-8 m/s,
// any incidence, spin and side).
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/pool.h>

#include "bench_util.h"
#include "collision.h"
#include "cushion_mathavan.h"
#include "mathavan_reference.h"
#include "vec3.h"

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
// law: 0 Petit, 1 libpool's Mathavan, 2 the reference in 128 steps.
static void time_law(const char *set, const char *name, int law, const pool_params *p, const pool_ball_state *in,
                     pool_vec3 n) {
	static double t[BATCHES];
	for (int b = 0; b < BATCHES; ++b) {
		const double t0 = pool_bench_now_s();
		double acc = 0.0;
		for (int i = 0; i < IMPACTS; ++i) {
			pool_ball_state s = in[i];
			if (law == 1)
				pool_cushion_mathavan(&s, p, n, POOL_MATHAVAN_TOLERANCE);
			else if (law == 2)
				pool_mathavan_reference(&s, p, n, 128);
			else
				pool_collide(&s, p->ball_radius, p->ball_mass, NULL, p->ball_radius, 0.0, n, p->e_cushion, p->mu_cushion);
			acc += s.vel.y;
		}
		t[b] = (pool_bench_now_s() - t0) / IMPACTS;
		sink = acc;
	}
	const pool_bench_summary s = pool_bench_summarise(t, BATCHES);
	printf("cushion impact  %-8s %-34s median %8.3f us  min %8.3f us\n", set, name, 1e6 * s.median, 1e6 * s.min);
}

static int compare_doubles(const void *a, const void *b) {
	const double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static void print_quantiles(const char *what, double *d, int n) {
	qsort(d, (size_t)n, sizeof d[0], compare_doubles);
	printf("%-52s median %9.3g  p90 %9.3g  p99 %9.3g  worst %9.3g\n", what, d[n / 2], d[n * 9 / 10], d[n * 99 / 100],
	       d[n - 1]);
}

// N random impacts as test_model_fidelity draws them (pool_mathavan_random_impact), on the default
// table and parameters.
static int accuracy(int impacts) {
	const pool_params p = pool_default_params();
	const double R = p.ball_radius, sin_t = (0.03629 - R) / R;
	const pool_vec3 n = pool_v3(0.0, -sqrt(1.0 - sin_t * sin_t), -sin_t);
	double *d[4];
	for (int k = 0; k < 4; ++k)
		if (!(d[k] = malloc(sizeof(double) * (size_t)impacts)))
			return 1;
	uint64_t seed = 0x9E3779B97F4A7C15ull;
	for (int i = 0; i < impacts; ++i) {
		const pool_ball_state b = pool_mathavan_random_impact(&seed, R);
		pool_ball_state ours = b, old = b, ref = b, fine = b;
		if (pool_cushion_mathavan(&ours, &p, n, POOL_MATHAVAN_TOLERANCE) != POOL_MATHAVAN_RESOLVED ||
		    pool_mathavan_reference(&old, &p, n, 128) != POOL_MATHAVAN_RESOLVED ||
		    pool_mathavan_reference(&ref, &p, n, 8192) != POOL_MATHAVAN_RESOLVED ||
		    pool_mathavan_reference(&fine, &p, n, 65536) != POOL_MATHAVAN_RESOLVED) {
			fprintf(stderr, "pool-bench-models: impact %d not resolved\n", i);
			for (int k = 0; k < 4; ++k)
				free(d[k]);
			return 1;
		}
		d[0][i] = pool_mathavan_difference(&b, &ours, &fine, R);
		d[1][i] = pool_mathavan_difference(&b, &ours, &ref, R);
		d[2][i] = pool_mathavan_difference(&b, &old, &fine, R);
		d[3][i] = pool_mathavan_difference(&b, &ref, &fine, R);
	}
	printf("%d random impacts (0.1-8 m/s, any incidence, spin and side), differences of the speed scale:\n", impacts);
	char what[96];
	snprintf(what, sizeof what, "libpool (tolerance %g) vs reference 65536 steps", POOL_MATHAVAN_TOLERANCE);
	print_quantiles(what, d[0], impacts);
	snprintf(what, sizeof what, "libpool (tolerance %g) vs reference 8192 steps", POOL_MATHAVAN_TOLERANCE);
	print_quantiles(what, d[1], impacts);
	print_quantiles("reference 128 steps vs reference 65536 steps", d[2], impacts);
	print_quantiles("reference 8192 steps vs reference 65536 steps", d[3], impacts);
	for (int k = 0; k < 4; ++k)
		free(d[k]);
	return 0;
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
			printf("usage: pool-bench-models [--runs N] [--accuracy N]\n"
			       "Times one ball-cushion impact by Petit's law, by mathavan2010 and by its reference\n"
			       "in 128 fixed steps (median and minimum per impact over %d batches of %d random\n"
			       "spinning impacts, and of rolling balls without side; mathavan2010 also on\n"
			       "rolling balls at single incidences), then the 8 m/s break\n"
			       "(frozen and 0.1 mm gap) under thesis, with each measured law, with the default\n"
			       "models, N runs each (default 1000): median and minimum per shot, and the ratio\n"
			       "to thesis. --accuracy N: libpool's Mathavan integration against the fixed-step\n"
			       "reference at 8192 and 65536 steps over N random impacts (and the reference at\n"
			       "128 and 8192 steps against 65536): median, p90, p99, worst.\n",
			       BATCHES, IMPACTS);
			return 0;
		}
		if (strcmp(argv[i], "--accuracy") == 0 && i + 1 < argc) {
			const int impacts = atoi(argv[++i]);
			if (impacts <= 0) {
				fprintf(stderr, "pool-bench-models: --accuracy: must be > 0\n");
				return 2;
			}
			return accuracy(impacts);
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
	// Rolling balls without side, 0.2-3 m/s, 0-85 deg in: most rail impacts of a game (the cloth
	// contact starts at zero slip).
	static pool_ball_state rolling[IMPACTS];
	for (int i = 0; i < IMPACTS; ++i) {
		const double v = 0.2 + 2.8 * urand(), a = urand() * 85.0 * 3.14159265358979 / 180.0;
		memset(&rolling[i], 0, sizeof rolling[i]);
		rolling[i].pos = (pool_vec3){1.0, def.table.width - 0.03, R};
		rolling[i].vel = (pool_vec3){v * sin(a), v * cos(a), 0.0};
		rolling[i].omega = (pool_vec3){-rolling[i].vel.y / R, rolling[i].vel.x / R, 0.0};
	}
	char name[64];
	snprintf(name, sizeof name, "mathavan2010 (tolerance %g)", POOL_MATHAVAN_TOLERANCE);
	for (int set = 0; set < 2; ++set) {
		const char *what = set ? "rolling" : "random";
		const pool_ball_state *impacts = set ? rolling : in;
		time_law(what, "petit (pool_collide)", 0, p, impacts, n);
		time_law(what, name, 1, p, impacts, n);
		time_law(what, "reference (128 fixed steps)", 2, p, impacts, n);
	}
	// The cost of one incidence: rolling balls at 0.2-3 m/s all at that angle (near right angles
	// the nose's slip turns as it shrinks to zero, which takes the integration many short steps).
	for (int deg = 0; deg <= 80; deg += deg < 30 ? 10 : 25) {
		static pool_ball_state at[IMPACTS];
		const double a = deg * 3.14159265358979 / 180.0;
		for (int i = 0; i < IMPACTS; ++i) {
			const double v = 0.2 + 2.8 * (i + 0.5) / IMPACTS;
			at[i] = rolling[i];
			at[i].vel = (pool_vec3){v * sin(a), v * cos(a), 0.0};
			at[i].omega = (pool_vec3){-at[i].vel.y / R, at[i].vel.x / R, 0.0};
		}
		char what[24]; // (room for any int the compiler can imagine)
		snprintf(what, sizeof what, "roll %2d", deg);
		time_law(what, name, 1, p, at, n);
	}
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
