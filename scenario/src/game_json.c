// The "game" object of scenario and result files (game_json.h).
#include "game_json.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "text_escape.h"

static int fail(char *err, size_t size, const char *format, ...) __attribute__((format(printf, 3, 4)));
static int fail(char *err, size_t size, const char *format, ...) {
	if (err && size) {
		va_list args;
		va_start(args, format);
		vsnprintf(err, size, format, args);
		va_end(args);
	}
	return -1;
}

pool_game_state pool_game_json_default_state(pool_game_rules rules) {
	pool_game_state s = pool_game_default_state(rules);
	s.break_shot = false;
	s.ball_in_hand = false;
	s.behind_head_string = false;
	return s;
}

pool_pocket pool_game_pocket_from_name(const char *name) {
	for (int p = POOL_POCKET_SW; p <= POOL_POCKET_N; ++p)
		if (name && strcmp(name, pool_pocket_name((pool_pocket)p)) == 0)
			return (pool_pocket)p;
	return POOL_POCKET_NONE;
}

static int unknown_key(const json_t *object, const char *path, const char *const *allowed, char *err,
                       size_t size) {
	const char *key;
	json_t *value;
	json_object_foreach((json_t *)object, key, value) {
		bool known = false;
		for (const char *const *a = allowed; *a; ++a)
			known = known || strcmp(key, *a) == 0;
		if (!known) {
			char shown[POOL_ESCAPE_SHORT];
			return key[0] ? fail(err, size, "%s.%s: unknown field", path, pool_escape_str(shown, sizeof shown, key))
			              : fail(err, size, "%s: unknown field \"\"", path);
		}
	}
	return 0;
}

static int get_bool(const json_t *object, const char *path, const char *key, bool *out, char *err, size_t size) {
	const json_t *v = json_object_get(object, key);
	if (!v)
		return 0;
	if (!json_is_boolean(v))
		return fail(err, size, "%s.%s: must be true or false", path, key);
	*out = json_is_true(v);
	return 0;
}

static int get_count(const json_t *object, const char *path, const char *key, int *out, char *err, size_t size) {
	const json_t *v = json_object_get(object, key);
	if (!v)
		return 0;
	if (!json_is_integer(v) || json_integer_value(v) < 0 || json_integer_value(v) > 1000000000)
		return fail(err, size, "%s.%s: must be a whole number from 0 to 1000000000", path, key);
	*out = (int)json_integer_value(v);
	return 0;
}

static int get_id(const json_t *object, const char *path, const char *key, int32_t *out, char *err, size_t size) {
	const json_t *v = json_object_get(object, key);
	if (!v)
		return 0;
	if (!json_is_integer(v) || json_integer_value(v) < INT32_MIN + 1 || json_integer_value(v) > INT32_MAX)
		return fail(err, size, "%s.%s: must be a ball id (a 32-bit integer)", path, key);
	*out = (int32_t)json_integer_value(v);
	return 0;
}

int pool_game_json_parse_state(const json_t *s, const char *path, pool_game_rules rules, pool_game_state *state,
                               char *err, size_t size) {
	static const char *const fields[] = {
		"player", "break", "cue_ball", "opponent_cue_ball", "group", "called", "safety", "push_out",
		"push_out_available", "ball_in_hand", "behind_head_string", "fouls", "opponent_fouls", "points",
		"opponent_points", "target", NULL};
	*state = pool_game_json_default_state(rules);
	if (!s)
		return 0;
	if (!json_is_object(s))
		return fail(err, size, "%s: must be an object", path);
	if (unknown_key(s, path, fields, err, size))
		return -1;
	if (get_count(s, path, "player", &state->player, err, size) ||
	    get_bool(s, path, "break", &state->break_shot, err, size) ||
	    get_id(s, path, "cue_ball", &state->cue_ball, err, size) ||
	    get_id(s, path, "opponent_cue_ball", &state->opponent_cue_ball, err, size) ||
	    get_bool(s, path, "safety", &state->safety, err, size) ||
	    get_bool(s, path, "push_out", &state->push_out, err, size) ||
	    get_bool(s, path, "push_out_available", &state->push_out_available, err, size) ||
	    get_bool(s, path, "ball_in_hand", &state->ball_in_hand, err, size) ||
	    get_bool(s, path, "behind_head_string", &state->behind_head_string, err, size) ||
	    get_count(s, path, "fouls", &state->fouls, err, size) ||
	    get_count(s, path, "opponent_fouls", &state->opponent_fouls, err, size) ||
	    get_count(s, path, "points", &state->points, err, size) ||
	    get_count(s, path, "opponent_points", &state->opponent_points, err, size) ||
	    get_count(s, path, "target", &state->target_points, err, size))
		return -1;
	const json_t *group = json_object_get(s, "group");
	if (group) {
		const int g = json_is_string(group) ? pool_game_group_from_name(json_string_value(group)) : -1;
		if (g < 0)
			return fail(err, size, "%s.group: must be \"open\", \"solids\" or \"stripes\"", path);
		state->group = (pool_game_group)g;
	}
	const json_t *called = json_object_get(s, "called");
	if (called) {
		char sub[64];
		snprintf(sub, sizeof sub, "%s.called", path);
		static const char *const call_fields[] = {"ball", "pocket", NULL};
		if (!json_is_object(called))
			return fail(err, size, "%s: must be an object (\"ball\", \"pocket\")", sub);
		if (unknown_key(called, sub, call_fields, err, size) ||
		    get_id(called, sub, "ball", &state->called_ball, err, size))
			return -1;
		const json_t *pocket = json_object_get(called, "pocket");
		if (pocket) {
			state->called_pocket = json_is_string(pocket) ? pool_game_pocket_from_name(json_string_value(pocket))
			                                              : POOL_POCKET_NONE;
			if (state->called_pocket == POOL_POCKET_NONE)
				return fail(err, size, "%s.pocket: must be one of \"sw\", \"se\", \"nw\", \"ne\", \"s\", \"n\"", sub);
		}
	}
	pool_error e;
	if (pool_game_state_validate(state, &e) != POOL_OK) {
		// The library names fields "game.state....": put them under this path.
		const char *rest = strncmp(e.message, "game.state", 10) == 0 ? e.message + 10 : NULL;
		return rest ? fail(err, size, "%s%s", path, rest) : fail(err, size, "%s: %s", path, e.message);
	}
	return 0;
}

int pool_game_json_parse(const json_t *game, const char *path, pool_game_state *state, char *err, size_t size) {
	static const char *const fields[] = {"rules", "state", NULL};
	if (!json_is_object(game))
		return fail(err, size, "%s: must be an object (\"rules\", \"state\")", path);
	if (unknown_key(game, path, fields, err, size))
		return -1;
	const json_t *rules = json_object_get(game, "rules");
	if (!rules)
		return fail(err, size, "%s.rules: missing (8ball, 9ball, three_cushion)", path);
	const int r = json_is_string(rules) ? pool_game_rules_from_name(json_string_value(rules)) : -1;
	if (r < 0) {
		char shown[POOL_ESCAPE_SHORT];
		if (!json_is_string(rules))
			return fail(err, size, "%s.rules: must be a string (8ball, 9ball, three_cushion)", path);
		return fail(err, size, "%s.rules: unknown rules \"%s\" (8ball, 9ball, three_cushion)", path,
		            pool_escape_text(shown, sizeof shown, json_string_value(rules), json_string_length(rules)));
	}
	char sub[64];
	snprintf(sub, sizeof sub, "%s.state", path);
	return pool_game_json_parse_state(json_object_get(game, "state"), sub, (pool_game_rules)r, state, err, size);
}

void pool_jw_game_state(pool_jw *w, const pool_game_state *s) {
	pool_jw_object(w, true);
	pool_jw_key(w, "player");
	pool_jw_int(w, s->player);
	pool_jw_key(w, "break");
	pool_jw_bool(w, s->break_shot);
	if (s->rules == POOL_GAME_THREE_CUSHION) {
		pool_jw_key(w, "cue_ball");
		pool_jw_int(w, s->cue_ball);
		pool_jw_key(w, "opponent_cue_ball");
		pool_jw_int(w, s->opponent_cue_ball);
	}
	if (s->rules == POOL_GAME_8BALL) {
		pool_jw_key(w, "group");
		pool_jw_string(w, pool_game_group_name(s->group));
		if (s->called_ball != POOL_GAME_NO_BALL || s->called_pocket != POOL_POCKET_NONE) {
			pool_jw_key(w, "called");
			pool_jw_object(w, true);
			if (s->called_ball != POOL_GAME_NO_BALL) {
				pool_jw_key(w, "ball");
				pool_jw_int(w, s->called_ball);
			}
			if (s->called_pocket != POOL_POCKET_NONE) {
				pool_jw_key(w, "pocket");
				pool_jw_string(w, pool_pocket_name(s->called_pocket));
			}
			pool_jw_end(w, '}');
		}
	}
	if (s->rules != POOL_GAME_THREE_CUSHION) {
		pool_jw_key(w, "safety");
		pool_jw_bool(w, s->safety);
	}
	if (s->rules == POOL_GAME_9BALL) {
		pool_jw_key(w, "push_out");
		pool_jw_bool(w, s->push_out);
		pool_jw_key(w, "push_out_available");
		pool_jw_bool(w, s->push_out_available);
	}
	if (s->rules != POOL_GAME_THREE_CUSHION) {
		pool_jw_key(w, "ball_in_hand");
		pool_jw_bool(w, s->ball_in_hand);
		pool_jw_key(w, "behind_head_string");
		pool_jw_bool(w, s->behind_head_string);
	}
	pool_jw_key(w, "fouls");
	pool_jw_int(w, s->fouls);
	pool_jw_key(w, "opponent_fouls");
	pool_jw_int(w, s->opponent_fouls);
	if (s->rules == POOL_GAME_THREE_CUSHION) {
		pool_jw_key(w, "points");
		pool_jw_int(w, s->points);
		pool_jw_key(w, "opponent_points");
		pool_jw_int(w, s->opponent_points);
		pool_jw_key(w, "target");
		pool_jw_int(w, s->target_points);
	}
	pool_jw_end(w, '}');
}

void pool_game_foul_list(uint32_t fouls, const char *sep, char *out, size_t size) {
	size_t used = 0;
	out[0] = '\0';
	for (int k = 0; k < POOL_GAME_FOUL_KINDS; ++k)
		if (fouls & (1u << k)) {
			const int n = snprintf(out + used, size - used, "%s%s", used ? sep : "", pool_game_foul_name(1u << k));
			if (n < 0 || (size_t)n >= size - used)
				return;
			used += (size_t)n;
		}
}

static void id_list(pool_jw *w, const char *key, const int32_t *ids, int count) {
	pool_jw_key(w, key);
	pool_jw_array(w, true);
	for (int i = 0; i < count; ++i)
		pool_jw_int(w, ids[i]);
	pool_jw_end(w, ']');
}

void pool_jw_game_result(pool_jw *w, pool_game_rules rules, const pool_game_result *r) {
	pool_jw_object(w, false);
	pool_jw_key(w, "rules");
	pool_jw_string(w, pool_game_rules_name(rules));
	pool_jw_key(w, "legal");
	pool_jw_bool(w, r->legal);
	pool_jw_key(w, "fouls");
	pool_jw_array(w, true);
	for (int k = 0; k < POOL_GAME_FOUL_KINDS; ++k)
		if (r->fouls & (1u << k))
			pool_jw_string(w, pool_game_foul_name(1u << k));
	pool_jw_end(w, ']');
	pool_jw_key(w, "outcome");
	pool_jw_string(w, pool_game_outcome_name(r->outcome));
	pool_jw_key(w, "reason");
	pool_jw_string(w, pool_game_reason_name(r->reason));
	pool_jw_key(w, "ball_in_hand");
	pool_jw_bool(w, r->ball_in_hand);
	pool_jw_key(w, "behind_head_string");
	pool_jw_bool(w, r->behind_head_string);
	pool_jw_key(w, "rerack_option");
	pool_jw_bool(w, r->rerack_option);
	pool_jw_key(w, "pass_option");
	pool_jw_bool(w, r->pass_option);
	pool_jw_key(w, "points");
	pool_jw_int(w, r->points);
	pool_jw_key(w, "first_hit");
	if (r->first_hit == POOL_GAME_NO_BALL)
		pool_jw_null(w);
	else
		pool_jw_int(w, r->first_hit);
	pool_jw_key(w, "rails_after_contact");
	pool_jw_int(w, r->rails_after_contact);
	pool_jw_key(w, "cue_cushions");
	pool_jw_int(w, r->cue_cushions);
	id_list(w, "pocketed", r->pocketed, r->pocketed_count);
	pool_jw_key(w, "pockets");
	pool_jw_array(w, true);
	for (int i = 0; i < r->pocketed_count; ++i)
		pool_jw_string(w, pool_pocket_name(r->pocketed_in[i]));
	pool_jw_end(w, ']');
	id_list(w, "off_table", r->off_table, r->off_table_count);
	id_list(w, "spot", r->spot, r->spot_count);
	pool_jw_key(w, "state");
	pool_jw_game_state(w, &r->next);
	pool_jw_end(w, '}');
}
