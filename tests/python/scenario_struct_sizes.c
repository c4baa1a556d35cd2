// Prints sizeof and offsetof of the scenario library's structures that libpool._scenario mirrors,
// as JSON (the format of struct_sizes.c); test_scenario_binding.py compares it with ctypes.
#include <stdio.h>

#include <pool/batch.h>
#include <pool/scenario.h>

#include "struct_json.h"

int main(void) {
	printf("{");
	begin("pool_batch_strike", sizeof(pool_batch_strike));
	FIELD(pool_batch_strike, ball, 0); FIELD(pool_batch_strike, speed, 0); FIELD(pool_batch_strike, phi, 0);
	FIELD(pool_batch_strike, theta, 0); FIELD(pool_batch_strike, a, 0); FIELD(pool_batch_strike, b, 1);
	begin("pool_scenario", sizeof(pool_scenario));
	FIELD(pool_scenario, def, 0); FIELD(pool_scenario, ball_count, 0); FIELD(pool_scenario, balls, 0);
	FIELD(pool_scenario, has_strike, 0); FIELD(pool_scenario, strike_ball, 0); FIELD(pool_scenario, strike, 0);
	FIELD(pool_scenario, written, 0); FIELD(pool_scenario, has_game, 0); FIELD(pool_scenario, game, 1);
	begin("pool_batch_shot", sizeof(pool_batch_shot));
	FIELD(pool_batch_shot, result, 0); FIELD(pool_batch_shot, failed, 0); FIELD(pool_batch_shot, stop_reason, 0);
	FIELD(pool_batch_shot, events, 0); FIELD(pool_batch_shot, end_time, 0); FIELD(pool_batch_shot, hit, 0);
	FIELD(pool_batch_shot, first_hit, 0); FIELD(pool_batch_shot, judged, 0); FIELD(pool_batch_shot, game, 0);
	FIELD(pool_batch_shot, message, 1);
	begin("pool_result_options", sizeof(pool_result_options));
	FIELD(pool_result_options, sample_dt, 0); FIELD(pool_result_options, pretty, 0);
	FIELD(pool_result_options, def, 0); FIELD(pool_result_options, game, 1);
	printf(", \"constants\": {\"POOL_SCENARIO_MESSAGE_SIZE\": %d, \"POOL_BATCH_MESSAGE_SIZE\": %d, "
	       "\"POOL_SCENARIO_MAX_ABS\": %.17g}}\n",
	       POOL_SCENARIO_MESSAGE_SIZE, POOL_BATCH_MESSAGE_SIZE, POOL_SCENARIO_MAX_ABS);
	return 0;
}
