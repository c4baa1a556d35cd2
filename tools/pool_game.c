// pool-game: plays a whole rack (8-ball, 9-ball) or a three-cushion game, shot after shot, under
// libpool games' rules: a strategy command answers each turn with a strike (and, with the ball in
// hand, where the cue ball goes), or the strikes come on standard input; the rules spot balls,
// pass turns, end the game; the game record (libpool-game/1) is written at the end.
// Exit status: 0 success (the record is written whatever ended the game), 2 bad input or usage (an
// answer that is not a strike names the shot and the field), 1 internal failure or a strategy
// that failed.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pool/batch.h"
#include "cli.h"
#include "game/peer.h"
#include "game_json.h"
#include "json_writer.h"
#include "read_input.h"
#include "pool/scenario.h"
#include "text_escape.h"

#define PROGRAM "pool-game"
#define GAME_DEFAULT_MAX_SHOTS 500L
#define GAME_MAX_SHOTS 1000000L
// An answer is a few hundred bytes; a longer line is not a strike.
#define GAME_MAX_ANSWER 65536
// The rack's gap between neighbouring object balls, as pool-rack's default (m).
#define GAME_RACK_GAP 0.0001
#define GAME_MAX_ABS 1e9

typedef struct game_options {
	const char *rules_name;
	const char *table_preset;
	const char *layout_path;
	const char *strategy;
	const char *noise_spec;
	long seed;
	long max_shots;
	long target;
	bool have_target;
	const char *output;
	size_t max_input;
	bool help;
} game_options;

static const char usage_text[] =
	"usage: pool-game 8ball|9ball|three_cushion [--strategy COMMAND] [--layout FILE | --table PRESET]\n"
	"                 [--noise NAME|SPEC] [--seed S] [--target N] [--max-shots N] [-o RECORD.json]\n"
	"                 [--max-input BYTES]\n"
	"\n"
	"Plays a game shot after shot under libpool games' rules (docs/games.md) and writes its record\n"
	"(libpool-game/1 JSON). Each shot comes from the strategy, or from standard input: one JSON line\n"
	"per shot, {\"strike\": {\"speed\": 3, \"phi\": 10, \"theta\": 0, \"a\": 0, \"b\": 0}} (angles in\n"
	"degrees) with, when the cue ball is in hand, \"cue_pos\": [x, y]; in 8-ball \"call\": {\"ball\": 3,\n"
	"\"pocket\": \"ne\"}; \"safety\": true; in 9-ball \"push_out\": true on the shot after the break.\n"
	"\n"
	"  --strategy COMMAND  run COMMAND (with /bin/sh -c): before each shot it reads one line, the\n"
	"                      turn (the balls on the table, the rules' state, whether the cue ball is\n"
	"                      in hand), and answers one line as above\n"
	"  --layout FILE       start from this libpool-scenario/1 (table, params, models, balls, and its\n"
	"                      \"game\" state if any; its strike is ignored) instead of the opening rack\n"
	"  --table PRESET      table preset for the opening rack, with its balls (wpa-9ft default;\n"
	"                      three_cushion plays on carom: 2.84 x 1.42 m, no pockets, 61.5 mm balls)\n"
	"  --noise NAME|SPEC   Gaussian noise on every strike (none, fastfiz, or NAME=SD pairs as in\n"
	"                      pool-batch); shot k draws sample k of --seed\n"
	"  --seed S            seed of the noise (default 1)\n"
	"  --target N          three_cushion: the score that wins (default 0: play until --max-shots)\n"
	"  --max-shots N       stop after N shots (default 500)\n"
	"  -o, --output FILE   write the record to FILE (atomically) instead of standard output\n"
	"  --max-input BYTES   limit on --layout (default 64M)\n"
	"  -h, --help          show this help\n"
	"\n"
	"The game ends with a win or a loss, at --max-shots, or when the strikes end; the record says\n"
	"which. Exit status: 0 success, 2 bad input or usage (message names the shot and field), 1\n"
	"internal error or a strategy that exits with an error.\n";

static int game_option(void *context, const char *a, const char *v) {
	game_options *o = context;
	if (strcmp(a, "--strategy") == 0) {
		o->strategy = v;
	} else if (strcmp(a, "--layout") == 0) {
		o->layout_path = v;
	} else if (strcmp(a, "--table") == 0) {
		o->table_preset = v;
	} else if (strcmp(a, "--noise") == 0) {
		o->noise_spec = v;
	} else if (strcmp(a, "--seed") == 0) {
		if (!pool_cli_parse_count(v, &o->seed))
			return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number >= 0", pool_cli_arg(v));
	} else if (strcmp(a, "--target") == 0) {
		o->have_target = true;
		if (!pool_cli_parse_count(v, &o->target) || o->target > 1000000000L)
			return pool_cli_usage_error(PROGRAM, "--target: '%s' is not a score from 0 to 1000000000", pool_cli_arg(v));
	} else if (strcmp(a, "--max-shots") == 0) {
		if (!pool_cli_parse_count(v, &o->max_shots) || o->max_shots < 1 || o->max_shots > GAME_MAX_SHOTS)
			return pool_cli_usage_error(PROGRAM, "--max-shots: '%s' is not a number of shots from 1 to %ld",
			                            pool_cli_arg(v), GAME_MAX_SHOTS);
	} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
		o->output = v;
	} else if (strcmp(a, "--max-input") == 0) {
		return pool_cli_max_input(PROGRAM, v, &o->max_input);
	}
	return 0;
}

static int parse_options(int argc, char **argv, game_options *o) {
	memset(o, 0, sizeof *o);
	o->max_shots = GAME_DEFAULT_MAX_SHOTS;
	o->seed = 1;
	o->max_input = POOL_INPUT_DEFAULT_MAX;
	static const char *const flags[] = {NULL};
	static const char *const with_value[] = {"--strategy", "--layout", "--table", "--noise", "--seed", "--target",
	                                         "--max-shots", "-o", "--output", "--max-input", NULL};
	const int status =
	    pool_cli_walk(PROGRAM, argc, argv, "game", flags, with_value, game_option, o, &o->rules_name, &o->help);
	if (status || o->help)
		return status;
	if (!o->rules_name)
		return pool_cli_usage_error(PROGRAM, "%s", "missing the rules (8ball, 9ball or three_cushion)");
	if (pool_game_rules_from_name(o->rules_name) < 0)
		return pool_cli_usage_error(PROGRAM, "'%s': unknown rules (8ball, 9ball, three_cushion)",
		                            pool_cli_arg(o->rules_name));
	if (o->layout_path && o->table_preset)
		return pool_cli_usage_error(PROGRAM, "%s", "--table: give --layout or --table, not both");
	if (o->have_target && pool_game_rules_from_name(o->rules_name) != POOL_GAME_THREE_CUSHION)
		return pool_cli_usage_error(PROGRAM, "--target: only in three_cushion, not %s", o->rules_name);
	return 0;
}

// ---- the game --------------------------------------------------------------------------------

typedef struct game {
	const game_options *o;
	pool_game_rules rules;
	pool_sim_def def;
	pool_game_state state;
	int count;                               ///< balls on the table
	pool_ball_state balls[POOL_GAME_MAX_BALLS]; ///< at rest on the cloth
	int start_count;
	pool_ball_state start[POOL_GAME_MAX_BALLS];
	bool noisy;
	pool_noise noise;
	pool_sim *sim;
	pool_jw record;                          ///< "shots" being written
	long shots;
	const char *end;                         ///< why the game ended
	int winner;                              ///< 0 or 1, -1 none
} game;

static int shot_error(long shot, const char *format, ...) __attribute__((format(printf, 2, 3)));
static int shot_error(long shot, const char *format, ...) {
	fprintf(stderr, "%s: shot %ld: ", PROGRAM, shot);
	va_list args;
	va_start(args, format);
	vfprintf(stderr, format, args);
	va_end(args);
	fputc('\n', stderr);
	return POOL_EXIT_BAD_INPUT;
}

/// The table and balls of a preset (pool_table_preset, pool_params_preset: the balls and cloth
/// its game is played with); nonzero when the name is not a preset.
static int use_preset(pool_sim_def *def, const char *name) {
	return pool_table_preset(name, &def->table) != POOL_OK || pool_params_preset(name, &def->params) != POOL_OK;
}

static int setup(game *g) {
	const game_options *o = g->o;
	g->rules = (pool_game_rules)pool_game_rules_from_name(o->rules_name);
	g->winner = -1;
	if (o->layout_path) {
		pool_scenario sc;
		char err[512];
		if (pool_scenario_load_file_limit(o->layout_path, o->max_input, &sc, err, sizeof err) != 0) {
			fprintf(stderr, "%s: --layout: %s\n", PROGRAM, err);
			return POOL_EXIT_BAD_INPUT;
		}
		g->def = sc.def;
		g->state = sc.has_game ? sc.game : pool_game_default_state(g->rules);
		const bool other_rules = sc.has_game && sc.game.rules != g->rules;
		const bool too_many = sc.ball_count > POOL_GAME_MAX_BALLS;
		if (!other_rules && !too_many) {
			g->count = sc.ball_count;
			memcpy(g->balls, sc.balls, (size_t)sc.ball_count * sizeof *sc.balls);
		}
		pool_scenario_free(&sc);
		if (other_rules)
			return pool_cli_usage_error(PROGRAM, "--layout: game.rules: %s, not %s", pool_game_rules_name(g->state.rules),
			                            o->rules_name);
		if (too_many)
			return pool_cli_usage_error(PROGRAM, "--layout: balls: more than %d", POOL_GAME_MAX_BALLS);
		for (int i = 0; i < g->count; ++i)
			if (g->balls[i].motion != POOL_MOTION_STATIONARY)
				return pool_cli_usage_error(PROGRAM, "--layout: balls[%d]: must be at rest on the cloth", i);
	} else {
		g->def = pool_default_sim_def();
		// Three cushion is played on the carom table (UMB: no pockets, carom balls) unless told.
		const char *preset = o->table_preset ? o->table_preset : g->rules == POOL_GAME_THREE_CUSHION ? "carom" : NULL;
		if (preset && use_preset(&g->def, preset))
			return pool_cli_usage_error(PROGRAM, "--table: unknown preset '%s' (wpa-9ft, wpa-8ft, wpa-7ft, snooker, carom)",
			                            pool_cli_arg(preset));
		g->count = pool_game_rack(g->rules, &g->def.table, &g->def.params, GAME_RACK_GAP, g->balls,
		                          POOL_GAME_MAX_BALLS);
		if (g->count < 0) {
			fprintf(stderr, "%s: the opening position does not fit the table\n", PROGRAM);
			return POOL_EXIT_INTERNAL;
		}
		g->state = pool_game_default_state(g->rules);
	}
	if (o->have_target)
		g->state.target_points = (int)o->target;
	pool_error e;
	if (pool_game_check_balls(&g->state, g->balls, g->count, &e) != POOL_OK)
		return pool_cli_usage_error(PROGRAM, "%s%s", o->layout_path ? "--layout: " : "", e.message);
	if (o->noise_spec) {
		if (pool_noise_parse(o->noise_spec, &g->noise, &e) != POOL_OK) {
			char shown[POOL_ESCAPE_SHORT];
			return pool_cli_usage_error(PROGRAM, "--noise: %s",
			                            pool_escape_str(shown, sizeof shown, e.message + strlen("noise: ")));
		}
		g->noisy = g->noise.speed > 0 || g->noise.phi > 0 || g->noise.theta > 0 || g->noise.a > 0 || g->noise.b > 0;
	}
	g->start_count = g->count;
	memcpy(g->start, g->balls, sizeof g->balls);
	return 0;
}

static int index_of(const game *g, int32_t id) {
	for (int i = 0; i < g->count; ++i)
		if (g->balls[i].id == id)
			return i;
	return -1;
}

static void jw_balls(pool_jw *w, const char *key, const pool_ball_state *balls, int count, bool with_state) {
	pool_jw_key(w, key);
	pool_jw_array(w, false);
	for (int i = 0; i < count; ++i) {
		pool_jw_object(w, true);
		pool_jw_key(w, "id");
		pool_jw_int(w, balls[i].id);
		pool_jw_key(w, "pos");
		pool_jw_array(w, true);
		pool_jw_number(w, balls[i].pos.x);
		pool_jw_number(w, balls[i].pos.y);
		pool_jw_end(w, ']');
		if (with_state) {
			pool_jw_key(w, "state");
			pool_jw_string(w, pool_motion_name(balls[i].motion));
		}
		pool_jw_end(w, '}');
	}
	pool_jw_end(w, ']');
}

static void jw_table(pool_jw *w, const pool_sim_def *def) {
	pool_jw_key(w, "table");
	pool_jw_object(w, true);
	pool_jw_key(w, "length");
	pool_jw_number(w, def->table.length);
	pool_jw_key(w, "width");
	pool_jw_number(w, def->table.width);
	pool_jw_key(w, "cushion_height");
	pool_jw_number(w, def->table.cushion_height);
	pool_jw_key(w, "corner_mouth");
	pool_jw_number(w, def->table.corner_mouth);
	pool_jw_key(w, "side_mouth");
	pool_jw_number(w, def->table.side_mouth);
	pool_jw_key(w, "pockets");
	pool_jw_string(w, pool_pockets_model_name(def->table.pockets));
	pool_jw_end(w, '}');
	pool_jw_key(w, "ball_radius");
	pool_jw_number(w, def->params.ball_radius);
}

/// The turn sent to the strategy: one line of JSON.
static char *turn_text(const game *g) {
	pool_jw w;
	pool_jw_init(&w, false);
	pool_jw_object(&w, false);
	pool_jw_key(&w, "shot");
	pool_jw_int(&w, g->shots);
	pool_jw_key(&w, "rules");
	pool_jw_string(&w, pool_game_rules_name(g->rules));
	jw_table(&w, &g->def);
	pool_jw_key(&w, "state");
	pool_jw_game_state(&w, &g->state);
	jw_balls(&w, "balls", g->balls, g->count, false);
	pool_jw_end(&w, '}');
	char *text = pool_jw_finish(&w);
	if (text) // the writer ends the document with a newline; the peer adds its own
		text[strcspn(text, "\n")] = '\0';
	return text;
}

static void jw_strike(pool_jw *w, const char *key, const pool_batch_strike *s) {
	pool_jw_key(w, key);
	pool_jw_object(w, true);
	pool_jw_key(w, "ball");
	pool_jw_int(w, s->ball);
	const char *names[5] = {"speed", "phi", "theta", "a", "b"};
	const double v[5] = {s->speed, s->phi, s->theta, s->a, s->b};
	for (int k = 0; k < 5; ++k) {
		pool_jw_key(w, names[k]);
		pool_jw_number(w, v[k]);
	}
	pool_jw_end(w, '}');
}

typedef struct answer {
	pool_batch_strike strike;
	bool has_cue_pos;
	double cue_pos[2];
} answer;

static int get_number(long shot, const json_t *v, const char *path, double *out) {
	if (!json_is_number(v))
		return shot_error(shot, "%s: must be a number", path);
	const double x = json_number_value(v);
	if (!isfinite(x) || fabs(x) > GAME_MAX_ABS)
		return shot_error(shot, "%s: must be a finite number of at most %g", path, GAME_MAX_ABS);
	*out = x;
	return 0;
}

/// Reads an answer line into the strike, the cue ball's place and the state's call, safety and
/// push out.
static int read_answer(game *g, const char *line, answer *a) {
	const long shot = g->shots;
	json_error_t jerr;
	json_t *root = json_loads(line, JSON_REJECT_DUPLICATES, &jerr);
	if (!root) {
		char shown[POOL_ESCAPE_LONG];
		return shot_error(shot, "malformed JSON at column %d: %s", jerr.column,
		                  pool_escape_str(shown, sizeof shown, jerr.text));
	}
	int status = 0;
	static const char *const fields[] = {"strike", "cue_pos", "call", "safety", "push_out", NULL};
	static const char *const strike_fields[] = {"speed", "phi", "theta", "a", "b", NULL};
	const char *key;
	json_t *value;
	memset(a, 0, sizeof *a);
	a->strike.ball = g->state.cue_ball;
	if (!json_is_object(root)) {
		status = shot_error(shot, "the answer must be a JSON object with a \"strike\"");
		goto done;
	}
	json_object_foreach(root, key, value) {
		bool known = false;
		for (const char *const *f = fields; *f; ++f)
			known = known || strcmp(key, *f) == 0;
		if (!known) {
			char shown[POOL_ESCAPE_SHORT];
			status = shot_error(shot, "%s: unknown field (strike, cue_pos, call, safety, push_out)",
			                    pool_escape_str(shown, sizeof shown, key));
			goto done;
		}
	}
	json_t *strike = json_object_get(root, "strike");
	if (!json_is_object(strike)) {
		status = shot_error(shot, "strike: %s", strike ? "must be an object" : "missing");
		goto done;
	}
	json_object_foreach(strike, key, value) {
		int k = -1;
		for (int j = 0; strike_fields[j]; ++j)
			if (strcmp(key, strike_fields[j]) == 0)
				k = j;
		if (k < 0) {
			char shown[POOL_ESCAPE_SHORT];
			status = shot_error(shot, "strike.%s: unknown field (speed, phi, theta, a, b)",
			                    pool_escape_str(shown, sizeof shown, key));
			goto done;
		}
		double *field[5] = {&a->strike.speed, &a->strike.phi, &a->strike.theta, &a->strike.a, &a->strike.b};
		char path[32];
		snprintf(path, sizeof path, "strike.%s", strike_fields[k]);
		if ((status = get_number(shot, value, path, field[k])) != 0)
			goto done;
	}
	if (!json_object_get(strike, "speed")) {
		status = shot_error(shot, "strike.speed: missing");
		goto done;
	}
	json_t *cue_pos = json_object_get(root, "cue_pos");
	if (cue_pos) {
		if (!json_is_array(cue_pos) || json_array_size(cue_pos) != 2) {
			status = shot_error(shot, "cue_pos: must be [x, y] (m)");
			goto done;
		}
		for (int k = 0; k < 2 && status == 0; ++k)
			status = get_number(shot, json_array_get(cue_pos, (size_t)k), k ? "cue_pos[1]" : "cue_pos[0]",
			                    &a->cue_pos[k]);
		if (status)
			goto done;
		if (!g->state.ball_in_hand) {
			status = shot_error(shot, "cue_pos: the cue ball is not in hand (the rules put it in hand after a foul)");
			goto done;
		}
		a->has_cue_pos = true;
	}
	// The call, safety and push out go into the state the rules judge the shot with.
	json_t *state = json_object(), *call = json_object_get(root, "call");
	if (call)
		json_object_set(state, "called", call);
	if (json_object_get(root, "safety"))
		json_object_set(state, "safety", json_object_get(root, "safety"));
	if (json_object_get(root, "push_out"))
		json_object_set(state, "push_out", json_object_get(root, "push_out"));
	pool_game_state parsed;
	char err[300];
	if (json_object_size(state) > 0) {
		// Parse over the current state: the answer's keys on top of the game's own.
		pool_jw w;
		pool_jw_init(&w, false);
		pool_jw_game_state(&w, &g->state);
		char *text = pool_jw_finish(&w);
		json_t *base = text ? json_loads(text, 0, NULL) : NULL;
		free(text);
		if (base)
			json_object_update(base, state);
		if (!base || pool_game_json_parse_state(base, "answer", g->rules, &parsed, err, sizeof err) != 0) {
			if (base) {
				status = shot_error(shot, "%s", err);
			} else {
				fprintf(stderr, "%s: out of memory\n", PROGRAM);
				status = POOL_EXIT_INTERNAL;
			}
			json_decref(base);
			json_decref(state);
			goto done;
		}
		json_decref(base);
		parsed.player = g->state.player;
		g->state = parsed;
	}
	json_decref(state);
done:
	json_decref(root);
	return status;
}

/// Puts the balls of the table into the simulation, the cue ball where the answer places it.
static int set_up_shot(game *g, const answer *a) {
	const long shot = g->shots;
	pool_error e;
	pool_result r = g->sim ? pool_sim_reset(g->sim, &g->def, &e) : pool_sim_create(&g->def, &g->sim, &e);
	if (r != POOL_OK) {
		fprintf(stderr, "%s: %s\n", PROGRAM, e.message);
		return pool_cli_result_status(r);
	}
	const int32_t cue = g->state.cue_ball;
	const int at = index_of(g, cue);
	if (g->state.ball_in_hand && at < 0 && !a->has_cue_pos)
		return shot_error(shot, "cue_pos: missing (the cue ball is in hand and off the table)");
	if (a->has_cue_pos) {
		const pool_ball_state placed = {.id = cue, .motion = POOL_MOTION_STATIONARY,
		                                .pos = {a->cue_pos[0], a->cue_pos[1], g->def.params.ball_radius}};
		if (at >= 0)
			g->balls[at] = placed;
		else
			g->balls[g->count++] = placed;
	}
	// A placed cue ball goes in last, so that the library's refusal (an overlap, off the table)
	// is about it and is reported as the answer's cue_pos.
	for (int pass = 0; pass < 2; ++pass)
		for (int i = 0; i < g->count; ++i) {
			const bool placed = g->balls[i].id == cue && a->has_cue_pos;
			if (placed != (pass == 1))
				continue;
			if ((r = pool_sim_add_ball(g->sim, &g->balls[i], &e)) != POOL_OK) {
				const char *colon = strchr(e.message, ':');
				if (placed)
					return shot_error(shot, "cue_pos:%s", colon ? colon + 1 : e.message);
				fprintf(stderr, "%s: shot %ld: %s\n", PROGRAM, shot, e.message);
				return pool_cli_result_status(r);
			}
		}
	return 0;
}

/// The table after the shot: the balls at rest, without those pocketed or off the table, with
/// the ones the rules spot put back.
static int next_table(game *g, const pool_game_result *result) {
	pool_ball_state final[POOL_GAME_MAX_BALLS];
	if (pool_sim_state_at(g->sim, pool_sim_end_time(g->sim), final) != POOL_OK)
		return -1;
	int n = 0;
	for (int i = 0; i < g->count; ++i) {
		if (final[i].motion == POOL_MOTION_POCKETED || final[i].motion == POOL_MOTION_OFF_TABLE)
			continue;
		// A shot cut at max_time leaves balls moving: the next one starts from where they are.
		g->balls[n] = final[i];
		g->balls[n].motion = POOL_MOTION_STATIONARY;
		g->balls[n].vel = g->balls[n].omega = (pool_vec3){0, 0, 0};
		g->balls[n].pos.z = g->def.params.ball_radius;
		++n;
	}
	g->count = n;
	for (int k = 0; k < result->spot_count; ++k) {
		pool_vec3 pos;
		if (pool_game_spot_position(&result->next, result->spot[k], &g->def.table, g->def.params.ball_radius, g->balls,
		                            g->count, &pos) != POOL_OK)
			continue; // no room on the long string: the ball stays off (documented)
		g->balls[g->count++] = (pool_ball_state){.id = result->spot[k], .motion = POOL_MOTION_STATIONARY, .pos = pos};
	}
	return 0;
}

static int play_shot(game *g, game_peer *peer, bool *over) {
	const long shot = g->shots;
	char *turn = turn_text(g);
	if (!turn) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	const int sent = game_peer_send(peer, turn);
	free(turn);
	bool too_long = false;
	const char *line = sent == 0 ? game_peer_read(peer, GAME_MAX_ANSWER, &too_long) : NULL;
	if (too_long)
		return shot_error(shot, "the answer is longer than %d bytes", GAME_MAX_ANSWER);
	if (!line) {
		g->end = peer->pid ? "strategy_ended" : "no_more_strikes";
		*over = true;
		return 0;
	}
	const pool_game_state before_answer = g->state;
	answer a;
	int status = read_answer(g, line, &a);
	if (status == 0)
		status = set_up_shot(g, &a);
	if (status) {
		g->state = before_answer;
		return status;
	}
	const pool_batch_strike nominal = a.strike;
	const pool_batch_strike simulated = g->noisy ? pool_batch_noisy(&nominal, &g->noise, (uint64_t)g->o->seed,
	                                                                (uint64_t)shot)
	                                             : nominal;
	if (!(simulated.theta >= 0.0 && simulated.theta < 90.0))
		return shot_error(shot, "strike.theta: must be in [0, 90) degrees");
	const pool_strike strike = {.speed = simulated.speed, .phi = simulated.phi * POOL_DEGREE,
	                            .theta = simulated.theta * POOL_DEGREE, .a = simulated.a, .b = simulated.b};
	pool_error e;
	pool_result r = pool_sim_strike(g->sim, simulated.ball, &strike, &e);
	if (r != POOL_OK) {
		if (pool_cli_result_status(r) == POOL_EXIT_INTERNAL) {
			fprintf(stderr, "%s: shot %ld: %s\n", PROGRAM, shot, e.message);
			return POOL_EXIT_INTERNAL;
		}
		return shot_error(shot, "%s%s", strncmp(e.message, "strike", 6) == 0 ? "" : "strike: ", e.message);
	}
	if ((r = pool_sim_run(g->sim)) != POOL_OK) {
		fprintf(stderr, "%s: shot %ld: simulation failed at t = %.17g s: %s\n", PROGRAM, shot,
		        pool_sim_time(g->sim), pool_sim_last_error(g->sim)[0] ? pool_sim_last_error(g->sim) : pool_result_str(r));
		return POOL_EXIT_INTERNAL;
	}
	const pool_game_shot gs = pool_game_shot_of_sim(g->sim);
	pool_game_result result;
	if (pool_game_judge(&g->state, &gs, &g->def.table, &result, &e) != POOL_OK)
		return shot_error(shot, "%s", e.message);

	pool_jw *w = &g->record;
	pool_jw_object(w, false);
	pool_jw_key(w, "shot");
	pool_jw_int(w, shot);
	pool_jw_key(w, "player");
	pool_jw_int(w, g->state.player);
	pool_jw_key(w, "state");
	pool_jw_game_state(w, &g->state);
	pool_jw_key(w, "cue_pos");
	if (a.has_cue_pos) {
		pool_jw_array(w, true);
		pool_jw_number(w, a.cue_pos[0]);
		pool_jw_number(w, a.cue_pos[1]);
		pool_jw_end(w, ']');
	} else {
		pool_jw_null(w);
	}
	jw_strike(w, "strike", &simulated);
	if (g->noisy)
		jw_strike(w, "nominal", &nominal);
	pool_jw_key(w, "events");
	pool_jw_int(w, gs.event_count);
	pool_jw_key(w, "result");
	pool_jw_game_result(w, g->rules, &result);
	if (next_table(g, &result) != 0) {
		fprintf(stderr, "%s: shot %ld: the final states could not be read\n", PROGRAM, shot);
		return POOL_EXIT_INTERNAL;
	}
	jw_balls(w, "balls", g->balls, g->count, false);
	pool_jw_end(w, '}');
	g->shots++;
	if (result.outcome == POOL_OUTCOME_WIN || result.outcome == POOL_OUTCOME_LOSS) {
		g->winner = result.outcome == POOL_OUTCOME_WIN ? g->state.player : 1 - g->state.player;
		g->end = pool_game_outcome_name(result.outcome);
		*over = true;
	}
	g->state = result.next;
	return 0;
}

static int play(game *g) {
	const game_options *o = g->o;
	game_peer peer;
	if (o->strategy) {
		if (game_peer_start(&peer, o->strategy) != 0) {
			fprintf(stderr, "%s: --strategy: cannot start it: %s\n", PROGRAM, strerror(errno));
			return POOL_EXIT_INTERNAL;
		}
	} else {
		game_peer_stdin(&peer);
	}
	pool_jw_init(&g->record, true);
	pool_jw_object(&g->record, false);
	pool_jw_key(&g->record, "format");
	pool_jw_string(&g->record, "libpool-game/1");
	pool_jw_key(&g->record, "rules");
	pool_jw_string(&g->record, pool_game_rules_name(g->rules));
	jw_table(&g->record, &g->def);
	pool_jw_key(&g->record, "noise");
	if (g->noisy) {
		pool_jw_object(&g->record, true);
		pool_jw_key(&g->record, "speed");
		pool_jw_number(&g->record, g->noise.speed);
		pool_jw_key(&g->record, "phi");
		pool_jw_number(&g->record, g->noise.phi / POOL_DEGREE);
		pool_jw_key(&g->record, "theta");
		pool_jw_number(&g->record, g->noise.theta / POOL_DEGREE);
		pool_jw_key(&g->record, "a");
		pool_jw_number(&g->record, g->noise.a);
		pool_jw_key(&g->record, "b");
		pool_jw_number(&g->record, g->noise.b);
		pool_jw_end(&g->record, '}');
		pool_jw_key(&g->record, "seed");
		pool_jw_int(&g->record, o->seed);
	} else {
		pool_jw_null(&g->record);
	}
	jw_balls(&g->record, "start", g->start, g->start_count, false);
	pool_jw_key(&g->record, "shots");
	pool_jw_array(&g->record, false);
	int status = 0;
	bool over = false;
	while (!over && status == 0) {
		if (g->shots >= o->max_shots) {
			g->end = "max_shots";
			break;
		}
		status = play_shot(g, &peer, &over);
	}
	const int peer_status = game_peer_close(&peer);
	if (status != 0) {
		pool_jw_discard(&g->record);
		return status;
	}
	pool_jw_end(&g->record, ']');
	pool_jw_key(&g->record, "end");
	pool_jw_string(&g->record, g->end);
	pool_jw_key(&g->record, "winner");
	if (g->winner >= 0)
		pool_jw_int(&g->record, g->winner);
	else
		pool_jw_null(&g->record);
	pool_jw_key(&g->record, "next_state");
	pool_jw_game_state(&g->record, &g->state);
	pool_jw_end(&g->record, '}');
	char *text = pool_jw_finish(&g->record);
	if (!text) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	status = pool_cli_write_output(PROGRAM, o->output, text);
	free(text);
	if (status == 0 && peer_status != 0) {
		fprintf(stderr, "%s: --strategy: exited with status %d (the record is written)\n", PROGRAM, peer_status);
		status = POOL_EXIT_INTERNAL;
	}
	return status;
}

int main(int argc, char **argv) {
	game_options o;
	int status = parse_options(argc, argv, &o);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	game *g = calloc(1, sizeof *g);
	if (!g) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	g->o = &o;
	status = setup(g);
	if (status == 0)
		status = play(g);
	pool_sim_destroy(g->sim);
	free(g);
	return status;
}
