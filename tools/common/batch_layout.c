// pool-batch's and pool-sensitivity's layout file (batch_layout.h).
#include "batch_layout.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "read_input.h"

int pool_batch_load_layout(const char *path, size_t max_input, pool_scenario *layout,
                           double degrees[2], char *err, size_t err_size) {
	// What pool_scenario_load_file_limit does, keeping the text to read the strike's angles in
	// the file's degrees (the parsed scenario has them in radians).
	char *text = NULL;
	size_t length = 0;
	memset(layout, 0, sizeof *layout);
	degrees[0] = degrees[1] = 0.0;
	if (pool_read_input(path, max_input, &text, &length, err, err_size) != 0 ||
	    pool_scenario_parse(text, length, layout, err, err_size) != 0) {
		free(text);
		return POOL_EXIT_BAD_INPUT;
	}
	if (layout->has_strike) {
		json_t *root = json_loadb(text, length, 0, NULL);
		json_t *strike = json_object_get(root, "strike");
		json_t *phi = json_object_get(strike, "phi"), *theta = json_object_get(strike, "theta");
		degrees[0] = phi ? json_number_value(phi) : 0.0;
		degrees[1] = theta ? json_number_value(theta) : 0.0;
		json_decref(root);
	}
	free(text);
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
