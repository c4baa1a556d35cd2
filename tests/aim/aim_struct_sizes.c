// Prints sizeof and offsetof of the planning library's structures that libpool.aim mirrors, as
// JSON (the format of tests/python/struct_sizes.c); test_aim_python.py compares it with ctypes.
#include <stddef.h>
#include <stdio.h>

#include <pool/aim.h>

static int first = 1;

static void begin(const char *name, size_t size) {
	printf("%s\"%s\": {\"size\": %zu, \"fields\": {", first ? "" : ", ", name, size);
	first = 0;
}

#define FIELD(type, field, last) printf("\"%s\": %zu%s", #field, offsetof(type, field), (last) ? "}}" : ", ")

int main(void) {
	printf("{");
	begin("pool_aim_def", sizeof(pool_aim_def));
	FIELD(pool_aim_def, sim, 0); FIELD(pool_aim_def, balls, 0); FIELD(pool_aim_def, ball_count, 0);
	FIELD(pool_aim_def, cue_ball, 0); FIELD(pool_aim_def, ball, 0); FIELD(pool_aim_def, pocket, 0);
	FIELD(pool_aim_def, kinds, 0); FIELD(pool_aim_def, game, 0); FIELD(pool_aim_def, noise, 0);
	FIELD(pool_aim_def, seed, 0); FIELD(pool_aim_def, samples, 0); FIELD(pool_aim_def, top, 0);
	FIELD(pool_aim_def, time_budget, 0); FIELD(pool_aim_def, threads, 0); FIELD(pool_aim_def, position, 0);
	FIELD(pool_aim_def, distinct, 1);
	begin("pool_aim_shot", sizeof(pool_aim_shot));
	FIELD(pool_aim_shot, strike, 0); FIELD(pool_aim_shot, ball, 0); FIELD(pool_aim_shot, pocket, 0);
	FIELD(pool_aim_shot, kind, 0); FIELD(pool_aim_shot, via, 0); FIELD(pool_aim_shot, rail, 0);
	FIELD(pool_aim_shot, p_success, 0); FIELD(pool_aim_shot, ci_low, 0); FIELD(pool_aim_shot, ci_high, 0);
	FIELD(pool_aim_shot, samples, 0); FIELD(pool_aim_shot, cue_final, 0); FIELD(pool_aim_shot, position, 1);
	begin("pool_aim_stats", sizeof(pool_aim_stats));
	FIELD(pool_aim_stats, candidates, 0); FIELD(pool_aim_stats, blocked, 0); FIELD(pool_aim_stats, refined, 0);
	FIELD(pool_aim_stats, potting, 0); FIELD(pool_aim_stats, simulations, 0); FIELD(pool_aim_stats, seconds, 0);
	FIELD(pool_aim_stats, budget_reached, 1);
	printf("}\n");
	return 0;
}
