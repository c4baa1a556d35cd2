// Table presets, default parameters and validation messages.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "pool/pool.h"

static void test_presets(void **state) {
	(void)state;
	pool_table_def t;
	assert_int_equal(pool_table_preset("wpa-9ft", &t), POOL_OK);
	assert_true(t.length == 2.54 && t.width == 1.27);
	assert_int_equal(pool_table_preset("wpa-8ft", &t), POOL_OK);
	assert_true(fabs(t.length - 2.3368) < 1e-12 && fabs(t.width - 1.1684) < 1e-12);
	assert_int_equal(pool_table_preset("wpa-7ft", &t), POOL_OK);
	assert_true(fabs(t.length - 1.9812) < 1e-12 && fabs(t.width - 0.9906) < 1e-12);
	assert_true(t.cushion_height == 0.03629 && t.corner_mouth == 0.1143 && t.side_mouth == 0.127);
	assert_int_equal(pool_table_preset("snooker", &t), POOL_ERR_UNKNOWN_PRESET);
	pool_table_def d = pool_default_table_def();
	assert_true(d.length == 2.54 && d.cushion_height == 0.03629);
}

static void test_defaults(void **state) {
	(void)state;
	pool_params p = pool_default_params();
	assert_true(p.ball_radius == 0.028575 && p.ball_mass == 0.17 && p.g == 9.81);
	assert_true(p.mu_slide == 0.2 && p.mu_roll == 0.01 && p.mu_spin == 0.0127);
	assert_true(p.mu_ball == 0.06 && p.e_ball == 0.95 && p.mu_cushion == 0.2 && p.e_cushion == 0.85);
	assert_true(p.mu_table == 0.2 && p.e_table == 0.5 && p.cue_mass == 0.54);
	assert_int_equal(pool_params_validate(&p, NULL), POOL_OK);
	pool_sim_def def = pool_default_sim_def();
	assert_true(def.max_time == 120.0 && def.max_events == 100000 && !def.airborne);
}

static void test_validation(void **state) {
	(void)state;
	pool_error err;
	pool_table_def t = pool_default_table_def();
	t.width = -1.0;
	assert_int_equal(pool_table_def_validate(&t, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "table.width: must be > 0");
	t = pool_default_table_def();
	t.cushion_height = INFINITY;
	assert_int_equal(pool_table_def_validate(&t, &err), POOL_ERR_NON_FINITE);
	assert_string_equal(err.message, "table.cushion_height: must be finite");
	pool_params p = pool_default_params();
	p.mu_roll = -1e-3;
	assert_int_equal(pool_params_validate(&p, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "params.mu_roll: must be >= 0");
	p = pool_default_params();
	p.e_cushion = 1.5;
	assert_int_equal(pool_params_validate(&p, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "params.e_cushion: must be in [0, 1]");
	p = pool_default_params();
	p.ball_mass = 0.0;
	assert_int_equal(pool_params_validate(&p, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "params.ball_mass: must be > 0");
	assert_int_equal(pool_params_validate(&p, NULL), POOL_ERR_INVALID_ARGUMENT);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_presets), cmocka_unit_test(test_defaults), cmocka_unit_test(test_validation)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
