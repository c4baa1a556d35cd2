// One shot of a batch (pool/batch.h): moved out of pool-batch so that pool-sensitivity runs the
// very same shots.
#include "pool/batch.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


bool pool_batch_shoot(const pool_scenario *layout, const pool_batch_strike *s, pool_sim **sim,
                      pool_ball_state *final, char *error, size_t error_size, bool *internal) {
	*internal = false;
	if (!(s->theta >= 0.0 && s->theta < 90.0)) {
		snprintf(error, error_size, "strike.theta: must be in [0, 90) degrees"); // as the parser says
		return false;
	}
	pool_scenario shot = *layout; // shares the layout's balls, read only
	shot.has_strike = true;
	shot.strike_ball = s->ball;
	shot.strike = (pool_strike){.speed = s->speed, .phi = s->phi * POOL_BATCH_DEG,
	                            .theta = s->theta * POOL_BATCH_DEG, .a = s->a, .b = s->b};
	pool_error e = {{0}};
	pool_result r = pool_scenario_setup(&shot, sim, &e);
	if (r != POOL_OK) {
		const char *message = e.message[0] ? e.message : pool_result_str(r);
		snprintf(error, error_size, "%s%s", strncmp(message, "strike", 6) == 0 ? "" : "strike: ",
		         message);
		*internal = r == POOL_ERR_OUT_OF_MEMORY || r == POOL_ERR_INTERNAL;
		return false;
	}
	r = pool_sim_run(*sim);
	if (r == POOL_OK && layout->ball_count > 0)
		r = pool_sim_state_at(*sim, pool_sim_end_time(*sim), final);
	if (r != POOL_OK) {
		snprintf(error, error_size, "simulation failed at t = %.17g s: %s", pool_sim_time(*sim),
		         pool_sim_last_error(*sim)[0] ? pool_sim_last_error(*sim) : pool_result_str(r));
		*internal = true;
		return false;
	}
	return true;
}

bool pool_batch_first_hit(const pool_sim *sim, int32_t ball, int32_t *hit) {
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	for (int k = 0; k < count; ++k) {
		if (events[k].type != POOL_EVENT_BALL_BALL && events[k].type != POOL_EVENT_LINK_BEGIN)
			continue;
		const pool_ball_state *after = pool_sim_event_states(sim, &events[k]);
		bool involved = false;
		for (int j = 0; j < events[k].ball_count; ++j)
			involved = involved || after[j].id == ball;
		if (!involved)
			continue;
		for (int j = 0; j < events[k].ball_count; ++j)
			if (after[j].id != ball) {
				*hit = after[j].id;
				return true;
			}
	}
	return false;
}

static double noisy(double nominal, double sd, uint64_t seed, uint64_t sample, uint32_t k) {
	return sd > 0.0 ? nominal + sd * pool_noise_normal(seed, sample, k) : nominal;
}

pool_batch_strike pool_batch_noisy(const pool_batch_strike *nominal, const pool_noise *noise, uint64_t seed,
                                   uint64_t sample) {
	pool_batch_strike s = *nominal;
	s.speed = noisy(nominal->speed, noise->speed, seed, sample, 0);
	s.phi = noisy(nominal->phi, noise->phi / POOL_BATCH_DEG, seed, sample, 1);
	s.theta = fabs(noisy(nominal->theta, noise->theta / POOL_BATCH_DEG, seed, sample, 2));
	s.a = noisy(nominal->a, noise->a, seed, sample, 3);
	s.b = noisy(nominal->b, noise->b, seed, sample, 4);
	return s;
}

bool pool_batch_judge(const pool_scenario *layout, const pool_sim *sim, pool_game_result *result) {
	if (!layout->has_game)
		return false;
	const pool_game_shot shot = pool_game_shot_of_sim(sim);
	return pool_game_judge(&layout->game, &shot, &layout->def.table, result, NULL) == POOL_OK;
}
