// In-process tests of the libpool <-> pool_lcm conversion (tools/lcm/lcm_convert.c): messages
// built from a simulated shot, sent through liblcm's memq:// provider and decoded again, must
// carry exactly the simulation's events and states.
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <jansson.h>
#include <lcm/lcm.h>

#include "lcm_convert.h"
#include "pool/scenario.h"

typedef struct fixture {
	pool_scenario scenario;
	pool_sim *sim;
} fixture;

static int setup_shot_until(void **state, const char *name, double max_time)
{
	fixture *f = calloc(1, sizeof *f);
	char path[1024], err[512];
	snprintf(path, sizeof path, "%s/%s.json", POOL_LCM_TEST_DATA_DIR, name);
	if (pool_scenario_load_file(path, &f->scenario, err, sizeof err) != 0) {
		fail_msg("%s: %s", path, err);
	}
	if (max_time > 0.0) {
		f->scenario.def.max_time = max_time;
	}
	pool_error perr = {{0}};
	assert_int_equal(pool_scenario_setup(&f->scenario, &f->sim, &perr), POOL_OK);
	assert_int_equal(pool_sim_run(f->sim), POOL_OK);
	*state = f;
	return 0;
}

static int setup_shot(void **state, const char *name) { return setup_shot_until(state, name, 0.0); }
static int setup_cut(void **state) { return setup_shot(state, "cut"); }
static int setup_break(void **state) { return setup_shot(state, "break"); }
// A break cut at 0.5 s, balls still moving: its final states belong to max_time, as pool-sim's.
static int setup_break_cut(void **state) { return setup_shot_until(state, "break", 0.5); }
// A slow ball into a corner on a jaws table: it hits the jaws (tools/tables/rattle.json).
static int setup_rattle(void **state) { return setup_shot(state, "rattle"); }

static int teardown(void **state)
{
	fixture *f = *state;
	pool_sim_destroy(f->sim);
	pool_scenario_free(&f->scenario);
	free(f);
	return 0;
}

static void assert_ball_equal(const pool_lcm_ball_state_t *m, const pool_ball_state *s)
{
	assert_int_equal(m->id, s->id);
	assert_int_equal(m->state, (int)s->motion);
	// Exact equality: the wire carries IEEE doubles unchanged.
	double want[9] = {s->pos.x, s->pos.y, s->pos.z, s->vel.x, s->vel.y, s->vel.z,
	                  s->omega.x, s->omega.y, s->omega.z};
	double got[9] = {m->pos[0], m->pos[1], m->pos[2], m->vel[0], m->vel[1], m->vel[2],
	                 m->omega[0], m->omega[1], m->omega[2]};
	assert_memory_equal(got, want, sizeof want);
}

static void assert_event_matches(const pool_sim *sim, int seq, const pool_lcm_event_t *m)
{
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	assert_true(seq < count);
	const pool_event *e = &events[seq];
	assert_int_equal(m->seq, seq);
	assert_memory_equal(&m->t, &e->time, sizeof(double));
	assert_string_equal(m->type, pool_event_type_name(e->type));
	assert_string_equal(m->rail, e->rail == POOL_RAIL_NONE ? "" : pool_rail_name(e->rail));
	assert_string_equal(m->pocket, e->pocket == POOL_POCKET_NONE ? "" : pool_pocket_name(e->pocket));
	assert_int_equal(m->num_balls, e->ball_count);
	const pool_ball_state *after = pool_sim_event_states(sim, e);
	for (int i = 0; i < e->ball_count; ++i) {
		assert_ball_equal(&m->balls[i], &after[i]);
	}
}

typedef struct received {
	pool_lcm_shot_t *shot;
	int shots;
} received;

static void on_shot(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_shot_t *msg,
                    void *user)
{
	(void)rbuf;
	received *r = user;
	assert_string_equal(channel, POOL_LCM_CHANNEL_SHOT);
	r->shot = pool_lcm_shot_t_copy(msg);
	r->shots++;
}

static void check_shot_round_trip(void **state)
{
	fixture *f = *state;
	lcm_t *lcm = lcm_create("memq://");
	assert_non_null(lcm);
	received r = {0};
	pool_lcm_shot_t_subscription_t *sub = pool_lcm_shot_t_subscribe(lcm, POOL_LCM_CHANNEL_SHOT,
	                                                                 on_shot, &r);
	pool_lcm_shot_t shot;
	assert_int_equal(pool_lcm_shot_fill(f->sim, 77, 5, 123456, &shot), 0);
	assert_int_equal(pool_lcm_shot_t_publish(lcm, POOL_LCM_CHANNEL_SHOT, &shot), 0);
	pool_lcm_shot_release(&shot);
	assert_int_equal(lcm_handle_timeout(lcm, 1000), 1);
	assert_int_equal(r.shots, 1);

	const pool_lcm_shot_t *got = r.shot;
	int count = 0;
	pool_sim_events(f->sim, &count);
	assert_true(count > 1);
	assert_int_equal(got->shot_id, 77);
	assert_int_equal(got->request_id, 5);
	assert_int_equal(got->utime, 123456);
	assert_string_equal(got->error, "");
	assert_string_equal(got->stop_reason, pool_stop_reason_name(pool_sim_stop_reason(f->sim)));
	assert_true(got->sim_time == pool_sim_time(f->sim));
	assert_int_equal(got->num_events, count);
	for (int i = 0; i < count; ++i) {
		assert_event_matches(f->sim, i, &got->events[i]);
		assert_int_equal(got->events[i].shot_id, 77);
	}
	int balls = pool_sim_ball_count(f->sim);
	assert_int_equal(got->num_balls, balls);
	pool_ball_state *final_states = calloc((size_t)balls, sizeof *final_states);
	double end = pool_sim_time(f->sim);
	int moving = 0;
	if (pool_sim_stop_reason(f->sim) == POOL_STOP_MAX_TIME) {
		end = f->scenario.def.max_time;
		assert_true(pool_sim_end_time(f->sim) == end);
		assert_true(pool_sim_time(f->sim) < end);
	}
	assert_int_equal(pool_sim_state_at(f->sim, end, final_states), POOL_OK);
	for (int i = 0; i < balls; ++i) {
		assert_ball_equal(&got->final_states[i], &final_states[i]);
		moving += got->final_states[i].state == POOL_MOTION_SLIDING ||
		          got->final_states[i].state == POOL_MOTION_ROLLING;
		// At rest (or stopped): nothing still slides or rolls.
		if (pool_sim_stop_reason(f->sim) == POOL_STOP_REST) {
			assert_true(got->final_states[i].state == POOL_MOTION_STATIONARY ||
			            got->final_states[i].state == POOL_MOTION_POCKETED ||
			            got->final_states[i].state == POOL_MOTION_OFF_TABLE);
		}
	}
	if (pool_sim_stop_reason(f->sim) == POOL_STOP_MAX_TIME) {
		assert_true(moving > 0);
	}
	free(final_states);
	pool_lcm_shot_t_destroy(r.shot);
	pool_lcm_shot_t_unsubscribe(lcm, sub);
	lcm_destroy(lcm);
}

static void check_event_fill(void **state)
{
	fixture *f = *state;
	int count = 0;
	pool_sim_events(f->sim, &count);
	for (int i = 0; i < count; ++i) {
		pool_lcm_event_t m;
		assert_int_equal(pool_lcm_event_fill(f->sim, i, 9, 10, &m), 0);
		assert_event_matches(f->sim, i, &m);
		// Round trip through the wire format.
		int size = pool_lcm_event_t_encoded_size(&m);
		void *buffer = malloc((size_t)size);
		assert_int_equal(pool_lcm_event_t_encode(buffer, 0, size, &m), size);
		pool_lcm_event_t back;
		memset(&back, 0, sizeof back);
		assert_int_equal(pool_lcm_event_t_decode(buffer, 0, size, &back), size);
		assert_event_matches(f->sim, i, &back);
		pool_lcm_event_t_decode_cleanup(&back);
		free(buffer);
		pool_lcm_event_release(&m);
	}
	pool_lcm_event_t m;
	assert_int_equal(pool_lcm_event_fill(f->sim, count, 0, 0, &m), -1);
	assert_int_equal(pool_lcm_event_fill(f->sim, -1, 0, 0, &m), -1);
	pool_lcm_event_release(&m);
}

static void check_table_state(void **state)
{
	fixture *f = *state;
	int balls = pool_sim_ball_count(f->sim);
	pool_ball_state *want = calloc((size_t)balls, sizeof *want);
	double end = pool_sim_time(f->sim);
	double times[] = {0.0, 0.25 * end, 0.5 * end, end};
	for (size_t k = 0; k < sizeof times / sizeof times[0]; ++k) {
		pool_lcm_table_state_t m;
		assert_int_equal(pool_lcm_table_state_fill(f->sim, times[k], 3, 4, &m), 0);
		assert_int_equal(pool_sim_state_at(f->sim, times[k], want), POOL_OK);
		assert_int_equal(m.num_balls, balls);
		assert_true(m.t == times[k]);
		for (int i = 0; i < balls; ++i) {
			assert_ball_equal(&m.balls[i], &want[i]);
		}
		pool_lcm_table_state_release(&m);
	}
	free(want);
}

static void check_error_shot(void **state)
{
	(void)state;
	char message[] = "balls[1].pos: overlaps ball 0 by 0.01 m";
	pool_lcm_shot_t m;
	assert_int_equal(pool_lcm_shot_fill_error(1, 2, 3, message, &m), 0);
	message[0] = 'X'; // the message is copied
	assert_string_equal(m.error, "balls[1].pos: overlaps ball 0 by 0.01 m");
	assert_int_equal(m.num_events, 0);
	assert_int_equal(m.num_balls, 0);
	assert_int_equal(m.request_id, 2);
	int size = pool_lcm_shot_t_encoded_size(&m);
	assert_true(size > 0);
	pool_lcm_shot_release(&m);
	assert_int_equal(pool_lcm_shot_fill_error(1, 2, 3, "", &m), 0);
	assert_true(m.error[0] != '\0'); // never an empty error on an error shot
	pool_lcm_shot_release(&m);
}

// The part of the cushion an event hit, as the result file names it ("" when it names none).
static const char *part_name(const pool_event *e)
{
	return e->type == POOL_EVENT_BALL_CUSHION && e->part != POOL_PART_NONE ? pool_cushion_part_name(e->part) : "";
}

typedef struct received2 {
	pool_lcm_shot2_t *shot;
	int shots;
} received2;

static void on_shot2(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_shot2_t *msg, void *user)
{
	(void)channel;
	(void)msg;
	received2 *r = user;
	// Decoded again from the datagram rather than copied: lcm-gen's _copy clones an empty array
	// with memcpy(NULL, ..., 0), which UBSan reports (a shot of a few events has empty arrays).
	r->shot = calloc(1, sizeof *r->shot);
	assert_non_null(r->shot);
	assert_true(pool_lcm_shot2_t_decode(rbuf->data, 0, (int)rbuf->data_size, r->shot) > 0);
	r->shots++;
}

// shot2_t through memq://: one part per event of the embedded shot, each the sim's own; the table
// the shot was simulated on (its fields, cut angles in degrees as the result file writes them,
// the balls' radius, and the result file's setup as JSON).
static void check_shot2_parts_and_table(void **state)
{
	fixture *f = *state;
	const pool_sim_def *def = &f->scenario.def;
	assert_int_equal(def->table.pockets, POOL_POCKETS_JAWS);
	lcm_t *lcm = lcm_create("memq://");
	assert_non_null(lcm);
	received2 r = {0};
	pool_lcm_shot2_t_subscription_t *sub = pool_lcm_shot2_t_subscribe(lcm, POOL_LCM_CHANNEL_SHOT2, on_shot2, &r);
	pool_lcm_shot_t shot;
	pool_lcm_shot2_t shot2;
	assert_int_equal(pool_lcm_shot_fill(f->sim, 77, 5, 123456, &shot), 0);
	assert_int_equal(pool_lcm_shot2_fill(&shot, f->sim, def, NULL, &shot2), 0);
	assert_int_equal(pool_lcm_shot2_t_publish(lcm, POOL_LCM_CHANNEL_SHOT2, &shot2), 0);
	pool_lcm_shot2_release(&shot2);
	pool_lcm_shot_release(&shot);
	assert_int_equal(lcm_handle_timeout(lcm, 1000), 1);
	assert_int_equal(r.shots, 1);
	const pool_lcm_shot2_t *got = r.shot;
	int count = 0, jaws = 0;
	const pool_event *events = pool_sim_events(f->sim, &count);
	assert_int_equal(got->shot.num_events, count);
	assert_int_equal(got->num_event_parts, count);
	for (int k = 0; k < count; ++k) {
		assert_event_matches(f->sim, k, &got->shot.events[k]);
		assert_string_equal(got->event_parts[k], part_name(&events[k]));
		jaws += strcmp(got->event_parts[k], "jaw") == 0;
	}
	assert_true(jaws >= 1); // the rattle hits a jaw
	assert_true(got->has_table);
	const pool_lcm_table_t *t = &got->table;
	assert_string_equal(t->pockets, "jaws");
	assert_int_equal(t->shot_id, 77);
	assert_true(t->length == def->table.length && t->width == def->table.width);
	assert_true(t->cushion_height == def->table.cushion_height);
	assert_true(t->corner_mouth == def->table.corner_mouth && t->side_mouth == def->table.side_mouth);
	assert_true(t->corner_cut_angle == def->table.corner_cut_angle * 180.0 / 3.14159265358979323846);
	assert_true(t->side_cut_angle == def->table.side_cut_angle * 180.0 / 3.14159265358979323846);
	assert_true(fabs(t->corner_cut_angle - 142.0) < 1e-9 && fabs(t->side_cut_angle - 104.0) < 1e-9); // WPA
	assert_true(t->corner_jaw_radius == def->table.corner_jaw_radius && t->side_jaw_radius == def->table.side_jaw_radius);
	assert_true(t->corner_shelf == def->table.corner_shelf && t->side_shelf == def->table.side_shelf);
	assert_true(t->corner_hole_radius == def->table.corner_hole_radius &&
	            t->side_hole_radius == def->table.side_hole_radius);
	assert_true(t->ball_radius == def->params.ball_radius);
	json_error_t jerr;
	json_t *setup = json_loads(t->json, 0, &jerr);
	assert_non_null(setup);
	assert_string_equal(json_string_value(json_object_get(json_object_get(setup, "table"), "pockets")), "jaws");
	assert_true(json_real_value(json_object_get(setup, "ball_radius")) == def->params.ball_radius);
	assert_true(json_real_value(json_object_get(json_object_get(setup, "params"), "mu_slide")) == def->params.mu_slide);
	assert_string_equal(json_string_value(json_object_get(json_object_get(setup, "models"), "cushion")),
	                    pool_cushion_model_name(def->models.cushion));
	json_decref(setup);
	pool_lcm_shot2_t_destroy(r.shot);
	pool_lcm_shot2_t_unsubscribe(lcm, sub);
	lcm_destroy(lcm);
}

// An error answer's shot2_t has no parts and no table; a shot2_t whose sim ran other events is
// refused.
static void check_shot2_error_answer(void **state)
{
	fixture *f = *state;
	pool_lcm_shot_t error, shot;
	pool_lcm_shot2_t shot2;
	assert_int_equal(pool_lcm_shot_fill_error(1, 2, 3, "balls: none", &error), 0);
	assert_int_equal(pool_lcm_shot2_fill(&error, NULL, NULL, NULL, &shot2), 0);
	assert_int_equal(shot2.num_event_parts, 0);
	assert_false(shot2.has_table);
	assert_string_equal(shot2.table.pockets, "");
	assert_true(pool_lcm_shot2_t_encoded_size(&shot2) > 0);
	pool_lcm_shot2_release(&shot2);
	pool_lcm_shot_release(&error);
	assert_int_equal(pool_lcm_shot_fill(f->sim, 1, 2, 3, &shot), 0);
	shot.num_events -= 1; // not the sim's events
	assert_int_equal(pool_lcm_shot2_fill(&shot, f->sim, &f->scenario.def, NULL, &shot2), -1);
	shot.num_events += 1;
	pool_lcm_shot_release(&shot);
}

// event2_t: the event as event_t carries it, and its part.
static void check_event2_fill(void **state)
{
	fixture *f = *state;
	int count = 0;
	const pool_event *events = pool_sim_events(f->sim, &count);
	for (int k = 0; k < count; ++k) {
		pool_lcm_event2_t m;
		assert_int_equal(pool_lcm_event2_fill(f->sim, k, 9, 10, &m), 0);
		assert_event_matches(f->sim, k, &m.event);
		assert_string_equal(m.part, part_name(&events[k]));
		assert_true(pool_lcm_event2_t_encoded_size(&m) > pool_lcm_event_t_encoded_size(&m.event));
		pool_lcm_event2_release(&m);
	}
	pool_lcm_event2_t m;
	assert_int_equal(pool_lcm_event2_fill(f->sim, count, 9, 10, &m), -1);
	pool_lcm_event2_release(&m);
}

// The size pool-shot-server checks against --max-answer-bytes before building the answer: the
// final-states message plus the events' share equals the whole message's encoded size, and the
// final-states message carries exactly the full one's final states, sim_time and stop_reason.
static void check_shot_size(void **state)
{
	fixture *f = *state;
	pool_lcm_shot_t full, final;
	assert_int_equal(pool_lcm_shot_fill(f->sim, 7, 8, 9, &full), 0);
	assert_int_equal(pool_lcm_shot_fill_final(f->sim, 7, 8, 9, &final), 0);
	int64_t events = pool_lcm_shot_events_encoded_size(f->sim);
	assert_true(events > 0);
	assert_int_equal(pool_lcm_shot_t_encoded_size(&final) + events,
	                 pool_lcm_shot_t_encoded_size(&full));
	assert_int_equal(final.num_events, 0);
	assert_int_equal(final.num_balls, full.num_balls);
	assert_memory_equal(final.final_states, full.final_states,
	                    (size_t)full.num_balls * sizeof *full.final_states);
	assert_true(final.sim_time == full.sim_time);
	assert_string_equal(final.stop_reason, full.stop_reason);
	assert_string_equal(final.error, "");
	// set_error replaces the error (freeing the previous copy) and counts in the size.
	int before = pool_lcm_shot_t_encoded_size(&final);
	assert_int_equal(pool_lcm_shot_set_error(&final, "first"), 0);
	assert_int_equal(pool_lcm_shot_set_error(&final, "too large"), 0);
	assert_string_equal(final.error, "too large");
	assert_int_equal(pool_lcm_shot_t_encoded_size(&final), before + 9);
	pool_lcm_shot_release(&final);
	pool_lcm_shot_release(&full);
}

static void check_request_decode(void **state)
{
	(void)state;
	pool_lcm_shot_request_t req = {.utime = 11, .request_id = 42, .scenario_json = "{\"a\": 1}"};
	int size = pool_lcm_shot_request_t_encoded_size(&req);
	unsigned char *buffer = malloc((size_t)size);
	assert_int_equal(pool_lcm_shot_request_t_encode(buffer, 0, size, &req), size);
	pool_lcm_shot_request_t out;
	char err[256];
	assert_int_equal(pool_lcm_request_decode(buffer, (size_t)size, &out, err, sizeof err), 0);
	assert_int_equal(out.request_id, 42);
	assert_int_equal(out.utime, 11);
	assert_string_equal(out.scenario_json, "{\"a\": 1}");
	pool_lcm_shot_request_t_decode_cleanup(&out);

	// Truncated, empty, garbage, a lying length, an unterminated string, a wrong fingerprint.
	assert_int_equal(pool_lcm_request_decode(buffer, (size_t)size - 1, &out, err, sizeof err), -1);
	assert_non_null(strstr(err, "undecodable"));
	assert_int_equal(pool_lcm_request_decode(buffer, 0, &out, err, sizeof err), -1);
	assert_int_equal(pool_lcm_request_decode("garbage", 7, &out, err, sizeof err), -1);
	unsigned char *bad = malloc((size_t)size);
	memcpy(bad, buffer, (size_t)size);
	bad[24] = 0x7f;
	assert_int_equal(pool_lcm_request_decode(bad, (size_t)size, &out, err, sizeof err), -1);
	memcpy(bad, buffer, (size_t)size);
	bad[size - 1] = 'x';
	assert_int_equal(pool_lcm_request_decode(bad, (size_t)size, &out, err, sizeof err), -1);
	memcpy(bad, buffer, (size_t)size);
	bad[0] ^= 0xff;
	assert_int_equal(pool_lcm_request_decode(bad, (size_t)size, &out, err, sizeof err), -1);
	assert_non_null(strstr(err, "fingerprint"));
	free(bad);
	free(buffer);
}

static void check_resolve_url(void **state)
{
	(void)state;
	setenv("LCM_DEFAULT_URL", "memq://", 1);
	assert_string_equal(pool_lcm_resolve_url("udpm://239.1.2.3:7000?ttl=0"),
	                    "udpm://239.1.2.3:7000?ttl=0");
	assert_string_equal(pool_lcm_resolve_url(NULL), "memq://");
	unsetenv("LCM_DEFAULT_URL");
	assert_string_equal(pool_lcm_resolve_url(NULL), POOL_LCM_DEFAULT_URL);
	assert_string_equal(pool_lcm_resolve_url(""), POOL_LCM_DEFAULT_URL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(check_shot_round_trip, setup_cut, teardown),
		cmocka_unit_test_setup_teardown(check_shot_round_trip, setup_break, teardown),
		cmocka_unit_test_setup_teardown(check_shot_round_trip, setup_break_cut, teardown),
		cmocka_unit_test_setup_teardown(check_event_fill, setup_break, teardown),
		cmocka_unit_test_setup_teardown(check_table_state, setup_cut, teardown),
		cmocka_unit_test_setup_teardown(check_shot_size, setup_cut, teardown),
		cmocka_unit_test_setup_teardown(check_shot_size, setup_break, teardown),
		cmocka_unit_test(check_error_shot),
		cmocka_unit_test_setup_teardown(check_shot2_parts_and_table, setup_rattle, teardown),
		cmocka_unit_test_setup_teardown(check_shot2_error_answer, setup_rattle, teardown),
		cmocka_unit_test_setup_teardown(check_event2_fill, setup_rattle, teardown),
		cmocka_unit_test(check_request_decode),
		cmocka_unit_test(check_resolve_url),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
