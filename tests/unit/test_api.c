// The small public conveniences: pool_version, pool_stop_reason_name, pool_ball_on_cloth and
// pool_sim_states_at (many times in one call), and the messages that name the C def's fields.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "pool/pool.h"
#include "sim_fixture.h"

static void test_version_matches_headers(void **state) {
	(void)state;
	assert_int_equal(pool_version(), POOL_VERSION);
	// major * 10000 + minor * 100 + patch: every part below 100.
	assert_true(pool_version() > 0 && pool_version() % 100 < 100);
}

static void test_stop_reason_names(void **state) {
	(void)state;
	assert_string_equal(pool_stop_reason_name(POOL_STOP_NONE), "none");
	assert_string_equal(pool_stop_reason_name(POOL_STOP_REST), "rest");
	assert_string_equal(pool_stop_reason_name(POOL_STOP_MAX_TIME), "max_time");
	assert_string_equal(pool_stop_reason_name(POOL_STOP_MAX_EVENTS), "max_events");
	assert_string_equal(pool_stop_reason_name((pool_stop_reason)42), "unknown");
	assert_string_equal(pool_stop_reason_name((pool_stop_reason)-1), "unknown");
}

static void test_ball_on_cloth_is_accepted_where_a_zero_ball_is_not(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	def.params.ball_radius = 0.03;
	pool_sim *sim = make_sim(&def);
	pool_ball_state zero = {.id = 1, .pos = {1.0, 0.5, 0.0}};
	pool_error err;
	assert_int_equal(pool_sim_add_ball(sim, &zero, &err), POOL_ERR_INVALID_ARGUMENT);
	// The C API's message names the C field, not the JSON option.
	assert_non_null(strstr(err.message, "def.airborne"));
	assert_null(strstr(err.message, "options."));

	pool_ball_state b = pool_ball_on_cloth(1, 1.0, 0.5, &def.params);
	assert_int_equal(b.id, 1);
	assert_true(b.pos.x == 1.0 && b.pos.y == 0.5 && b.pos.z == 0.03);
	assert_true(b.vel.x == 0.0 && b.vel.y == 0.0 && b.vel.z == 0.0);
	assert_true(b.omega.x == 0.0 && b.omega.y == 0.0 && b.omega.z == 0.0);
	assert_int_equal(b.motion, POOL_MOTION_STATIONARY);
	assert_int_equal(pool_sim_add_ball(sim, &b, &err), POOL_OK);
	// NULL params: the default ball.
	assert_true(pool_ball_on_cloth(2, 0.0, 0.0, NULL).pos.z == pool_default_params().ball_radius);
	pool_sim_destroy(sim);
}

static void test_def_messages_name_c_fields(void **state) {
	(void)state;
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim = NULL;
	pool_error err;
	def.max_time = 0.0;
	assert_int_equal(pool_sim_create(&def, &sim, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "def.max_time: must be > 0");
	def = pool_default_sim_def();
	def.max_events = 0;
	assert_int_equal(pool_sim_create(&def, &sim, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "def.max_events: must be > 0");
	assert_null(sim);
}

// A break, so the balls' chains hold many states of every motion.
static pool_sim *break_shot(void) {
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim = make_sim(&def);
	pool_ball_state balls[16];
	int n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 1e-4, balls, 16);
	for (int i = 0; i < n; ++i)
		add_ball(sim, &balls[i]);
	pool_strike s = pool_break_strike(8.0);
	assert_int_equal(pool_sim_strike(sim, 0, &s, NULL), POOL_OK);
	return sim;
}

static void test_states_at_equals_state_at_bit_for_bit(void **state) {
	(void)state;
	pool_sim *sim = break_shot();
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	const int n = pool_sim_ball_count(sim);
	// Event times (where states change), times between them, out of order, repeated.
	int count_events;
	const pool_event *events = pool_sim_events(sim, &count_events);
	const int count = 2 * count_events + 3;
	double *times = malloc((size_t)count * sizeof *times);
	for (int k = 0; k < count_events; ++k) {
		times[2 * k] = events[count_events - 1 - k].time;
		times[2 * k + 1] = events[k].time + 0.37 * (k + 1 < count_events ? events[k + 1].time - events[k].time : 1.0);
	}
	times[count - 3] = 0.0;
	times[count - 2] = pool_sim_end_time(sim) + 5.0; // beyond the end of a shot at rest: allowed
	times[count - 1] = times[3];
	pool_ball_state *many = malloc((size_t)count * (size_t)n * sizeof *many);
	pool_ball_state *one = malloc((size_t)n * sizeof *one);
	assert_int_equal(pool_sim_states_at(sim, times, count, many, NULL), POOL_OK);
	for (int k = 0; k < count; ++k) {
		assert_int_equal(pool_sim_state_at(sim, times[k], one), POOL_OK);
		assert_memory_equal(one, many + (size_t)k * (size_t)n, (size_t)n * sizeof *one);
	}
	free(one);
	free(many);
	free(times);
	pool_sim_destroy(sim);
}

static void test_states_at_refuses_bad_times_writing_nothing(void **state) {
	(void)state;
	pool_sim *sim = break_shot();
	assert_int_equal(pool_sim_run_until(sim, 0.5), POOL_OK);
	const int n = pool_sim_ball_count(sim);
	pool_ball_state out[3 * 16];
	memset(out, 0xAB, sizeof out);
	unsigned char pristine[sizeof out];
	memcpy(pristine, out, sizeof out);
	int bad = -1;
	double nan_time[3] = {0.1, NAN, 0.2};
	assert_int_equal(pool_sim_states_at(sim, nan_time, 3, out, &bad), POOL_ERR_INVALID_ARGUMENT);
	assert_int_equal(bad, 1);
	double negative[3] = {0.1, 0.2, -1e-300};
	assert_int_equal(pool_sim_states_at(sim, negative, 3, out, &bad), POOL_ERR_INVALID_ARGUMENT);
	assert_int_equal(bad, 2);
	// Beyond the processed time of a shot still running: the state there is not known yet.
	double late[3] = {10.0, 0.1, 0.2};
	assert_int_equal(pool_sim_states_at(sim, late, 3, out, &bad), POOL_ERR_STATE);
	assert_int_equal(bad, 0);
	assert_memory_equal(out, pristine, sizeof out);
	// Zero times: nothing to do; NULL arrays with a count are refused.
	assert_int_equal(pool_sim_states_at(sim, NULL, 0, NULL, NULL), POOL_OK);
	assert_int_equal(pool_sim_states_at(sim, NULL, 2, out, NULL), POOL_ERR_INVALID_ARGUMENT);
	assert_int_equal(pool_sim_states_at(sim, late, -1, out, NULL), POOL_ERR_INVALID_ARGUMENT);
	assert_int_equal(pool_sim_states_at(NULL, late, 1, out, NULL), POOL_ERR_INVALID_ARGUMENT);
	assert_true(n == 16);
	pool_sim_destroy(sim);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_version_matches_headers),
		cmocka_unit_test(test_stop_reason_names),
		cmocka_unit_test(test_ball_on_cloth_is_accepted_where_a_zero_ball_is_not),
		cmocka_unit_test(test_def_messages_name_c_fields),
		cmocka_unit_test(test_states_at_equals_state_at_bit_for_bit),
		cmocka_unit_test(test_states_at_refuses_bad_times_writing_nothing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
