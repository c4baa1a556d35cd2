// pool-bench-games: what the rules cost against the shot they judge (issue 22's target: under
// 5 %). For each scene, SHOTS shots are simulated once (reset, balls, strike, run), then judged
// JUDGES times each; a run times both over all the shots. RUNS runs: median and minimum per shot
// of the simulation and of the judge, and the judge's share of the simulation. The machine's
// CPU and online CPUs are printed first.
#define _DEFAULT_SOURCE // M_PI
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <pool/game.h>

#include "bench_util.h"

enum { SHOTS = 200, RUNS = 15, JUDGES = 20 };

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double urand(double lo, double hi) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return lo + (hi - lo) * (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct scene {
	const char *name;
	pool_game_rules rules;
	bool break_shot;
} scene;

/// Shot i of a scene: its balls and strike (the same in every run).
static int setup(const scene *sc, const pool_sim_def *def, int i, pool_ball_state *balls, pool_strike *strike) {
	rng = 0x2545F4914F6CDD1Dull + (uint64_t)i * 0x9E3779B97F4A7C15ull;
	const int n = pool_game_rack(sc->rules, &def->table, &def->params, urand(0.0, 1e-4), balls, POOL_GAME_MAX_BALLS);
	if (sc->rules == POOL_GAME_THREE_CUSHION) {
		*strike = (pool_strike){.speed = urand(2.0, 6.0), .phi = urand(-M_PI, M_PI),
		                        .a = urand(-0.4, 0.4) * def->params.ball_radius};
	} else if (sc->break_shot) {
		*strike = pool_break_strike(urand(6.0, 9.0));
		strike->phi = urand(-0.02, 0.02);
	} else { // a cut at the rack's apex ball from the head spot, softer
		*strike = (pool_strike){.speed = urand(1.0, 4.0), .phi = urand(-0.05, 0.05),
		                        .b = urand(-0.4, 0.4) * def->params.ball_radius};
	}
	return n;
}

static double run_shots(pool_sim *sim, const scene *sc, const pool_sim_def *def, pool_game_shot *kept,
                        pool_sim **store) {
	const double t0 = pool_bench_now_s();
	for (int i = 0; i < SHOTS; ++i) {
		pool_ball_state balls[POOL_GAME_MAX_BALLS];
		pool_strike strike;
		const int n = setup(sc, def, i, balls, &strike);
		pool_sim *s = store ? store[i] : sim;
		pool_sim_reset(s, def, NULL);
		for (int k = 0; k < n; ++k)
			pool_sim_add_ball(s, &balls[k], NULL);
		pool_sim_strike(s, 0, &strike, NULL);
		pool_sim_run(s);
		if (kept)
			kept[i] = pool_game_shot_of_sim(s);
	}
	return (pool_bench_now_s() - t0) / SHOTS;
}

static volatile int sink;

int main(void) {
	char cpu[256];
	printf("pool-bench-games: %s, %ld CPUs online; %d shots per scene, %d runs, each shot judged %d times a run\n",
	       pool_bench_cpu_model(cpu, sizeof cpu), pool_bench_cpus_online(), SHOTS, RUNS, JUDGES);
	const scene scenes[] = {{"8-ball breaks", POOL_GAME_8BALL, true},
	                        {"9-ball breaks", POOL_GAME_9BALL, true},
	                        {"9-ball soft shots at the rack", POOL_GAME_9BALL, false},
	                        {"three-cushion shots", POOL_GAME_THREE_CUSHION, false}};
	for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; ++k) {
		const scene *sc = &scenes[k];
		pool_sim_def def = pool_default_sim_def();
		if (sc->rules == POOL_GAME_THREE_CUSHION) { // the carom table and balls of pool-game
			pool_table_preset("carom", &def.table);
			pool_params_preset("carom", &def.params);
		}
		pool_sim *sim = NULL;
		pool_sim_create(&def, &sim, NULL);
		pool_sim **store = calloc(SHOTS, sizeof *store);
		pool_game_shot *shots = calloc(SHOTS, sizeof *shots);
		for (int i = 0; i < SHOTS; ++i)
			pool_sim_create(&def, &store[i], NULL);
		run_shots(NULL, sc, &def, shots, store); // the shots the judge reads, kept
		pool_game_state st = pool_game_default_state(sc->rules);
		st.break_shot = sc->break_shot;
		if (!sc->break_shot)
			st.ball_in_hand = st.behind_head_string = false;
		double sim_t[RUNS], judge_t[RUNS], share[RUNS];
		long events = 0;
		for (int i = 0; i < SHOTS; ++i)
			events += shots[i].event_count;
		for (int r = 0; r < RUNS; ++r) {
			sim_t[r] = run_shots(sim, sc, &def, NULL, NULL);
			const double t0 = pool_bench_now_s();
			int acc = 0;
			for (int j = 0; j < JUDGES; ++j)
				for (int i = 0; i < SHOTS; ++i) {
					pool_game_result res;
					acc += pool_game_judge(&st, &shots[i], &def.table, &res, NULL) == POOL_OK ? (int)res.outcome : -1;
				}
			judge_t[r] = (pool_bench_now_s() - t0) / (SHOTS * (double)JUDGES);
			share[r] = judge_t[r] / sim_t[r];
			sink = acc;
		}
		const pool_bench_summary s = pool_bench_summarise(sim_t, RUNS);
		const pool_bench_summary j = pool_bench_summarise(judge_t, RUNS);
		const pool_bench_summary q = pool_bench_summarise(share, RUNS);
		printf("%-30s %5.0f events/shot  simulation median %8.2f us min %8.2f us   rules median %6.3f us "
		       "min %6.3f us   rules/simulation median %5.2f %% min %5.2f %%\n",
		       sc->name, (double)events / SHOTS, 1e6 * s.median, 1e6 * s.min, 1e6 * j.median, 1e6 * j.min,
		       100.0 * q.median, 100.0 * q.min);
		for (int i = 0; i < SHOTS; ++i)
			pool_sim_destroy(store[i]);
		free(store);
		free(shots);
		pool_sim_destroy(sim);
	}
	return 0;
}
