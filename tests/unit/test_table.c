// Table presets, default parameters and validation messages.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

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
	assert_int_equal(t.pockets, POOL_POCKETS_JAWS);
	assert_int_equal(pool_table_preset("pool", &t), POOL_ERR_UNKNOWN_PRESET);
	pool_table_def d = pool_default_table_def();
	assert_true(d.length == 2.54 && d.cushion_height == 0.03629);
	// WPA's cut angles (142 and 104 degrees) and the jaws.
	assert_int_equal(d.pockets, POOL_POCKETS_JAWS);
	assert_true(fabs(d.corner_cut_angle * 180.0 / M_PI - 142.0) < 1e-12 && fabs(d.side_cut_angle * 180.0 / M_PI - 104.0) < 1e-12);
	assert_true(d.corner_jaw_radius > 0.0 && d.side_jaw_radius > 0.0 && d.corner_hole_radius > 0.0);
	// Snooker (WPBSA 3569 x 1778 mm) and carom (UMB 2840 x 1420 mm, nose 37 mm, no pockets), with
	// their balls.
	pool_params p;
	assert_int_equal(pool_table_preset("snooker", &t), POOL_OK);
	assert_true(t.length == 3.569 && t.width == 1.778 && t.pockets == POOL_POCKETS_JAWS);
	assert_int_equal(pool_params_preset("snooker", &p), POOL_OK);
	assert_true(p.ball_radius == 0.02625);
	assert_int_equal(pool_table_preset("carom", &t), POOL_OK);
	assert_true(t.length == 2.84 && t.width == 1.42 && t.cushion_height == 0.037 && t.pockets == POOL_POCKETS_NONE);
	assert_int_equal(pool_params_preset("carom", &p), POOL_OK);
	assert_true(p.ball_radius == 0.03075);
	assert_int_equal(pool_params_preset("wpa-8ft", &p), POOL_OK);
	assert_true(p.ball_radius == 0.028575);
	assert_int_equal(pool_params_preset("billiards", &p), POOL_ERR_UNKNOWN_PRESET);
	// Every preset builds a simulation with its own balls.
	const char *names[] = {"wpa-9ft", "wpa-8ft", "wpa-7ft", "snooker", "carom"};
	for (int k = 0; k < 5; ++k) {
		pool_sim_def def = pool_default_sim_def();
		assert_int_equal(pool_table_preset(names[k], &def.table), POOL_OK);
		assert_int_equal(pool_params_preset(names[k], &def.params), POOL_OK);
		pool_sim *sim = NULL;
		pool_error err;
		if (pool_sim_create(&def, &sim, &err) != POOL_OK)
			fail_msg("%s: %s", names[k], err.message);
		pool_sim_destroy(sim);
	}
	assert_string_equal(pool_pockets_model_name(POOL_POCKETS_MOUTH_LINES), "mouth_lines");
	assert_int_equal(pool_pockets_model_from_name("jaws"), POOL_POCKETS_JAWS);
	assert_int_equal(pool_pockets_model_from_name("none"), POOL_POCKETS_NONE);
	assert_int_equal(pool_pockets_model_from_name("holes"), -1);
}

// Geometry that cannot be built is refused, the message naming the field.
static void expect_refused(pool_table_def t, const char *message) {
	pool_sim_def def = pool_default_sim_def();
	def.table = t;
	pool_sim *sim = NULL;
	pool_error err;
	assert_int_not_equal(pool_sim_create(&def, &sim, &err), POOL_OK);
	assert_null(sim);
	if (strncmp(err.message, message, strlen(message)) != 0)
		fail_msg("got \"%s\", want it to start with \"%s\"", err.message, message);
}

static void test_impossible_geometry(void **state) {
	(void)state;
	pool_table_def t = pool_default_table_def();
	t.side_mouth = 0.05; // narrower than a 57.15 mm ball
	expect_refused(t, "table.side_mouth: 0.05 m is narrower than a ball");
	t = pool_default_table_def();
	t.corner_jaw_radius = 0.5; // its tangent points lie beyond the hole
	expect_refused(t, "table.corner_jaw_radius:");
	t = pool_default_table_def();
	t.side_hole_radius = 0.01; t.side_shelf = 0.05; // a small hole far behind: the facings never reach it
	expect_refused(t, "table.side_hole_radius: the hole does not reach the facings");
	t = pool_default_table_def();
	t.corner_cut_angle = 170.0 * M_PI / 180.0; t.corner_shelf = 0.1; // facings closing to less than a ball
	expect_refused(t, "table.corner_cut_angle: the facings are");
	t = pool_default_table_def();
	t.side_cut_angle = 200.0 * M_PI / 180.0;
	expect_refused(t, "table.side_cut_angle: must be between 0 and 180 degrees");
	t = pool_default_table_def();
	t.corner_hole_radius = -1.0;
	expect_refused(t, "table.corner_hole_radius: must be > 0");
	t = pool_default_table_def();
	t.pockets = (pool_pockets_model)7;
	expect_refused(t, "table.pockets: unknown pocket model 7");
	// The thesis model reads none of the jaws' fields.
	t = pool_default_table_def();
	t.pockets = POOL_POCKETS_MOUTH_LINES;
	t.corner_jaw_radius = -1.0;
	assert_int_equal(pool_table_def_validate(&t, NULL), POOL_OK);
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
		cmocka_unit_test(test_presets), cmocka_unit_test(test_defaults), cmocka_unit_test(test_validation),
		cmocka_unit_test(test_impossible_geometry)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
