// The samples of a sensitivity study, all drawn before any shot runs, in sample order, from one
// seeded GSL generator: the study's numbers then depend on the seed alone, never on the threads.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"

const char *const sens_cue_names[SENS_CUE_COUNT] = {"speed", "phi", "theta", "a", "b"};

// Mersenne Twister (Matsumoto and Nishimura 1998), GSL's default: period 2^19937 - 1, and the
// same sequence for a seed on every platform GSL runs on.
static const gsl_rng_type *rng_type(void) { return gsl_rng_mt19937; }

const char *sens_rng_name(void) { return rng_type()->name; }

static double noisy(double nominal, double sd, double z) { return sd > 0.0 ? nominal + sd * z : nominal; }

int sens_draw_samples(const pool_scenario *layout, const pool_batch_strike *nominal,
                      const sens_noise *noise, long n, unsigned long seed, sens_samples *out) {
	memset(out, 0, sizeof *out);
	int m = noise->position_count;
	out->n = n;
	out->position_count = m;
	out->strikes = calloc((size_t)n, sizeof *out->strikes);
	out->positions = m ? calloc((size_t)n * (size_t)m * 2, sizeof *out->positions) : NULL;
	gsl_rng *rng = gsl_rng_alloc(rng_type());
	if (!out->strikes || (m && !out->positions) || !rng) {
		gsl_rng_free(rng);
		sens_samples_free(out);
		return -1;
	}
	gsl_rng_set(rng, seed);
	const double *sd = noise->cue_sd;
	for (long i = 0; i < n; ++i) {
		double z[SENS_CUE_COUNT];
		for (int p = 0; p < SENS_CUE_COUNT; ++p) // every deviate is drawn, whatever the sd
			z[p] = gsl_ran_gaussian(rng, 1.0);
		pool_batch_strike *s = &out->strikes[i];
		s->ball = nominal->ball;
		s->speed = noisy(nominal->speed, sd[SENS_SPEED], z[SENS_SPEED]);
		s->phi = noisy(nominal->phi, sd[SENS_PHI], z[SENS_PHI]);
		s->theta = fabs(noisy(nominal->theta, sd[SENS_THETA], z[SENS_THETA]));
		s->a = noisy(nominal->a, sd[SENS_A], z[SENS_A]);
		s->b = noisy(nominal->b, sd[SENS_B], z[SENS_B]);
		for (int k = 0; k < m; ++k) {
			const pool_ball_state *ball = &layout->balls[noise->position_index[k]];
			double zx = gsl_ran_gaussian(rng, 1.0), zy = gsl_ran_gaussian(rng, 1.0);
			out->positions[(i * m + k) * 2] = noisy(ball->pos.x, noise->position_sd, zx);
			out->positions[(i * m + k) * 2 + 1] = noisy(ball->pos.y, noise->position_sd, zy);
		}
	}
	gsl_rng_free(rng);
	return 0;
}

void sens_samples_free(sens_samples *s) {
	free(s->strikes);
	free(s->positions);
	memset(s, 0, sizeof *s);
}
