// The batch shot (pool/batch.h): pool-batch's shots, shared with pool-sensitivity and Python's
// libpool.batch so that their rows are the same shots.
#include "pool/batch.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

// Simulates strike s on layout in *sim; the final states to final. Returns POOL_OK, or the code
// of a refusal or failure with pool-batch's message in error and *failed set for failures (the
// library's, not the strike's fault).
static pool_result shoot(const pool_scenario *layout, const pool_batch_strike *s, pool_sim **sim,
                         pool_ball_state *final, char *error, size_t error_size, bool *failed) {
	*failed = false;
	if (!(s->theta >= 0.0 && s->theta < 90.0)) {
		snprintf(error, error_size, "strike.theta: must be in [0, 90) degrees"); // as the parser says
		return POOL_ERR_BAD_STRIKE;
	}
	pool_scenario shot = *layout; // shares the layout's balls, read only
	shot.has_strike = true;
	shot.strike_ball = s->ball;
	shot.strike = (pool_strike){.speed = s->speed, .phi = s->phi * POOL_DEGREE,
	                            .theta = s->theta * POOL_DEGREE, .a = s->a, .b = s->b};
	pool_error e = {{0}};
	pool_result r = pool_scenario_setup(&shot, sim, &e);
	if (r != POOL_OK) {
		const char *message = e.message[0] ? e.message : pool_result_str(r);
		snprintf(error, error_size, "%s%s", strncmp(message, "strike", 6) == 0 ? "" : "strike: ",
		         message);
		*failed = r == POOL_ERR_OUT_OF_MEMORY || r == POOL_ERR_INTERNAL;
		return r;
	}
	r = pool_sim_run(*sim);
	if (r == POOL_OK && layout->ball_count > 0)
		r = pool_sim_state_at(*sim, pool_sim_end_time(*sim), final);
	if (r != POOL_OK) {
		snprintf(error, error_size, "simulation failed at t = %.17g s: %s", pool_sim_time(*sim),
		         pool_sim_last_error(*sim)[0] ? pool_sim_last_error(*sim) : pool_result_str(r));
		*failed = true;
	}
	return r;
}

bool pool_batch_shoot(const pool_scenario *layout, const pool_batch_strike *s, pool_sim **sim,
                      pool_ball_state *final, char *error, size_t error_size, bool *internal) {
	return shoot(layout, s, sim, final, error, error_size, internal) == POOL_OK;
}

int pool_batch_run(const pool_scenario *layout, const pool_batch_strike *strikes, int count,
                   pool_sim **sim, pool_batch_shot *shots, pool_ball_state *finals) {
	for (int i = 0; i < count; ++i) {
		pool_batch_shot *shot = &shots[i];
		memset(shot, 0, sizeof *shot);
		shot->result = shoot(layout, &strikes[i], sim, finals + (size_t)i * (size_t)layout->ball_count,
		                     shot->message, sizeof shot->message, &shot->failed);
		if (shot->failed)
			return i + 1;
		if (shot->result != POOL_OK)
			continue;
		shot->stop_reason = pool_sim_stop_reason(*sim);
		pool_sim_events(*sim, &shot->events);
		shot->end_time = pool_sim_end_time(*sim);
		shot->hit = pool_batch_first_hit(*sim, strikes[i].ball, &shot->first_hit);
		shot->judged = pool_batch_judge(layout, *sim, &shot->game);
	}
	return count;
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
	s.phi = noisy(nominal->phi, noise->phi / POOL_DEGREE, seed, sample, 1);
	s.theta = fabs(noisy(nominal->theta, noise->theta / POOL_DEGREE, seed, sample, 2));
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
