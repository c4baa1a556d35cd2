// The optional models of a scenario (docs/interfaces.md "Scenario file", docs/physics.md "Models")
// in the tools: "models" and the four model parameters read into the pool_sim_def, refusals that
// name the field, pool-rack's --model kinds (models_json.h), and the models written back into a
// result so they round-trip through the parser.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <jansson.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models_json.h"
#include "pool/scenario.h"

// One ball on the cloth, and the text that goes between "format" and "balls".
#define DOC(middle) \
	"{\"format\": \"libpool-scenario/1\", " middle " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}"

static int parse(const char *text, pool_scenario *s, char *err, size_t n) {
	return pool_scenario_parse(text, strlen(text), s, err, n);
}

static void assert_models(const pool_models *got, pool_cushion_model c, pool_ball_friction_model f,
                          pool_squirt_model q) {
	assert_int_equal(got->cushion, c);
	assert_int_equal(got->ball_ball_friction, f);
	assert_int_equal(got->squirt, q);
}

// Without "models" a scenario has the library's default laws (issue 25: the measured ones).
static void test_no_models_means_the_defaults(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	assert_int_equal(parse(DOC(""), &s, err, sizeof err), 0);
	assert_models(&s.def.models, POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_ALCIATORE, POOL_SQUIRT_NONE);
	const pool_models d = pool_default_models();
	assert_memory_equal(&s.def.models, &d, sizeof d);
	pool_scenario_free(&s);
	// An empty object is the defaults too, and so is the set "default".
	assert_int_equal(parse(DOC("\"models\": {},"), &s, err, sizeof err), 0);
	assert_memory_equal(&s.def.models, &d, sizeof d);
	pool_scenario_free(&s);
	assert_int_equal(parse(DOC("\"models\": \"default\","), &s, err, sizeof err), 0);
	assert_memory_equal(&s.def.models, &d, sizeof d);
	pool_scenario_free(&s);
}

// "thesis" (a string, or an object's "set") is the 2012 work's laws; an object's kinds override
// its set kind by kind.
static void test_model_sets(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	assert_int_equal(parse(DOC("\"models\": \"thesis\","), &s, err, sizeof err), 0);
	assert_models(&s.def.models, POOL_CUSHION_PETIT, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_NONE);
	pool_scenario_free(&s);
	assert_int_equal(parse(DOC("\"models\": {\"set\": \"thesis\"},"), &s, err, sizeof err), 0);
	assert_models(&s.def.models, POOL_CUSHION_PETIT, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_NONE);
	pool_scenario_free(&s);
	if (parse(DOC("\"models\": {\"squirt\": \"endmass\", \"set\": \"thesis\", \"cushion\": \"mathavan2010\"},"), &s,
	          err, sizeof err))
		fail_msg("%s", err);
	assert_models(&s.def.models, POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_ENDMASS);
	pool_scenario_free(&s);
	assert_int_equal(parse(DOC("\"models\": {\"set\": \"default\", \"ball_ball_friction\": \"constant\"},"), &s, err,
	                       sizeof err),
	                 0);
	assert_models(&s.def.models, POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_NONE);
	pool_scenario_free(&s);
}

static void test_every_model_is_read_by_name(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	const char *doc = DOC("\"models\": {\"cushion\": \"mathavan2010\", \"ball_ball_friction\": "
	                      "\"alciatore\", \"squirt\": \"endmass\"},");
	if (parse(doc, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_models(&s.def.models, POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_ALCIATORE, POOL_SQUIRT_ENDMASS);
	pool_scenario_free(&s);
	// Kinds not given keep the defaults; every name is accepted, the 2012 work's laws too.
	assert_int_equal(parse(DOC("\"models\": {\"squirt\": \"endmass\", \"cushion\": \"petit\"},"), &s,
	                       err, sizeof err), 0);
	assert_models(&s.def.models, POOL_CUSHION_PETIT, POOL_BALL_FRICTION_ALCIATORE, POOL_SQUIRT_ENDMASS);
	pool_scenario_free(&s);
}

static void test_model_parameters_are_read(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	const char *doc = DOC("\"params\": {\"throw_a\": 0.02, \"throw_b\": 0.2, \"throw_c\": 2.5,"
	                      " \"cue_end_mass\": 0.09, \"e_cushion_mathavan\": 0.9, \"mu_cushion_mathavan\": 0.3},");
	if (parse(doc, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_true(s.def.params.e_cushion_mathavan == 0.9 && s.def.params.mu_cushion_mathavan == 0.3);
	assert_true(s.def.params.throw_a == 0.02);
	assert_true(s.def.params.throw_b == 0.2);
	assert_true(s.def.params.throw_c == 2.5);
	assert_true(s.def.params.cue_end_mass == 0.09);
	pool_scenario_free(&s);
	// Missing ones take the library's defaults (docs/physics.md: 9.951e-3, 0.108, 1.088).
	assert_int_equal(parse(DOC(""), &s, err, sizeof err), 0);
	pool_params d = pool_default_params();
	assert_true(s.def.params.throw_a == d.throw_a && s.def.params.throw_b == d.throw_b);
	assert_true(s.def.params.throw_c == d.throw_c && s.def.params.cue_end_mass == d.cue_end_mass);
	assert_true(d.throw_a == 9.951e-3 && d.throw_b == 0.108 && d.throw_c == 1.088);
	pool_scenario_free(&s);
}

static void test_refusals_name_the_field(void **state) {
	(void)state;
	static const struct {
		const char *doc;
		const char *expect; // the whole message
	} cases[] = {
		{DOC("\"models\": {\"cushion\": \"foo\"},"),
		 "models.cushion: unknown model \"foo\" (petit, mathavan2010)"},
		{DOC("\"models\": {\"ball_ball_friction\": \"Alciatore\"},"),
		 "models.ball_ball_friction: unknown model \"Alciatore\" (constant, alciatore)"},
		{DOC("\"models\": {\"squirt\": \"\"},"), "models.squirt: unknown model \"\" (none, endmass)"},
		{DOC("\"models\": {\"squirt\": 1},"), "models.squirt: must be a string"},
		{DOC("\"models\": {\"cushion\": null},"), "models.cushion: must be a string"},
		{DOC("\"models\": {\"cushions\": \"petit\"},"), "models.cushions: unknown field"},
		{DOC("\"models\": {\"\": \"petit\"},"), "models: unknown field \"\""},
		{DOC("\"models\": \"mathavan2010\","), "models: unknown model set \"mathavan2010\" (default, thesis)"},
		{DOC("\"models\": [\"mathavan2010\"],"), "models: must be a model set name or an object"},
		{DOC("\"models\": 0,"), "models: must be a model set name or an object"},
		{DOC("\"models\": {\"set\": \"2012\"},"), "models.set: unknown model set \"2012\" (default, thesis)"},
		{DOC("\"models\": {\"set\": [\"thesis\"]},"), "models.set: must be a string"},
		{DOC("\"models\": {\"set\": \"thesis\", \"squirt\": \"no\"},"),
		 "models.squirt: unknown model \"no\" (none, endmass)"},
		// The echoed name is escaped: a control character cannot reach the terminal.
		{DOC("\"models\": {\"cushion\": \"\\u001b[2J\"},"),
		 "models.cushion: unknown model \"\\u001b[2J\" (petit, mathavan2010)"},
		{DOC("\"params\": {\"throw_q\": 1},"), "params.throw_q: unknown field"},
		{DOC("\"params\": {\"throw_a\": \"big\"},"), "params.throw_a: must be a number"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
		pool_scenario s;
		char err[256] = "";
		int r = parse(cases[i].doc, &s, err, sizeof err);
		bool owned = s.balls != NULL;
		pool_scenario_free(&s); // (a parse that wrongly succeeded owns balls)
		if (r != -1 || strcmp(err, cases[i].expect) != 0)
			fail_msg("case %zu: got %d \"%s\", expected \"%s\"", i, r, err, cases[i].expect);
		assert_false(owned);
	}
}

// The library's own range checks reach the user with the parameter named (docs/physics.md: finite,
// >= 0; cue_end_mass > 0).
static void test_parameter_ranges_are_the_librarys(void **state) {
	(void)state;
	static const char *const cases[][2] = {
		{DOC("\"params\": {\"throw_a\": -0.01},"), "params.throw_a"},
		{DOC("\"params\": {\"throw_b\": -1},"), "params.throw_b"},
		{DOC("\"params\": {\"throw_c\": -1},"), "params.throw_c"},
		{DOC("\"params\": {\"cue_end_mass\": 0},"), "params.cue_end_mass"},
		{DOC("\"params\": {\"cue_end_mass\": -0.1},"), "params.cue_end_mass"},
		{DOC("\"params\": {\"e_cushion_mathavan\": 1.1},"), "params.e_cushion_mathavan"},
		{DOC("\"params\": {\"mu_cushion_mathavan\": -0.1},"), "params.mu_cushion_mathavan"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
		pool_scenario s;
		char err[256] = "";
		int r = parse(cases[i][0], &s, err, sizeof err);
		pool_scenario_free(&s); // (a parse that wrongly succeeded owns balls)
		if (r != -1 || strncmp(err, cases[i][1], strlen(cases[i][1])) != 0 ||
		    err[strlen(cases[i][1])] != ':')
			fail_msg("case %zu: got %d \"%s\", expected \"%s: ...\"", i, r, err, cases[i][1]);
	}
}

static void test_kinds_by_name(void **state) {
	(void)state;
	pool_models m = {0};
	assert_int_equal(pool_models_set(&m, "cushion", "mathavan2010"), 0);
	assert_int_equal(m.cushion, POOL_CUSHION_MATHAVAN2010);
	assert_int_equal(pool_models_set(&m, "squirt", "endmass"), 0);
	assert_int_equal(pool_models_set(&m, "ball_ball_friction", "alciatore"), 0);
	assert_int_equal(m.ball_ball_friction, POOL_BALL_FRICTION_ALCIATORE);
	assert_int_equal(m.squirt, POOL_SQUIRT_ENDMASS);
	pool_models before = m;
	assert_int_equal(pool_models_set(&m, "cushion", "rubber"), -2);
	assert_int_equal(pool_models_set(&m, "cushion", NULL), -2);
	assert_int_equal(pool_models_set(&m, "spin", "petit"), -1);
	assert_int_equal(pool_models_set(&m, NULL, "petit"), -1);
	assert_memory_equal(&m, &before, sizeof m);

	char names[128];
	pool_model_names("cushion", names, sizeof names);
	assert_string_equal(names, "petit, mathavan2010");
	pool_model_names("ball_ball_friction", names, sizeof names);
	assert_string_equal(names, "constant, alciatore");
	pool_model_names("squirt", names, sizeof names);
	assert_string_equal(names, "none, endmass");
	pool_model_names(NULL, names, sizeof names);
	assert_string_equal(names, "cushion, ball_ball_friction, squirt");
	// Cut to fit, at a whole name.
	char small[12];
	pool_model_names("cushion", small, sizeof small);
	assert_string_equal(small, "petit");
	int i = 0;
	while (pool_model_kinds[i])
		++i;
	assert_int_equal(i, 3);
	pool_model_set_names(names, sizeof names);
	assert_string_equal(names, "default, thesis");
}

// --models values: sets and names joined with '+', left to right; a bad part names itself and
// changes nothing.
static void test_models_spec(void **state) {
	(void)state;
	char err[512];
	pool_models m = pool_default_models();
	assert_int_equal(pool_models_parse_spec(&m, "thesis", err, sizeof err), 0);
	assert_models(&m, POOL_CUSHION_PETIT, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_NONE);
	assert_int_equal(pool_models_parse_spec(&m, "endmass+mathavan2010", err, sizeof err), 0);
	assert_models(&m, POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_CONSTANT, POOL_SQUIRT_ENDMASS);
	assert_int_equal(pool_models_parse_spec(&m, "endmass+default", err, sizeof err), 0);
	assert_models(&m, POOL_CUSHION_MATHAVAN2010, POOL_BALL_FRICTION_ALCIATORE, POOL_SQUIRT_NONE);
	const pool_models before = m;
	assert_int_equal(pool_models_parse_spec(&m, "thesis+rubber", err, sizeof err), -1);
	assert_string_equal(err, "'rubber' is no model set (default, thesis) nor model (petit, mathavan2010, constant, "
	                         "alciatore, none, endmass)");
	assert_memory_equal(&m, &before, sizeof m);
	assert_int_equal(pool_models_parse_spec(&m, "", err, sizeof err), -1);
	assert_int_equal(pool_models_parse_spec(&m, "thesis+", err, sizeof err), -1);
	assert_string_equal(err, "'' is no model set (default, thesis) nor model (petit, mathavan2010, constant, "
	                         "alciatore, none, endmass)");
	assert_memory_equal(&m, &before, sizeof m);
	assert_true(pool_models_apply(&m, "alciatore"));
	assert_false(pool_models_apply(&m, "Thesis"));
	assert_false(pool_models_apply(&m, NULL));
}

static json_t *result_of(const char *doc, pool_scenario *s) {
	char err[256];
	if (parse(doc, s, err, sizeof err) != 0)
		fail_msg("%s", err);
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	if (pool_scenario_setup(s, &sim, &e) != POOL_OK)
		fail_msg("%s", e.message);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	pool_result_options ro = {.def = &s->def};
	char *text = pool_result_json(sim, &ro);
	assert_non_null(text);
	json_error_t jerr;
	json_t *root = json_loads(text, 0, &jerr);
	assert_non_null(root);
	free(text);
	pool_sim_destroy(sim);
	return root;
}

// A result says which models made it, by the names a scenario uses, so its "models" object put
// into a scenario selects the same models again; every result carries them, the defaults too
// (a reader whose defaults differ still knows the laws).
static void test_result_carries_the_models(void **state) {
	(void)state;
	pool_scenario s, again;
	json_t *root = result_of(
		"{\"format\": \"libpool-scenario/1\", \"models\": {\"cushion\": \"mathavan2010\","
		" \"squirt\": \"endmass\"}, \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}],"
		" \"strike\": {\"ball\": 0, \"speed\": 1.5, \"phi\": 10, \"a\": 0.01}}",
		&s);
	json_t *models = json_object_get(root, "models");
	assert_non_null(models);
	assert_string_equal(json_string_value(json_object_get(models, "cushion")), "mathavan2010");
	assert_string_equal(json_string_value(json_object_get(models, "ball_ball_friction")), "alciatore");
	assert_string_equal(json_string_value(json_object_get(models, "squirt")), "endmass");
	assert_int_equal(json_object_size(models), 3);

	json_t *doc = json_pack("{s:s, s:O, s:[{s:i, s:[f,f]}]}", "format", "libpool-scenario/1",
	                        "models", models, "balls", "id", 0, "pos", 0.5, 0.5);
	char *text = json_dumps(doc, 0);
	char err[256];
	if (parse(text, &again, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_memory_equal(&again.def.models, &s.def.models, sizeof s.def.models);
	free(text);
	json_decref(doc);
	json_decref(root);
	pool_scenario_free(&again);
	pool_scenario_free(&s);

	root = result_of(DOC(""), &s);
	models = json_object_get(root, "models");
	assert_string_equal(json_string_value(json_object_get(models, "cushion")), "mathavan2010");
	assert_string_equal(json_string_value(json_object_get(models, "ball_ball_friction")), "alciatore");
	assert_string_equal(json_string_value(json_object_get(models, "squirt")), "none");
	assert_non_null(json_object_get(root, "table"));
	json_decref(root);
	pool_scenario_free(&s);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_no_models_means_the_defaults),
		cmocka_unit_test(test_model_sets),
		cmocka_unit_test(test_every_model_is_read_by_name),
		cmocka_unit_test(test_model_parameters_are_read),
		cmocka_unit_test(test_refusals_name_the_field),
		cmocka_unit_test(test_parameter_ranges_are_the_librarys),
		cmocka_unit_test(test_kinds_by_name),
		cmocka_unit_test(test_models_spec),
		cmocka_unit_test(test_result_carries_the_models),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
