// The samples of a sensitivity study, drawn before any shot runs from libpool games' counter-based
// normal deviates (pool/noise.h): sample i depends on the seed and i alone, never on the threads,
// and its strike is pool-batch --noise's strike i for the same noise and seed (batch_shot.h).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"

const char *const sens_cue_names[SENS_CUE_COUNT] = {"speed", "phi", "theta", "a", "b"};

const char *sens_rng_name(void) { return "pool_noise_normal"; }

int sens_draw_samples(const pool_scenario *layout, const pool_batch_strike *nominal,
                      const sens_noise *noise, long n, unsigned long seed, sens_samples *out) {
	memset(out, 0, sizeof *out);
	int m = noise->position_count;
	out->n = n;
	out->position_count = m;
	out->strikes = calloc((size_t)n, sizeof *out->strikes);
	out->positions = m ? calloc((size_t)n * (size_t)m * 2, sizeof *out->positions) : NULL;
	if (!out->strikes || (m && !out->positions)) {
		sens_samples_free(out);
		return -1;
	}
	for (long i = 0; i < n; ++i) {
		// Deviates 0 to 4: the cue parameters; then 5 + 2k and 6 + 2k: x and y of noisy ball k.
		out->strikes[i] = pool_batch_noisy(nominal, &noise->cue, seed, (uint64_t)i);
		for (int k = 0; k < m; ++k) {
			const pool_ball_state *ball = &layout->balls[noise->position_index[k]];
			double *xy = &out->positions[(i * m + k) * 2];
			xy[0] = ball->pos.x;
			xy[1] = ball->pos.y;
			if (noise->position_sd > 0.0) {
				xy[0] += noise->position_sd * pool_noise_normal(seed, (uint64_t)i, 5u + 2u * (uint32_t)k);
				xy[1] += noise->position_sd * pool_noise_normal(seed, (uint64_t)i, 6u + 2u * (uint32_t)k);
			}
		}
	}
	return 0;
}

void sens_samples_free(sens_samples *s) {
	free(s->strikes);
	free(s->positions);
	memset(s, 0, sizeof *s);
}
