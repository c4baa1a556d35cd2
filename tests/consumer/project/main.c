// A user's program: solves (x - 1)(x - 2)(x - 3)(x - 4) = 0 through the installed libpool, and
// reads the installed libpool games' names and noise presets.
#include <math.h>
#include <stdio.h>

#include <pool/game.h>
#include <pool/noise.h>
#include <pool/pool.h>

int main(void) {
	const double c[5] = {1.0, -10.0, 35.0, -50.0, 24.0};
	double roots[4];
	int n = pool_quartic_real_roots(c, roots);
	printf("consumer: %d roots: %g %g %g %g\n", n, roots[0], roots[1], roots[2], roots[3]);
	if (n != 4)
		return 1;
	for (int i = 0; i < 4; ++i)
		if (fabs(roots[i] - (i + 1)) > 1e-12)
			return 1;
	pool_noise noise;
	if (pool_game_rules_from_name("9ball") != POOL_GAME_9BALL || pool_noise_preset("fastfiz", &noise) != POOL_OK ||
	    noise.speed != 0.075)
		return 1;
	return 0;
}
