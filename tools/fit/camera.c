// What a camera above the table records of a simulated shot (pool-tracks, the fit's trials).
#include <stdlib.h>

#include "fit.h"

int fit_camera(const pool_sim *sim, double rate, double duration, double sigma, double (*normal)(void *ctx),
               void *ctx, fit_observation **out, long *count) {
	*out = NULL;
	*count = 0;
	int balls = pool_sim_ball_count(sim);
	long frames = (long)(duration * rate) + 1;
	fit_observation *obs = malloc((size_t)frames * (size_t)(balls > 0 ? balls : 1) * sizeof *obs);
	pool_ball_state *states = malloc((size_t)(balls > 0 ? balls : 1) * sizeof *states);
	if (!obs || !states) {
		free(obs);
		free(states);
		return -1;
	}
	double last = pool_sim_end_time(sim);
	long n = 0;
	for (long k = 0; k < frames; ++k) {
		double t = (double)k / rate;
		pool_sim_state_at(sim, t < last ? t : last, states);
		for (int b = 0; b < balls; ++b) {
			// Both deviates are drawn for every ball and frame, seen or not, so a frame's noise does
			// not depend on which balls have dropped.
			double dx = sigma > 0.0 ? sigma * normal(ctx) : 0.0, dy = sigma > 0.0 ? sigma * normal(ctx) : 0.0;
			if (states[b].motion == POOL_MOTION_POCKETED || states[b].motion == POOL_MOTION_OFF_TABLE)
				continue;
			obs[n++] = (fit_observation){.t = t, .ball = b, .x = states[b].pos.x + dx, .y = states[b].pos.y + dy,
			                             .line = n + 2};
		}
	}
	free(states);
	*out = obs;
	*count = n;
	return 0;
}
