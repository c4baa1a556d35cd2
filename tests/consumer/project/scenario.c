// A user's program on the installed scenario library (find_package: libpool::pool_scenario;
// pkg-config: libpool_scenario): a scenario document parsed, its shot simulated and written as
// a result document, and a batch of strikes on the same layout whose first shot is that shot.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/batch.h>
#include <pool/scenario.h>

static const char doc[] =
	"{\"format\": \"" POOL_SCENARIO_FORMAT "\", \"table\": \"wpa-8ft\","
	" \"balls\": [{\"id\": 0, \"pos\": [0.6, 0.6]}, {\"id\": 1, \"pos\": [1.2, 0.6]}],"
	" \"strike\": {\"ball\": 0, \"speed\": 2, \"phi\": 0}}";

int main(void) {
	pool_scenario s;
	char err[POOL_SCENARIO_MESSAGE_SIZE];
	if (pool_scenario_parse(doc, strlen(doc), &s, err, sizeof err) != 0)
		return fprintf(stderr, "%s\n", err), 1;
	pool_sim *sim = NULL;
	pool_error e;
	if (pool_scenario_setup(&s, &sim, &e) != POOL_OK || pool_sim_run(sim) != POOL_OK)
		return 1;
	int events;
	pool_sim_events(sim, &events);
	const pool_result_options options = {.def = &s.def};
	char *result = pool_result_json(sim, &options);
	int ok = result && strstr(result, "\"" POOL_RESULT_FORMAT "\"") != NULL;
	pool_scenario_text_free(result);

	// A refused strike (a beyond the ball's edge) among them: its record says why.
	const pool_batch_strike strikes[] = {s.written, {0, 2.0, 0.0, 0.0, 0.05, 0.0}};
	pool_batch_shot shots[2];
	pool_ball_state finals[2 * 2];
	pool_sim *batch_sim = NULL;
	ok = ok && pool_batch_run(&s, strikes, 2, &batch_sim, shots, finals) == 2 &&
	     shots[0].result == POOL_OK && shots[0].events == events && shots[0].hit && shots[0].first_hit == 1 &&
	     shots[1].result != POOL_OK && strncmp(shots[1].message, "strike.a", 8) == 0;
	printf("consumer_scenario: a shot of %d events written as %s; batch: %s\n", events, POOL_RESULT_FORMAT,
	       shots[1].message);
	pool_sim_destroy(batch_sim);
	pool_sim_destroy(sim);
	pool_scenario_free(&s);
	return ok ? 0 : 1;
}
