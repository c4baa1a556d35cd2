// Synthetic observed shots for pool-fit-trials and pool-bench-fit: a random layout and strike (and
// table, when its parameters are fitted), simulated by libpool and recorded by a camera with
// Gaussian noise from a generator of their own (splitmix64, Box-Muller), not GSL's nor the
// library's: the trials check pool-fit against values it never saw.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit.h"
#include "splitmix.h"

typedef struct rng {
	uint64_t state;
	bool has_spare;
	double spare;
} rng;

static double uniform(rng *r) {
	return pool_splitmix_uniform(&r->state);
}

static double between(rng *r, double lo, double hi) { return lo + (hi - lo) * uniform(r); }

static double normal(void *ctx) {
	rng *r = ctx;
	if (r->has_spare) {
		r->has_spare = false;
		return r->spare;
	}
	double u = uniform(r), v = uniform(r), m = sqrt(-2.0 * log(u));
	r->spare = m * sin(6.283185307179586 * v);
	r->has_spare = true;
	return m * cos(6.283185307179586 * v);
}

/// Measured ranges (docs/validation.md) the true values of fitted table parameters are drawn from.
void fit_random_table(uint64_t seed, const bool *free_table, pool_params *p) {
	rng state = {.state = seed}, *r = &state;
	static const double range[FIT_TABLE_PARAMS][2] = {
		[FIT_MU_SLIDE] = {0.15, 0.3}, [FIT_MU_ROLL] = {0.006, 0.014}, [FIT_MU_SPIN] = {0.008, 0.018},
		[FIT_MU_BALL] = {0.03, 0.08}, [FIT_E_BALL] = {0.92, 0.98},   [FIT_MU_CUSHION] = {0.1, 0.3},
		[FIT_E_CUSHION] = {0.7, 0.9}, [FIT_MU_TABLE] = {0.1, 0.3},   [FIT_E_TABLE] = {0.5, 0.7},
		[FIT_THROW_A] = {0.005, 0.015}, [FIT_THROW_B] = {0.08, 0.13}, [FIT_THROW_C] = {0.8, 1.4},
		[FIT_CUE_END_MASS] = {0.005, 0.012}, [FIT_E_CUSHION_MATHAVAN] = {0.9, 0.99},
		[FIT_MU_CUSHION_MATHAVAN] = {0.1, 0.25}};
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		if (free_table[k])
			*fit_table_field(p, k) = between(r, range[k][0], range[k][1]);
}

/// A random shot: the cue ball, an object ball 0.3 to 1.2 m away hit with a cut of up to 70 % of
/// a full ball's offset, a third ball anywhere, a strike of 1 to 3 m/s with tip offsets within
/// 0.4 R. Writes the layout and the true strike.
static void random_shot(rng *r, const pool_sim_def *def, pool_ball_state balls[FIT_SYNTHETIC_BALLS], pool_strike *truth) {
	const double R = def->params.ball_radius, L = def->table.length, W = def->table.width, margin = 0.1;
	for (;;) {
		for (int k = 0; k < FIT_SYNTHETIC_BALLS; ++k)
			balls[k] = (pool_ball_state){.id = k, .pos = {between(r, margin, L - margin), between(r, margin, W - margin), R}};
		double d = between(r, 0.3, 1.2), angle = between(r, 0.0, 6.283185307179586);
		balls[1].pos.x = balls[0].pos.x + d * cos(angle);
		balls[1].pos.y = balls[0].pos.y + d * sin(angle);
		bool ok = balls[1].pos.x > margin && balls[1].pos.x < L - margin && balls[1].pos.y > margin &&
		          balls[1].pos.y < W - margin;
		for (int i = 0; i < FIT_SYNTHETIC_BALLS; ++i)
			for (int j = i + 1; j < FIT_SYNTHETIC_BALLS; ++j)
				ok = ok && hypot(balls[i].pos.x - balls[j].pos.x, balls[i].pos.y - balls[j].pos.y) > 0.1;
		if (!ok)
			continue;
		double cut = asin(between(r, -0.7, 0.7) * 2.0 * R / d);
		double tip = 0.4 * R * sqrt(uniform(r)), around = between(r, 0.0, 6.283185307179586);
		*truth = (pool_strike){.speed = between(r, 1.0, 3.0), .phi = angle + cut, .theta = 0.0,
		                       .a = tip * cos(around), .b = tip * sin(around)};
		return;
	}
}

int fit_synthetic_shot(uint64_t seed, long index, const pool_params *table, const pool_models *models,
                       double rate, double sigma, fit_synthetic *truth, fit_shot *shot) {
	rng r = {.state = seed * 0x100000001B3ULL + (uint64_t)index};
	pool_sim_def def = pool_default_sim_def();
	def.max_time = 20.0;
	def.params = *table;
	def.models = *models;
	memset(shot, 0, sizeof *shot);
	random_shot(&r, &def, truth->balls, &truth->strike);
	truth->params = *table;
	pool_sim *sim = NULL;
	pool_error err;
	if (pool_sim_create(&def, &sim, &err) != POOL_OK)
		return -1;
	for (int k = 0; k < FIT_SYNTHETIC_BALLS; ++k)
		pool_sim_add_ball(sim, &truth->balls[k], NULL);
	if (pool_sim_strike(sim, 0, &truth->strike, &err) != POOL_OK || pool_sim_run(sim) != POOL_OK) {
		pool_sim_destroy(sim);
		return -1;
	}
	// The camera's noise comes from a stream of its own, the same for every sigma (scaled), so
	// noise levels differ only in the noise's size.
	rng noise = {.state = r.state ^ 0xD1B54A32D192ED03ULL};
	int status = fit_camera(sim, rate, pool_sim_end_time(sim), sigma, normal, &noise, &shot->obs, &shot->obs_count);
	pool_sim_destroy(sim);
	if (status != 0)
		return -1;
	// The start: the table's defaults, the strike's direction off by a random half degree and its
	// speed by 10 %, no spin.
	shot->scenario_path = shot->tracks_path = "synthetic";
	def.params = pool_default_params();
	shot->scenario = (pool_scenario){.def = def, .ball_count = FIT_SYNTHETIC_BALLS, .balls = truth->balls,
	                                 .has_strike = true, .strike_ball = 0};
	shot->ball = 0;
	shot->start[FIT_SPEED] = truth->strike.speed * (1.0 + 0.1 * normal(&r));
	shot->start[FIT_PHI] = truth->strike.phi + 0.5 * 3.14159265358979323846 / 180.0 * normal(&r);
	shot->scenario.strike = (pool_strike){shot->start[FIT_SPEED], shot->start[FIT_PHI], 0.0, 0.0, 0.0};
	return 0;
}
