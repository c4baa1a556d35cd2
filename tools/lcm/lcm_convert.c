// Conversion between libpool simulations and pool_lcm messages (see lcm_convert.h).
#include "lcm_convert.h"

#include "game_json.h"
#include "pool/scenario.h"
#include "result_setup.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>

// lcm-gen declares strings as char*; encoding only reads them, so static names are safe to use.
static char pool_lcm_empty[] = "";

int64_t pool_lcm_utime_now(void)
{
	struct timeval tv;
	gettimeofday(&tv, NULL);
	return (int64_t)tv.tv_sec * 1000000 + tv.tv_usec;
}

const char *pool_lcm_resolve_url(const char *url)
{
	if (url != NULL && url[0] != '\0') {
		return url;
	}
	const char *env = getenv("LCM_DEFAULT_URL");
	if (env != NULL && env[0] != '\0') {
		return env;
	}
	return POOL_LCM_DEFAULT_URL;
}

void pool_lcm_ball_from_state(const pool_ball_state *state, pool_lcm_ball_state_t *out)
{
	out->id = state->id;
	out->state = (int8_t)state->motion;
	out->pos[0] = state->pos.x;
	out->pos[1] = state->pos.y;
	out->pos[2] = state->pos.z;
	out->vel[0] = state->vel.x;
	out->vel[1] = state->vel.y;
	out->vel[2] = state->vel.z;
	out->omega[0] = state->omega.x;
	out->omega[1] = state->omega.y;
	out->omega[2] = state->omega.z;
}

static char *pool_lcm_name_or_empty(const char *name)
{
	return name != NULL ? (char *)name : pool_lcm_empty;
}

// Fills out from an event without touching the sim's event array beyond it.
static int pool_lcm_event_fill_from(const pool_sim *sim, const pool_event *event, int seq,
                                    int64_t shot_id, int64_t utime, pool_lcm_event_t *out)
{
	memset(out, 0, sizeof *out);
	out->utime = utime;
	out->shot_id = shot_id;
	out->seq = seq;
	out->t = event->time;
	out->type = pool_lcm_name_or_empty(pool_event_type_name(event->type));
	// Like the result file: a rail or pocket whenever the event names one.
	out->rail = pool_lcm_name_or_empty(event->rail != POOL_RAIL_NONE ? pool_rail_name(event->rail)
	                                                                 : NULL);
	out->pocket = pool_lcm_name_or_empty(
		event->pocket != POOL_POCKET_NONE ? pool_pocket_name(event->pocket) : NULL);
	out->num_balls = event->ball_count;
	if (event->ball_count > 0) {
		out->balls = calloc((size_t)event->ball_count, sizeof *out->balls);
		if (out->balls == NULL) {
			out->num_balls = 0;
			return -1;
		}
		const pool_ball_state *after = pool_sim_event_states(sim, event);
		for (int i = 0; i < event->ball_count; ++i) {
			pool_lcm_ball_from_state(&after[i], &out->balls[i]);
		}
	}
	return 0;
}

int pool_lcm_event_fill(const pool_sim *sim, int seq, int64_t shot_id, int64_t utime,
                        pool_lcm_event_t *out)
{
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	memset(out, 0, sizeof *out);
	out->type = out->rail = out->pocket = pool_lcm_empty;
	if (seq < 0 || seq >= count) {
		return -1;
	}
	return pool_lcm_event_fill_from(sim, &events[seq], seq, shot_id, utime, out);
}

void pool_lcm_event_release(pool_lcm_event_t *msg)
{
	free(msg->balls);
	msg->balls = NULL;
	msg->num_balls = 0;
}

static void pool_lcm_shot_blank(int64_t shot_id, int64_t request_id, int64_t utime,
                                pool_lcm_shot_t *out)
{
	memset(out, 0, sizeof *out);
	out->utime = utime;
	out->shot_id = shot_id;
	out->request_id = request_id;
	out->stop_reason = pool_lcm_empty;
	out->error = pool_lcm_empty;
}

// Final states of every ball at pool_sim_end_time (max_time for a shot cut there, as pool-sim's
// "final"), sim_time and stop_reason (events untouched).
static int pool_lcm_shot_fill_final_part(const pool_sim *sim, pool_lcm_shot_t *out)
{
	int balls = pool_sim_ball_count(sim);
	if (balls > 0) {
		pool_ball_state *states = calloc((size_t)balls, sizeof *states);
		out->final_states = calloc((size_t)balls, sizeof *out->final_states);
		if (states == NULL || out->final_states == NULL ||
		    pool_sim_state_at(sim, pool_sim_end_time(sim), states) != POOL_OK) {
			free(states);
			return -1;
		}
		out->num_balls = balls;
		for (int i = 0; i < balls; ++i) {
			pool_lcm_ball_from_state(&states[i], &out->final_states[i]);
		}
		free(states);
	}
	out->sim_time = pool_sim_time(sim);
	out->stop_reason = pool_lcm_name_or_empty(pool_stop_reason_name(pool_sim_stop_reason(sim)));
	return 0;
}

int pool_lcm_shot_fill(const pool_sim *sim, int64_t shot_id, int64_t request_id, int64_t utime,
                       pool_lcm_shot_t *out)
{
	pool_lcm_shot_blank(shot_id, request_id, utime, out);
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	if (count > 0) {
		out->events = calloc((size_t)count, sizeof *out->events);
		if (out->events == NULL) {
			return -1;
		}
		for (int i = 0; i < count; ++i) {
			out->num_events = i + 1;
			if (pool_lcm_event_fill_from(sim, &events[i], i, shot_id, utime, &out->events[i]) != 0) {
				pool_lcm_shot_release(out);
				return -1;
			}
		}
	}
	if (pool_lcm_shot_fill_final_part(sim, out) != 0) {
		pool_lcm_shot_release(out);
		return -1;
	}
	return 0;
}

int pool_lcm_shot_fill_final(const pool_sim *sim, int64_t shot_id, int64_t request_id,
                             int64_t utime, pool_lcm_shot_t *out)
{
	pool_lcm_shot_blank(shot_id, request_id, utime, out);
	if (pool_lcm_shot_fill_final_part(sim, out) != 0) {
		pool_lcm_shot_release(out);
		return -1;
	}
	return 0;
}

int64_t pool_lcm_shot_events_encoded_size(const pool_sim *sim)
{
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	int64_t total = 0;
	for (int i = 0; i < count; ++i) {
		// One event at a time (its strings and ball states), so measuring needs no whole message.
		pool_lcm_event_t msg;
		if (pool_lcm_event_fill_from(sim, &events[i], i, 0, 0, &msg) != 0) {
			pool_lcm_event_release(&msg);
			return -1;
		}
		total += __pool_lcm_event_t_encoded_array_size(&msg, 1);
		pool_lcm_event_release(&msg);
	}
	return total;
}

int pool_lcm_shot_set_error(pool_lcm_shot_t *msg, const char *message)
{
	const char *text = (message != NULL && message[0] != '\0') ? message : "unknown error";
	char *copy = malloc(strlen(text) + 1);
	if (copy == NULL) {
		return -1;
	}
	strcpy(copy, text);
	if (msg->error != NULL && msg->error != pool_lcm_empty) {
		free(msg->error);
	}
	msg->error = copy;
	return 0;
}

int pool_lcm_shot_fill_error(int64_t shot_id, int64_t request_id, int64_t utime,
                             const char *message, pool_lcm_shot_t *out)
{
	pool_lcm_shot_blank(shot_id, request_id, utime, out);
	return pool_lcm_shot_set_error(out, message);
}

void pool_lcm_shot_release(pool_lcm_shot_t *msg)
{
	for (int i = 0; i < msg->num_events; ++i) {
		pool_lcm_event_release(&msg->events[i]);
	}
	free(msg->events);
	free(msg->final_states);
	if (msg->error != NULL && msg->error != pool_lcm_empty) {
		free(msg->error);
	}
	msg->events = NULL;
	msg->final_states = NULL;
	msg->num_events = 0;
	msg->num_balls = 0;
	msg->error = pool_lcm_empty;
}

int pool_lcm_table_state_fill(const pool_sim *sim, double t, int64_t shot_id, int64_t utime,
                              pool_lcm_table_state_t *out)
{
	memset(out, 0, sizeof *out);
	out->utime = utime;
	out->shot_id = shot_id;
	out->t = t;
	int balls = pool_sim_ball_count(sim);
	if (balls <= 0) {
		return 0;
	}
	pool_ball_state *states = calloc((size_t)balls, sizeof *states);
	out->balls = calloc((size_t)balls, sizeof *out->balls);
	if (states == NULL || out->balls == NULL || pool_sim_state_at(sim, t, states) != POOL_OK) {
		free(states);
		pool_lcm_table_state_release(out);
		return -1;
	}
	out->num_balls = balls;
	for (int i = 0; i < balls; ++i) {
		pool_lcm_ball_from_state(&states[i], &out->balls[i]);
	}
	free(states);
	return 0;
}

void pool_lcm_table_state_release(pool_lcm_table_state_t *msg)
{
	free(msg->balls);
	msg->balls = NULL;
	msg->num_balls = 0;
}

static uint32_t pool_lcm_be32(const unsigned char *p)
{
	return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | p[3];
}

static uint64_t pool_lcm_be64(const unsigned char *p)
{
	return ((uint64_t)pool_lcm_be32(p) << 32) | pool_lcm_be32(p + 4);
}

int pool_lcm_request_peek(const void *data, size_t size, int64_t *request_id, char *err,
                          size_t err_size)
{
	// Layout: 8-byte fingerprint, int64 utime, int64 request_id, int32 length (with NUL), bytes.
	enum { header = 8 + 8 + 8 + 4 };
	const unsigned char *bytes = data;
	if (data == NULL || size < header || size > (size_t)0x7fffffff) {
		snprintf(err, err_size, "undecodable shot_request_t: %zu bytes", size);
		return -1;
	}
	uint32_t length = pool_lcm_be32(bytes + 24);
	if (length < 1 || length != size - header || bytes[size - 1] != '\0') {
		snprintf(err, err_size,
		         "undecodable shot_request_t: scenario_json length %u in a %zu-byte message",
		         length, size);
		return -1;
	}
	if (pool_lcm_be64(bytes) != (uint64_t)__pool_lcm_shot_request_t_get_hash()) {
		snprintf(err, err_size, "undecodable shot_request_t: wrong type fingerprint");
		return -1;
	}
	if (request_id != NULL) {
		*request_id = (int64_t)pool_lcm_be64(bytes + 16);
	}
	return 0;
}

int pool_lcm_request_decode(const void *data, size_t size, pool_lcm_shot_request_t *out,
                            char *err, size_t err_size)
{
	memset(out, 0, sizeof *out);
	if (pool_lcm_request_peek(data, size, NULL, err, err_size) != 0) {
		return -1;
	}
	if (pool_lcm_shot_request_t_decode(data, 0, (int)size, out) < 0) {
		pool_lcm_shot_request_t_decode_cleanup(out);
		memset(out, 0, sizeof *out);
		snprintf(err, err_size, "undecodable shot_request_t: wrong type fingerprint");
		return -1;
	}
	return 0;
}

int pool_lcm_table_fill(const pool_sim_def *def, int64_t shot_id, int64_t utime, pool_lcm_table_t *out)
{
	memset(out, 0, sizeof *out);
	out->pockets = out->json = pool_lcm_empty;
	if (def == NULL) {
		return 0;
	}
	const pool_table_def *t = &def->table;
	out->utime = utime;
	out->shot_id = shot_id;
	out->pockets = pool_lcm_name_or_empty(pool_pockets_model_name(t->pockets));
	out->length = t->length;
	out->width = t->width;
	out->cushion_height = t->cushion_height;
	out->corner_mouth = t->corner_mouth;
	out->side_mouth = t->side_mouth;
	if (t->pockets == POOL_POCKETS_JAWS) { // the other models read no geometry beyond the mouths
		// Degrees by the result file's expression, so the two agree to the bit.
		out->corner_cut_angle = t->corner_cut_angle * 180.0 / 3.14159265358979323846;
		out->side_cut_angle = t->side_cut_angle * 180.0 / 3.14159265358979323846;
		out->corner_jaw_radius = t->corner_jaw_radius;
		out->side_jaw_radius = t->side_jaw_radius;
		out->corner_shelf = t->corner_shelf;
		out->side_shelf = t->side_shelf;
		out->corner_hole_radius = t->corner_hole_radius;
		out->side_hole_radius = t->side_hole_radius;
	}
	out->ball_radius = def->params.ball_radius;
	pool_jw w;
	pool_jw_init(&w, false);
	pool_jw_object(&w, false);
	pool_jw_sim_setup(&w, def);
	pool_jw_end(&w, '}');
	char *json = pool_jw_finish(&w);
	if (json == NULL) {
		return -1;
	}
	json[strcspn(json, "\n")] = '\0';
	out->json = json;
	return 0;
}

void pool_lcm_table_release(pool_lcm_table_t *msg)
{
	if (msg->json != pool_lcm_empty) {
		free(msg->json);
	}
	msg->json = pool_lcm_empty;
}

static char *pool_lcm_part_name(const pool_event *event)
{
	return event->type == POOL_EVENT_BALL_CUSHION && event->part != POOL_PART_NONE
	           ? pool_lcm_name_or_empty(pool_cushion_part_name(event->part))
	           : pool_lcm_empty;
}

int pool_lcm_event2_fill(const pool_sim *sim, int seq, int64_t shot_id, int64_t utime,
                         pool_lcm_event2_t *out)
{
	memset(out, 0, sizeof *out);
	out->utime = utime;
	out->part = pool_lcm_empty;
	if (pool_lcm_event_fill(sim, seq, shot_id, utime, &out->event) != 0) {
		return -1;
	}
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	out->part = pool_lcm_part_name(&events[seq]);
	return 0;
}

void pool_lcm_event2_release(pool_lcm_event2_t *msg)
{
	pool_lcm_event_release(&msg->event);
}

int pool_lcm_shot2_fill(const pool_lcm_shot_t *shot, const pool_sim *sim, const pool_sim_def *def,
                        const pool_game_state *game, pool_lcm_shot2_t *out)
{
	memset(out, 0, sizeof *out);
	out->utime = shot->utime;
	out->shot = *shot;
	out->game_rules = out->game_outcome = out->game_reason = out->game_json = pool_lcm_empty;
	out->table.pockets = out->table.json = pool_lcm_empty;
	// The parts, parallel to the shot's events (none without the sim that ran them).
	int count = 0;
	const pool_event *events = sim != NULL ? pool_sim_events(sim, &count) : NULL;
	if (shot->num_events > 0 && sim != NULL) {
		if (count != shot->num_events) {
			return -1;
		}
		out->event_parts = calloc((size_t)count, sizeof *out->event_parts);
		if (out->event_parts == NULL) {
			return -1;
		}
		out->num_event_parts = count;
		for (int k = 0; k < count; ++k) {
			out->event_parts[k] = pool_lcm_part_name(&events[k]);
		}
	}
	if (def != NULL) {
		if (pool_lcm_table_fill(def, shot->shot_id, shot->utime, &out->table) != 0) {
			pool_lcm_shot2_release(out);
			return -1;
		}
		out->has_table = 1;
	}
	if (game == NULL || sim == NULL || def == NULL) {
		return 0;
	}
	const pool_game_shot judged_shot = pool_game_shot_of_sim(sim);
	pool_game_result r;
	if (pool_game_judge(game, &judged_shot, &def->table, &r, NULL) != POOL_OK) {
		pool_lcm_shot2_release(out);
		return -1;
	}
	out->game_rules = pool_lcm_name_or_empty(pool_game_rules_name(game->rules));
	out->game_legal = r.legal;
	out->game_outcome = pool_lcm_name_or_empty(pool_game_outcome_name(r.outcome));
	out->game_reason = pool_lcm_name_or_empty(pool_game_reason_name(r.reason));
	out->game_ball_in_hand = r.ball_in_hand;
	out->game_points = r.points;
	out->game_has_first_hit = r.first_hit != POOL_GAME_NO_BALL;
	out->game_first_hit = out->game_has_first_hit ? r.first_hit : 0;
	out->game_rails_after_contact = r.rails_after_contact;
	out->game_fouls = calloc(POOL_GAME_FOUL_KINDS, sizeof *out->game_fouls);
	out->game_pocketed = calloc(POOL_GAME_MAX_BALLS, sizeof *out->game_pocketed);
	pool_jw w;
	pool_jw_init(&w, false);
	pool_jw_game_result(&w, game->rules, &r);
	char *json = pool_jw_finish(&w);
	if (out->game_fouls == NULL || out->game_pocketed == NULL || json == NULL) {
		free(json);
		pool_lcm_shot2_release(out);
		return -1;
	}
	json[strcspn(json, "\n")] = '\0';
	out->game_json = json;
	for (int k = 0; k < POOL_GAME_FOUL_KINDS; ++k) {
		if (r.fouls & (1u << k)) {
			out->game_fouls[out->game_num_fouls++] = (char *)pool_game_foul_name(1u << k);
		}
	}
	for (int i = 0; i < r.pocketed_count; ++i) {
		out->game_pocketed[out->game_num_pocketed++] = r.pocketed[i];
	}
	return 0;
}

void pool_lcm_shot2_release(pool_lcm_shot2_t *msg)
{
	free(msg->game_fouls);
	free(msg->game_pocketed);
	if (msg->game_json != pool_lcm_empty) {
		free(msg->game_json);
	}
	free(msg->event_parts);
	pool_lcm_table_release(&msg->table);
	msg->game_fouls = NULL;
	msg->game_pocketed = NULL;
	msg->event_parts = NULL;
	msg->game_json = pool_lcm_empty;
	msg->game_num_fouls = msg->game_num_pocketed = msg->num_event_parts = 0;
	msg->has_table = 0;
}
