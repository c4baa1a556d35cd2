// pool-batch's and pool-sensitivity's layout file (batch_layout.h).
#include "batch_layout.h"

#include <stdio.h>

#include "cli.h"

int pool_batch_load_layout(const char *path, size_t max_input, pool_scenario *layout, char *err,
                           size_t err_size) {
	if (pool_scenario_load_file_limit(path, max_input, layout, err, err_size) != 0)
		return POOL_EXIT_BAD_INPUT;
	// The layout alone must set up (the parser already checked it; this is the library's word).
	pool_scenario balls_only = *layout;
	balls_only.has_strike = false;
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	pool_result r = pool_scenario_setup(&balls_only, &sim, &e);
	pool_sim_destroy(sim);
	if (r != POOL_OK) {
		snprintf(err, err_size, "%s", e.message[0] ? e.message : pool_result_str(r));
		pool_scenario_free(layout);
		return pool_cli_result_status(r);
	}
	return 0;
}
