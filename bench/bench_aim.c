// pool-bench-aim: seconds for pool-aim's best shot (top 1, 400 samples, fastfiz noise) of
// positions left by real breaks, on every core: a 9-ball rack broken (its balls where they rest,
// judged by the 9-ball rules: the lowest ball first), and an 8-ball rack broken softly so all 15
// object balls stay on the table (no rules: any ball, any pocket). Median and minimum of RUNS
// searches each, with the machine. docs/measurements.md "pool-aim".
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/aim.h>

#include "bench_util.h"

#define RUNS 7

/// The balls at rest after a break of `kind` at speed (phi a little off the rack's axis), or 0
/// when a ball dropped or left the table and want_all asks for every ball.
static int broken(pool_rack_kind kind, double speed, double phi, bool want_all, pool_ball_state *out) {
	pool_sim_def def = pool_default_sim_def();
	pool_ball_state balls[16];
	int n = pool_rack(kind, &def.table, &def.params, 1e-4, balls, 16);
	pool_sim *sim = NULL;
	pool_sim_create(&def, &sim, NULL);
	for (int k = 0; k < n; ++k)
		pool_sim_add_ball(sim, &balls[k], NULL);
	pool_strike s = pool_break_strike(speed);
	s.phi = phi;
	pool_sim_strike(sim, 0, &s, NULL);
	pool_sim_run(sim);
	int kept = 0;
	bool cue = false;
	for (int k = 0; k < n; ++k) {
		pool_ball_state b = pool_sim_balls(sim)[k];
		if (b.motion == POOL_MOTION_POCKETED || b.motion == POOL_MOTION_OFF_TABLE)
			continue;
		cue = cue || b.id == 0;
		b.vel = b.omega = (pool_vec3){0.0, 0.0, 0.0};
		b.motion = POOL_MOTION_STATIONARY;
		out[kept++] = b;
	}
	pool_sim_destroy(sim);
	return cue && (!want_all || kept == n) ? kept : 0;
}

static void bench(const char *name, const pool_ball_state *balls, int n, const pool_game_state *game) {
	pool_aim_def d = pool_default_aim_def();
	d.balls = balls;
	d.ball_count = n;
	d.top = 1;
	d.game = game;
	double seconds[RUNS], cpu[RUNS];
	pool_aim_shot shot = {0};
	pool_aim_stats stats = {0};
	int count = 0;
	for (int r = 0; r < RUNS; ++r) {
		double t0 = pool_bench_now_s(), c0 = pool_bench_cpu_s();
		pool_error e;
		if (pool_aim_search(&d, &shot, 1, &count, &stats, &e) != POOL_OK) {
			fprintf(stderr, "pool-bench-aim: %s: %s\n", name, e.message);
			exit(1);
		}
		seconds[r] = pool_bench_now_s() - t0;
		cpu[r] = pool_bench_cpu_s() - c0;
	}
	pool_bench_summary s = pool_bench_summarise(seconds, RUNS), c = pool_bench_summarise(cpu, RUNS);
	printf("%-34s %2d balls: median %.3f s, min %.3f s (CPU: median %.3f s, min %.3f s); %d candidates, %d pot, "
	       "%lld shots simulated", name, n, s.median, s.min, c.median, c.min, stats.candidates, stats.potting,
	       stats.simulations);
	if (count)
		printf("; best: %s ball %d into %s, p_success %.3f", pool_aim_kind_name(shot.kind), (int)shot.ball,
		       pool_pocket_name(shot.pocket), shot.p_success);
	printf("\n");
}

int main(void) {
	char cpu[256];
	printf("pool-bench-aim: %s, %ld CPUs online, load %.2f; pool-aim top 1, 400 samples, fastfiz noise, all "
	       "CPUs, %d runs; wall time, and the CPU time of every thread\n", pool_bench_cpu_model(cpu, sizeof cpu),
	       pool_bench_cpus_online(), pool_bench_load(), RUNS);
	pool_ball_state nine[16], fifteen[16];
	int n9 = 0, n15 = 0;
	for (int k = 0; k < 100 && !n9; ++k) // the first break that leaves the cue ball and the 1
		if ((n9 = broken(POOL_RACK_9BALL, 8.0, 0.002 * k, false, nine)) && nine[1].id != 1)
			n9 = 0;
	for (int k = 0; k < 100 && !n15; ++k)
		n15 = broken(POOL_RACK_8BALL, 3.0 + 0.05 * k, 0.003 * k, true, fifteen);
	pool_game_state game = pool_game_default_state(POOL_GAME_9BALL);
	game.break_shot = game.ball_in_hand = game.behind_head_string = game.push_out_available = false;
	if (n9)
		bench("9-ball after the break (rules)", nine, n9, &game);
	if (n15)
		bench("8-ball rack broken, 15 balls left", fifteen, n15, NULL);
	return 0;
}
