// A user's program on the installed libpool games (find_package: libpool::pool_games): the rules'
// names and the fastfiz noise preset as docs/interfaces.md gives it.
#include <stdio.h>

#include <pool/game.h>
#include <pool/noise.h>
#include <pool/pool.h>

int main(void) {
	pool_noise noise;
	if (pool_game_rules_from_name("9ball") != POOL_GAME_9BALL || pool_noise_preset("fastfiz", &noise) != POOL_OK ||
	    noise.speed != 0.075)
		return 1;
	printf("consumer_games: 9ball rules, fastfiz speed sd %g m/s\n", noise.speed);
	return 0;
}
