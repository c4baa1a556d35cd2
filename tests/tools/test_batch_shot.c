// Unit tests of the batch shot (pool/batch.h) through the installed library's public API only:
// a shot's record and final states equal the same shot set up with libpool's own calls, refused
// strikes carry pool-batch's messages, the first ball hit is the one aimed at, a game layout is
// judged, the simulation reused or not gives the same bits, and a batch stops at a failing shot.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pool/batch.h"

// Cue ball 0 at (0.6, 0.635), ball 1 straight ahead along +x (phi = 0), ball 2 off to the side,
// away from every path below; the layout's own strike as written.
static const char layout_doc[] =
	"{\"format\": \"libpool-scenario/1\","
	" \"balls\": [{\"id\": 0, \"pos\": [0.6, 0.635]}, {\"id\": 1, \"pos\": [1.2, 0.635]},"
	"             {\"id\": 2, \"pos\": [1.8, 1.0]}],"
	" \"strike\": {\"ball\": 0, \"speed\": 2.5, \"phi\": 33.3, \"theta\": 7.25, \"a\": 0.004, \"b\": -0.006}}";

static void parse_ok(const char *doc, pool_scenario *s) {
	char err[POOL_SCENARIO_MESSAGE_SIZE];
	if (pool_scenario_parse(doc, strlen(doc), s, err, sizeof err) != 0)
		fail_msg("%s", err);
}

// The shot with libpool's own calls: the oracle of a batch shot's final states and figures.
static void direct_shot(const pool_scenario *layout, const pool_batch_strike *s, pool_ball_state *final,
                        int *events, double *end_time, pool_stop_reason *stop) {
	pool_sim *sim = NULL;
	pool_error e;
	assert_int_equal(pool_sim_create(&layout->def, &sim, &e), POOL_OK);
	for (int i = 0; i < layout->ball_count; ++i)
		assert_int_equal(pool_sim_add_ball(sim, &layout->balls[i], &e), POOL_OK);
	const double deg = 3.14159265358979323846 / 180.0;
	const pool_strike strike = {s->speed, s->phi * deg, s->theta * deg, s->a, s->b};
	assert_int_equal(pool_sim_strike(sim, s->ball, &strike, &e), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	*end_time = pool_sim_end_time(sim);
	assert_int_equal(pool_sim_state_at(sim, *end_time, final), POOL_OK);
	pool_sim_events(sim, events);
	*stop = pool_sim_stop_reason(sim);
	pool_sim_destroy(sim);
}

static void test_written_strike_is_the_files(void **state) {
	(void)state;
	pool_scenario s;
	parse_ok(layout_doc, &s);
	assert_true(s.has_strike);
	assert_int_equal(s.written.ball, 0);
	assert_true(s.written.speed == 2.5 && s.written.phi == 33.3 && s.written.theta == 7.25);
	assert_true(s.written.a == 0.004 && s.written.b == -0.006);
	assert_true(s.strike.phi == 33.3 * POOL_DEGREE && s.strike.theta == 7.25 * POOL_DEGREE);
	pool_scenario_free(&s);
	// Absent angles are 0 as written and in radians.
	const char *bare = "{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 4, \"pos\": [1, 0.5]}],"
	                   " \"strike\": {\"ball\": 4, \"speed\": 1}}";
	parse_ok(bare, &s);
	assert_int_equal(s.written.ball, 4);
	assert_true(s.written.phi == 0.0 && s.written.theta == 0.0 && s.strike.phi == 0.0);
	pool_scenario_free(&s);
}

static void test_batch_equals_direct_shots(void **state) {
	(void)state;
	pool_scenario layout;
	parse_ok(layout_doc, &layout);
	const pool_batch_strike strikes[] = {
		{0, 2.0, 0.0, 0.0, 0.0, 0.0},        // straight at ball 1
		{0, 1.0, 90.0, 0.0, 0.0, 0.0},       // away from every ball: to the north rail and back on x = 0.6
		{0, 3.0, 0.0, 0.0, 0.03, 0.0},       // refused: a beyond the ball
		{0, 3.0, 0.0, 95.0, 0.0, 0.0},       // refused: theta in degrees out of range
		{99, 3.0, 0.0, 0.0, 0.0, 0.0},       // refused: no such ball
		{1, 4.0, 123.4, 12.5, -0.01, 0.005}, // ball 1 struck
	};
	enum { N = sizeof strikes / sizeof strikes[0], BALLS = 3 };
	pool_batch_shot shots[N];
	pool_ball_state finals[N * BALLS];
	memset(finals, 0xA5, sizeof finals);
	pool_sim *sim = NULL;
	assert_int_equal(pool_batch_run(&layout, strikes, N, &sim, shots, finals), N);

	const int simulated[] = {0, 1, 5};
	for (size_t k = 0; k < sizeof simulated / sizeof simulated[0]; ++k) {
		const int i = simulated[k];
		pool_ball_state want[BALLS];
		int events;
		double end;
		pool_stop_reason stop;
		direct_shot(&layout, &strikes[i], want, &events, &end, &stop);
		assert_int_equal(shots[i].result, POOL_OK);
		assert_false(shots[i].failed);
		assert_string_equal(shots[i].message, "");
		assert_int_equal(shots[i].events, events);
		assert_true(shots[i].end_time == end);
		assert_int_equal(shots[i].stop_reason, stop);
		assert_int_equal(stop, POOL_STOP_REST);
		assert_memory_equal(&finals[i * BALLS], want, sizeof want);
		assert_false(shots[i].judged); // no "game" in the layout
	}
	assert_true(shots[0].hit);
	assert_int_equal(shots[0].first_hit, 1);
	assert_false(shots[1].hit);

	assert_int_equal(shots[2].result, POOL_ERR_BAD_STRIKE);
	assert_false(shots[2].failed);
	assert_string_equal(shots[2].message, "strike.a: a^2 + b^2 must be < R^2");
	assert_string_equal(shots[3].message, "strike.theta: must be in [0, 90) degrees");
	assert_int_equal(shots[4].result, POOL_ERR_UNKNOWN_BALL);
	assert_true(strncmp(shots[4].message, "strike", 6) == 0);
	// The finals of refused shots are left as they were.
	for (int i = 2; i <= 4; ++i)
		assert_int_equal(((const unsigned char *)&finals[i * BALLS])[0], 0xA5);

	// A new simulation per shot gives the same bits as the reused one.
	for (int i = 0; i < N; ++i) {
		pool_sim *fresh = NULL;
		pool_batch_shot again;
		pool_ball_state final[BALLS];
		memcpy(final, &finals[i * BALLS], sizeof final);
		assert_int_equal(pool_batch_run(&layout, &strikes[i], 1, &fresh, &again, final), 1);
		assert_memory_equal(&again, &shots[i], sizeof again);
		assert_memory_equal(final, &finals[i * BALLS], sizeof final);
		pool_sim_destroy(fresh);
	}
	pool_sim_destroy(sim);
	pool_scenario_free(&layout);
}

static void test_game_layout_is_judged(void **state) {
	(void)state;
	// 9-ball: the cue ball straight at the 1, the lowest ball on the table.
	const char *doc = "{\"format\": \"libpool-scenario/1\","
	                  " \"balls\": [{\"id\": 0, \"pos\": [0.6, 0.635]}, {\"id\": 1, \"pos\": [1.2, 0.635]},"
	                  "             {\"id\": 9, \"pos\": [1.8, 1.0]}],"
	                  " \"strike\": {\"ball\": 0, \"speed\": 2}, \"game\": {\"rules\": \"9ball\"}}";
	pool_scenario layout;
	parse_ok(doc, &layout);
	const pool_batch_strike strikes[] = {{0, 2.0, 0.0, 0.0, 0.0, 0.0}, {0, 2.0, 90.0, 0.0, 0.0, 0.0}};
	pool_batch_shot shots[2];
	pool_ball_state finals[2 * 3];
	pool_sim *sim = NULL;
	assert_int_equal(pool_batch_run(&layout, strikes, 2, &sim, shots, finals), 2);
	assert_true(shots[0].judged && shots[1].judged);
	assert_int_equal(shots[0].game.first_hit, 1);
	assert_false(shots[0].game.fouls & POOL_FOUL_NO_CONTACT);
	// Away from every ball: no contact, a foul.
	assert_false(shots[1].game.legal);
	assert_true(shots[1].game.fouls & POOL_FOUL_NO_CONTACT);
	pool_sim_destroy(sim);
	pool_scenario_free(&layout);
}

// An allocator with a budget of successful allocations, then none.
typedef struct budget {
	int left;
	int used;
} budget;

static void *budget_alloc(size_t size, void *context) {
	budget *b = context;
	if (b->left == 0)
		return NULL;
	if (b->left > 0)
		--b->left;
	++b->used;
	return malloc(size);
}

static void budget_free(void *memory, void *context) {
	(void)context;
	free(memory);
}

static void test_batch_stops_at_a_failing_shot(void **state) {
	(void)state;
	pool_scenario layout;
	parse_ok(layout_doc, &layout);
	budget b = {-1, 0};
	layout.def.allocator = (pool_allocator){budget_alloc, budget_free, &b};
	const pool_batch_strike strikes[] = {{0, 2.0, 0.0, 0.0, 0.0, 0.0}, {0, 2.0, 0.0, 0.0, 0.0, 0.0}};
	pool_batch_shot shots[2];
	pool_ball_state finals[2 * 3];

	// No memory at all: the first shot fails and the batch stops there.
	b.left = 0;
	pool_sim *sim = NULL;
	shots[1].events = -7;
	assert_int_equal(pool_batch_run(&layout, strikes, 2, &sim, shots, finals), 1);
	assert_true(shots[0].failed);
	assert_int_equal(shots[0].result, POOL_ERR_OUT_OF_MEMORY);
	assert_true(shots[0].message[0] != '\0');
	assert_int_equal(shots[1].events, -7); // not written
	pool_sim_destroy(sim);
	pool_scenario_free(&layout);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_written_strike_is_the_files),
		cmocka_unit_test(test_batch_equals_direct_shots),
		cmocka_unit_test(test_game_layout_is_judged),
		cmocka_unit_test(test_batch_stops_at_a_failing_shot),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
