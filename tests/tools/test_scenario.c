// Unit tests of the scenario parser, the JSON number formatting, the result writer, the escaping
// of echoed input and the input size limit.
#define _XOPEN_SOURCE 700 // mkstemp, fdopen, unlink
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "json_writer.h"
#include "read_input.h"
#include "pool/scenario.h"
#include "text_escape.h"

#define R 0.028575

static int parse(const char *text, pool_scenario *s, char *err, size_t n) {
	return pool_scenario_parse(text, strlen(text), s, err, n);
}

static void test_minimal_scenario_takes_defaults(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	const char *doc = "{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 3, \"pos\": [1, 0.5]}]}";
	assert_int_equal(parse(doc, &s, err, sizeof err), 0);
	pool_sim_def d = pool_default_sim_def();
	assert_memory_equal(&s.def.table, &d.table, sizeof d.table);
	assert_memory_equal(&s.def.params, &d.params, sizeof d.params);
	assert_true(s.def.airborne == d.airborne);
	assert_true(s.def.max_time == d.max_time);
	assert_int_equal(s.def.max_events, d.max_events);
	assert_int_equal(s.ball_count, 1);
	assert_int_equal(s.balls[0].id, 3);
	assert_true(s.balls[0].pos.x == 1.0 && s.balls[0].pos.y == 0.5);
	assert_true(s.balls[0].pos.z == d.params.ball_radius);
	assert_int_equal(s.balls[0].motion, POOL_MOTION_STATIONARY);
	assert_false(s.has_strike);
	pool_scenario_free(&s);
	assert_null(s.balls);
	pool_scenario_free(&s); // twice is fine
}

static void test_fields_are_read(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	const char *doc =
		"{\"format\": \"libpool-scenario/1\","
		" \"table\": {\"preset\": \"wpa-7ft\", \"side_mouth\": 0.13},"
		" \"params\": {\"mu_ball\": 0.05, \"ball_radius\": 0.03125},"
		" \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]},"
		"             {\"id\": 1, \"pos\": [1.0, 0.5, 0.03125], \"vel\": [0.5, 0, 0], \"omega\": [0, 16, 0]}],"
		" \"strike\": {\"ball\": 0, \"speed\": 2, \"phi\": 90, \"theta\": 10, \"a\": 0.01, \"b\": -0.005},"
		" \"options\": {\"airborne\": false, \"max_time\": 30, \"max_events\": 777}}";
	if (parse(doc, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	pool_table_def t7;
	assert_int_equal(pool_table_preset("wpa-7ft", &t7), POOL_OK);
	assert_true(s.def.table.length == t7.length && s.def.table.width == t7.width);
	assert_true(s.def.table.side_mouth == 0.13);
	assert_true(s.def.params.mu_ball == 0.05);
	assert_true(s.def.params.mu_slide == pool_default_params().mu_slide);
	assert_true(s.balls[0].pos.z == 0.03125); // a 2D position sits on the cloth: z = R
	assert_int_equal(s.balls[1].motion, POOL_MOTION_ROLLING); // v = R w (exact in binary): no slip
	assert_true(s.has_strike);
	assert_int_equal(s.strike_ball, 0);
	assert_true(s.strike.speed == 2.0);
	assert_true(fabs(s.strike.phi - 3.14159265358979323846 / 2) < 1e-15);
	assert_true(fabs(s.strike.theta - 10 * 3.14159265358979323846 / 180) < 1e-15);
	assert_true(s.strike.a == 0.01 && s.strike.b == -0.005);
	assert_false(s.def.airborne);
	assert_true(s.def.max_time == 30.0);
	assert_int_equal(s.def.max_events, 777);
	pool_scenario_free(&s);

	// Airborne mode is read; an engine that cannot simulate it yet must say so for that field.
	const char *airborne = "{\"format\": \"libpool-scenario/1\", \"options\": {\"airborne\": true},"
	                       " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}";
	if (parse(airborne, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_true(s.def.airborne);
	pool_scenario_free(&s);
}

#define AIR_HEAD "{\"format\": \"libpool-scenario/1\", \"options\": {\"airborne\": true}, "
#define PLANAR_HEAD "{\"format\": \"libpool-scenario/1\", "

// options.airborne = true: 3D positions and velocities are read and checked by the parser itself
// (the library refuses airborne simulations until it implements them; setup says so).
// The table's pocket model and geometry (docs/interfaces.md), a preset's balls as the params'
// defaults, and refusals naming the field.
static void test_table_geometry_is_read(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	const char *doc = "{\"format\": \"libpool-scenario/1\","
	                  " \"table\": {\"preset\": \"wpa-8ft\", \"corner_cut_angle\": 143, \"side_jaw_radius\": 0.01,"
	                  " \"corner_shelf\": 0.03, \"side_hole_radius\": 0.07},"
	                  " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}";
	if (parse(doc, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_int_equal(s.def.table.pockets, POOL_POCKETS_JAWS);
	assert_true(fabs(s.def.table.corner_cut_angle - 143 * 3.14159265358979323846 / 180) < 1e-15);
	assert_true(s.def.table.side_jaw_radius == 0.01 && s.def.table.corner_shelf == 0.03 && s.def.table.side_hole_radius == 0.07);
	pool_scenario_free(&s);
	// The thesis model by name; snooker's balls come with its table, and params override them.
	const char *thesis = "{\"format\": \"libpool-scenario/1\", \"table\": {\"pockets\": \"mouth_lines\"},"
	                     " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}";
	if (parse(thesis, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_int_equal(s.def.table.pockets, POOL_POCKETS_MOUTH_LINES);
	pool_scenario_free(&s);
	const char *snooker = "{\"format\": \"libpool-scenario/1\", \"table\": {\"preset\": \"snooker\"},"
	                      " \"params\": {\"mu_ball\": 0.05}, \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}";
	if (parse(snooker, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_true(s.def.params.ball_radius == 0.02625 && s.def.params.mu_ball == 0.05 && s.def.table.length == 3.569);
	assert_true(s.balls[0].pos.z == 0.02625);
	pool_scenario_free(&s);
	const struct {
		const char *table, *message;
	} bad[] = {
		{"{\"pockets\": \"holes\"}", "table.pockets: must be \"jaws\", \"mouth_lines\" or \"none\""},
		{"{\"side_cut_angle\": 190}", "table.side_cut_angle: must be between 0 and 180 degrees"},
		{"{\"corner_jaw_radius\": 0.5}", "table.corner_jaw_radius:"},
		{"{\"side_mouth\": 0.05}", "table.side_mouth: 0.05 m is narrower than a ball"},
		{"{\"corner_hole_radius\": \"big\"}", "table.corner_hole_radius: must be a number"},
	};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
		char text[512];
		snprintf(text, sizeof text, "{\"format\": \"libpool-scenario/1\", \"table\": %s, \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		         bad[k].table);
		assert_int_equal(parse(text, &s, err, sizeof err), -1);
		if (strncmp(err, bad[k].message, strlen(bad[k].message)) != 0)
			fail_msg("%s: got \"%s\"", bad[k].table, err);
	}
}

static void test_airborne_balls_are_read(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	const char *doc = AIR_HEAD
		"\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.2], \"vel\": [1.5, -0.5, 2.0], \"omega\": [0, 30, 0]},"
		"            {\"id\": 1, \"pos\": [0.5, 0.5, 0.028575]},"
		"            {\"id\": 2, \"pos\": [1.0, 0.5, 0.0285749995]},"
		"            {\"id\": 3, \"pos\": [1.5, 0.5], \"vel\": [0, 0, 1]},"
		"            {\"id\": 4, \"pos\": [2.0, 0.5]}],"
		" \"strike\": {\"ball\": 4, \"speed\": 3, \"theta\": 70, \"b\": 0.01}}";
	if (parse(doc, &s, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_true(s.def.airborne);
	assert_int_equal(s.ball_count, 5);
	// ball 0 is straight above ball 1, 0.171 m apart: no overlap in 3D
	assert_true(s.balls[0].pos.z == 0.2);
	assert_true(s.balls[0].vel.x == 1.5 && s.balls[0].vel.y == -0.5 && s.balls[0].vel.z == 2.0);
	assert_int_equal(s.balls[0].motion, POOL_MOTION_AIRBORNE);
	assert_int_equal(s.balls[1].motion, POOL_MOTION_STATIONARY);
	assert_true(s.balls[2].pos.z == R); // within the tolerance below the cloth: put on it
	assert_int_equal(s.balls[2].motion, POOL_MOTION_STATIONARY);
	assert_true(s.balls[3].pos.z == R && s.balls[3].vel.z == 1.0); // a ball thrown up from the cloth
	assert_int_equal(s.balls[3].motion, POOL_MOTION_AIRBORNE);
	assert_true(s.has_strike);
	assert_true(fabs(s.strike.theta - 70 * 3.14159265358979323846 / 180) < 1e-15);

	// The parse does not depend on the library; the library simulates airborne motion, so setup
	// succeeds and the shot runs.
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	assert_int_equal(pool_scenario_setup(&s, &sim, &e), POOL_OK);
	assert_int_equal(pool_sim_run(sim), POOL_OK);
	pool_sim_destroy(sim);
	pool_scenario_free(&s);
}

static void test_airborne_refusals_name_the_field(void **state) {
	(void)state;
	static const struct {
		const char *doc;
		const char *expect;
	} cases[] = {
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.02]}]}", "balls[0].pos: below the cloth"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}, {\"id\": 1, \"pos\": [1.5, 0.5, 0.0285]}]}",
		 "balls[1].pos: below the cloth"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, -1]}]}", "balls[0].pos: below the cloth"},
		// 3D interpenetration: ball 1 sits 0.05 m above ball 0 (< 2R)
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}, {\"id\": 1, \"pos\": [0.5, 0.5, 0.078575]}]}",
		 "balls[1].pos: overlaps ball 0 by 0.00715 m"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.1]}, {\"id\": 1, \"pos\": [0.52, 0.52, 0.12]}]}",
		 "balls[1].pos: overlaps ball 0"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}, {\"id\": 0, \"pos\": [1.5, 0.5, 0.3]}]}",
		 "balls[1].id: duplicate id 0"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}, {\"id\": 1, \"pos\": [3.5, 0.5, 0.3]}]}",
		 "balls[1].pos: off the table"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.3], \"vel\": [0, 0, 150]}]}",
		 "balls[0].vel: speed above"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.3], \"vel\": [0]}]}",
		 "balls[0].vel: must be an array of 2 or 3 numbers"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.3, 1]}]}", "balls[0].pos: must be an array"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 1e300]}]}", "balls[0].pos[2]: "},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}], \"strike\": {\"ball\": 0, \"speed\": 2, \"theta\": 90}}",
		 "strike.theta: must be in [0, 90) degrees"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}], \"strike\": {\"ball\": 0, \"speed\": 2, \"theta\": 120}}",
		 "strike.theta"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.2]}], \"strike\": {\"ball\": 0, \"speed\": 2}}",
		 "strike.ball: ball 0 must be at rest on the cloth"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5], \"vel\": [0, 0, 1]}], \"strike\": {\"ball\": 0, \"speed\": 2}}",
		 "strike.ball: ball 0 must be at rest on the cloth"},
		{AIR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}], \"strike\": {\"ball\": 0, \"speed\": 1, \"a\": 0.02, \"b\": 0.021}}",
		 "strike"},
		{AIR_HEAD "\"params\": {\"e_table\": -1}, \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.2]}]}",
		 "params.e_table"},
		// Planar mode keeps the library's rules exactly: z must be R, no vertical velocity.
		{PLANAR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.2]}]}", "balls[0].pos: z must be the ball radius"},
		{PLANAR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5], \"vel\": [1, 0, 0.5]}]}", "balls[0].vel: vertical velocity"},
		{PLANAR_HEAD "\"options\": {\"airborne\": false}, \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5, 0.0285]}]}",
		 "balls[0].pos: z must be the ball radius"},
		{PLANAR_HEAD "\"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}], \"strike\": {\"ball\": 0, \"speed\": 2, \"theta\": 90}}",
		 "strike.theta: must be in [0, 90) degrees"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
		pool_scenario s;
		char err[256] = "";
		int r = parse(cases[i].doc, &s, err, sizeof err);
		if (r != -1 || strncmp(err, cases[i].expect, strlen(cases[i].expect)) != 0)
			fail_msg("case %zu: got %d \"%s\", expected a message starting \"%s\"", i, r, err,
			         cases[i].expect);
		assert_null(s.balls);
		assert_int_equal(s.ball_count, 0);
	}
}

static void test_errors_name_the_field(void **state) {
	(void)state;
	static const struct {
		const char *doc;
		const char *expect;
	} cases[] = {
		{"{", "(document): malformed JSON at line 1"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}], \"x\": 1}",
		 "x: unknown field"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]},"
		 " {\"id\": 1, \"pos\": [0.55415, 0.5]}]}",
		 "balls[1].pos: overlaps ball 0 by 0.003 m"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]},"
		 " {\"id\": 0, \"pos\": [1.5, 0.5]}]}",
		 "balls[1].id"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [3.5, 0.5]}]}",
		 "balls[0]"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}],"
		 " \"strike\": {\"ball\": 0, \"speed\": 1, \"a\": 0.02, \"b\": 0.021}}",
		 "strike"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}],"
		 " \"strike\": {\"ball\": 4, \"speed\": 1}}",
		 "strike.ball: no ball has id 4"},
		{"{\"format\": \"libpool-scenario/1\", \"params\": {\"mu_roll\": -0.01},"
		 " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		 "params.mu_roll"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 1e300]}]}",
		 "balls[0].pos[1]: "},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5], \"vel\": \"fast\"}]}",
		 "balls[0].vel: must be an array"},
		{"{\"format\": \"libpool-scenario/0\", \"balls\": []}", "format: expected"},
		{"{\"format\": \"libpool-scenario/1\", \"table\": {\"preset\": 9},"
		 " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		 "table.preset: must be a string"},
		{"{\"format\": \"libpool-scenario/1\", \"options\": {\"max_events\": 0},"
		 " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		 "options.max_events"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
		pool_scenario s;
		char err[256] = "";
		int r = parse(cases[i].doc, &s, err, sizeof err);
		if (r != -1 || strncmp(err, cases[i].expect, strlen(cases[i].expect)) != 0)
			fail_msg("case %zu: got %d \"%s\", expected a message starting \"%s\"", i, r, err,
			         cases[i].expect);
		assert_null(s.balls);
		assert_int_equal(s.ball_count, 0);
	}
}

static void test_tiny_error_buffer_is_safe(void **state) {
	(void)state;
	pool_scenario s;
	char err[8];
	assert_int_equal(parse("{\"nope\": 1}", &s, err, sizeof err), -1);
	assert_int_equal(strlen(err), 7);
	assert_int_equal(parse("{\"nope\": 1}", &s, NULL, 0), -1);
}

static void test_load_file_names_the_path(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	assert_int_equal(pool_scenario_load_file("/nonexistent/x.json", &s, err, sizeof err), -1);
	assert_non_null(strstr(err, "/nonexistent/x.json: "));
}

// Echoed input is printable: controls, invalid UTF-8 and invisible characters escaped, long text
// cut at a character boundary with its length.
static void test_escape_text(void **state) {
	(void)state;
	char out[POOL_ESCAPE_SHORT];
#define CASE(in, expect) {in, sizeof in - 1, expect}
	static const struct {
		const char *in;
		size_t len;
		const char *expect;
	} cases[] = {
		CASE("plain key", "plain key"),
		CASE("a\x1b[31mb", "a\\u001b[31mb"),
		CASE("line\nbreak\r\t", "line\\u000abreak\\u000d\\u0009"),
		CASE("nul\0after", "nul\\u0000after"),
		CASE("del\x7f", "del\\u007f"),
		CASE("c1 \xc2\x9b csi", "c1 \\u009b csi"),
		CASE("raw \x9b byte", "raw \\x9b byte"),
		CASE("bad \xff\xc3(", "bad \\xff\\xc3("),
		CASE("overlong \xc0\xaf", "overlong \\xc0\\xaf"),
		CASE("surrogate \xed\xa0\x80", "surrogate \\xed\\xa0\\x80"),
		CASE("truncated \xe2\x82", "truncated \\xe2\\x82"),
		CASE("bidi \xe2\x80\xae!", "bidi \\u202e!"),
		CASE("bom \xef\xbb\xbf", "bom \\ufeff"),
		CASE("tag \xf3\xa0\x80\x81", "tag \\U000e0001"),
		CASE("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8e\xb1", "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8e\xb1"),
		CASE("back\\slash \"q\"", "back\\slash \"q\""),
		CASE("", ""),
	};
#undef CASE
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
		assert_string_equal(pool_escape_text(out, sizeof out, cases[i].in, cases[i].len), cases[i].expect);
	// 10 kB: cut to the buffer, ending with the input's length.
	char big[10240];
	memset(big, 'k', sizeof big);
	pool_escape_text(out, sizeof out, big, sizeof big);
	assert_int_equal(strlen(out), sizeof out - 1);
	assert_non_null(strstr(out, "kkk...(10240 bytes)"));
	// Escapes and UTF-8 sequences are never split by the cut.
	char escs[300];
	for (size_t i = 0; i < sizeof escs; ++i)
		escs[i] = (i % 3 == 0) ? '\x1b' : 'x';
	pool_escape_text(out, sizeof out, escs, sizeof escs);
	const char *suffix = strstr(out, "...(300 bytes)");
	assert_non_null(suffix);
	assert_int_equal(suffix[strlen("...(300 bytes)")], '\0');
	// Before the suffix: whole "\u001b" escapes and 'x's only, in the input's pattern.
	size_t k = 0;
	for (const char *p = out; p < suffix; ++k) {
		if (k % 3 == 0) {
			assert_memory_equal(p, "\\u001b", 6);
			p += 6;
		} else {
			assert_int_equal(*p, 'x');
			p += 1;
		}
	}
	char euro[100];
	for (size_t i = 0; i + 3 <= sizeof euro; i += 3)
		memcpy(euro + i, "\xe2\x82\xac", 3);
	char small[20];
	pool_escape_text(small, sizeof small, euro, 99);
	assert_string_equal(small, "\xe2\x82\xac\xe2\x82\xac...(99 bytes)"); // 19 bytes: no third euro sign
	// Too small for the suffix: just cut.
	char tiny[4];
	assert_string_equal(pool_escape_str(tiny, sizeof tiny, "\x1b[2J"), "");
	assert_string_equal(pool_escape_str(tiny, sizeof tiny, "abcdef"), "abc");
}

// The scenario parser escapes what it echoes (unknown keys, a preset name, jansson's quotes).
static void test_echoed_input_is_escaped(void **state) {
	(void)state;
	pool_scenario s;
	char err[512];
	static const struct {
		const char *doc;
		const char *expect;
	} cases[] = {
		{"{\"format\": \"libpool-scenario/1\", \"a\\u001bb\": 1, \"balls\": []}", "a\\u001bb: unknown field"},
		{"{\"format\": \"libpool-scenario/1\", \"params\": {\"x\\ny\": 1}, \"balls\": []}",
		 "params.x\\u000ay: unknown field"},
		{"{\"format\": \"libpool-scenario/1\", \"table\": {\"preset\": \"\\u001b[2J\"}, \"balls\": []}",
		 "table.preset: unknown preset \"\\u001b[2J\" (wpa-9ft, wpa-8ft, wpa-7ft, snooker, carom)"},
		{"{\"format\": \"libpool-scenario/1\", \"\x1b[2J\": 1}",
		 "(document): malformed JSON at line 1, column 34: control character 0x1b near '\"'"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
		assert_int_equal(parse(cases[i].doc, &s, err, sizeof err), -1);
		assert_string_equal(err, cases[i].expect);
	}
}

// pool_read_input and pool_scenario_load_file_limit: at most the limit, else a message naming
// the input; --max-input values.
static void test_input_limit(void **state) {
	(void)state;
	char path[] = "/tmp/test_scenario_limit_XXXXXX";
	int fd = mkstemp(path);
	assert_true(fd >= 0);
	const char *doc = "{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [1, 0.5]}]}";
	size_t n = strlen(doc);
	FILE *f = fdopen(fd, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(doc, 1, n, f), n);
	fclose(f);
	char *data = NULL;
	size_t length = 0;
	char err[512];
	assert_int_equal(pool_read_input(path, n, &data, &length, err, sizeof err), 0);
	assert_int_equal(length, n);
	assert_memory_equal(data, doc, n);
	assert_int_equal(data[n], '\0');
	free(data);
	assert_int_equal(pool_read_input(path, n - 1, &data, &length, err, sizeof err), -1);
	assert_null(data);
	char expect[600];
	snprintf(expect, sizeof expect, "%s: input is larger than the limit of %zu bytes (%zu bytes)", path, n - 1, n);
	assert_string_equal(err, expect);
	pool_scenario s;
	assert_int_equal(pool_scenario_load_file_limit(path, n, &s, err, sizeof err), 0);
	pool_scenario_free(&s);
	assert_int_equal(pool_scenario_load_file_limit(path, 10, &s, err, sizeof err), -1);
	assert_non_null(strstr(err, ": input is larger than the limit of 10 bytes"));
	// A device never ends: read up to the limit, then refused.
	assert_int_equal(pool_read_input("/dev/zero", 1000000, &data, &length, err, sizeof err), -1);
	assert_string_equal(err, "/dev/zero: input is larger than the limit of 1000000 bytes");
	assert_int_equal(pool_scenario_load_file("/dev/zero", &s, err, sizeof err), -1);
	assert_string_equal(err, "/dev/zero: input is larger than the limit of 67108864 bytes");
	unlink(path);

	size_t v = 0;
	assert_true(pool_parse_byte_count("1000", &v) && v == 1000);
	assert_true(pool_parse_byte_count("512k", &v) && v == 512u << 10);
	assert_true(pool_parse_byte_count("64M", &v) && v == POOL_INPUT_DEFAULT_MAX);
	assert_true(pool_parse_byte_count("64MiB", &v) && v == POOL_INPUT_DEFAULT_MAX);
	assert_true(pool_parse_byte_count("1g", &v) && v == (size_t)1 << 30);
	static const char *const bad[] = {"", "0", "0k", "-1", "+1", " 1", "1 ", "1.5", "1e6", "12q", "1kk",
	                                  "1KB", "1Mi", "99999999999999999999999", "17179869184G"};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
		v = 7;
		assert_false(pool_parse_byte_count(bad[i], &v));
		assert_int_equal(v, 7);
	}
}

static void test_numbers_round_trip_with_few_digits(void **state) {
	(void)state;
	const double values[] = {0.1, 1.0 / 3.0, 2.54, -0.028575, 1e-300, 5e-324, DBL_MAX, -2.5e17,
	                         0.1 + 0.2, 123456789.123456789, 1.0 - DBL_EPSILON};
	char text[32];
	for (size_t i = 0; i < sizeof values / sizeof values[0]; ++i) {
		pool_jw_format_double(values[i], text);
		assert_true(strtod(text, NULL) == values[i]);
	}
	pool_jw_format_double(0.1, text);
	assert_string_equal(text, "0.1");
	pool_jw_format_double(0.1 + 0.2, text);
	assert_string_equal(text, "0.30000000000000004");
	pool_jw_format_double(NAN, text);
	assert_string_equal(text, "null");
}

static void test_writer_escapes_and_nests(void **state) {
	(void)state;
	pool_jw w;
	pool_jw_init(&w, false);
	pool_jw_object(&w, false);
	pool_jw_key(&w, "s");
	pool_jw_string(&w, "a\"b\\c\n\x01");
	pool_jw_key(&w, "v");
	pool_jw_vec3(&w, (pool_vec3){1, -2.5, 0});
	pool_jw_key(&w, "e");
	pool_jw_array(&w, false);
	pool_jw_end(&w, ']');
	pool_jw_end(&w, '}');
	char *text = pool_jw_finish(&w);
	assert_string_equal(text, "{\"s\":\"a\\\"b\\\\c\\n\\u0001\",\"v\":[1,-2.5,0],\"e\":[]}\n");
	free(text);
}

static const char shot_doc[] =
	"{\"format\": \"libpool-scenario/1\","
	" \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635]}, {\"id\": 1, \"pos\": [1.905, 0.7]},"
	"             {\"id\": 2, \"pos\": [2.0, 1.0]}],"
	" \"strike\": {\"ball\": 0, \"speed\": 2.5, \"phi\": 3, \"a\": 0.005, \"b\": 0.01}}";

static char *simulate(pool_sim **sim, const pool_scenario *s, double dt, bool pretty) {
	pool_error e = {{0}};
	pool_result r = pool_scenario_setup(s, sim, &e);
	if (r != POOL_OK)
		fail_msg("setup: %s", e.message);
	assert_int_equal(pool_sim_run(*sim), POOL_OK);
	pool_result_options o = {.sample_dt = dt, .pretty = pretty, .def = &s->def};
	char *text = pool_result_json(*sim, &o);
	assert_non_null(text);
	return text;
}

static void test_result_document(void **state) {
	(void)state;
	pool_scenario s;
	char err[256];
	assert_int_equal(parse(shot_doc, &s, err, sizeof err), 0);
	pool_sim *sim = NULL;
	char *a = simulate(&sim, &s, 0.0, false);
	// Reusing the simulation (reset path) gives the same bytes: the shot is deterministic.
	char *b = simulate(&sim, &s, 0.0, false);
	assert_string_equal(a, b);
	char *pretty = simulate(&sim, &s, 0.05, true);

	json_error_t jerr;
	json_t *doc = json_loads(a, 0, &jerr);
	assert_non_null(doc);
	assert_string_equal(json_string_value(json_object_get(doc, "format")), "libpool-result/1");
	int count = 0;
	pool_sim_events(sim, &count);
	json_t *events = json_object_get(doc, "events");
	assert_int_equal((int)json_array_size(events), count);
	assert_int_equal(json_integer_value(json_object_get(json_object_get(doc, "stats"), "events")), count);
	assert_int_equal(json_array_size(json_object_get(doc, "final")), 3);
	json_t *first = json_array_get(events, 0);
	assert_string_equal(json_string_value(json_object_get(first, "type")), "strike");
	double last = 0.0;
	size_t i;
	json_t *ev;
	json_array_foreach(events, i, ev) {
		double t = json_number_value(json_object_get(ev, "t"));
		assert_true(t >= last);
		last = t;
		assert_int_equal(json_array_size(json_object_get(ev, "after")),
		                 json_array_size(json_object_get(ev, "balls")));
	}
	assert_null(json_object_get(doc, "samples"));

	json_t *sampled = json_loads(pretty, 0, &jerr);
	assert_non_null(sampled);
	json_t *balls = json_object_get(json_object_get(sampled, "samples"), "balls");
	assert_int_equal(json_array_size(balls), 3);
	json_t *cue = json_array_get(balls, 0);
	assert_int_equal(json_array_size(json_object_get(cue, "t")), json_array_size(json_object_get(cue, "pos")));
	assert_true(json_array_size(json_object_get(cue, "t")) > 10);
	// The document without samples equals the sampled one minus "samples".
	json_object_del(sampled, "samples");
	assert_true(json_equal(sampled, doc));

	json_decref(sampled);
	json_decref(doc);
	free(a);
	free(b);
	free(pretty);
	pool_sim_destroy(sim);
	pool_scenario_free(&s);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_minimal_scenario_takes_defaults),
		cmocka_unit_test(test_fields_are_read),
		cmocka_unit_test(test_table_geometry_is_read),
		cmocka_unit_test(test_airborne_balls_are_read),
		cmocka_unit_test(test_airborne_refusals_name_the_field),
		cmocka_unit_test(test_errors_name_the_field),
		cmocka_unit_test(test_tiny_error_buffer_is_safe),
		cmocka_unit_test(test_load_file_names_the_path),
		cmocka_unit_test(test_escape_text),
		cmocka_unit_test(test_echoed_input_is_escaped),
		cmocka_unit_test(test_input_limit),
		cmocka_unit_test(test_numbers_round_trip_with_few_digits),
		cmocka_unit_test(test_writer_escapes_and_nests),
		cmocka_unit_test(test_result_document),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
