// A position to plan, from a scenario file: the scenario parser reads the balls, table and models;
// the "game" is read here, since a planned position has no strike yet (pool-sim's parser wants
// one with a game).
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aim_tool.h"
#include "game_json.h"

int aim_position_parse(const char *json, size_t length, aim_position *out, char *err, size_t err_size) {
	memset(out, 0, sizeof *out);
	json_error_t jerr;
	json_t *root = json_loadb(json, length, JSON_REJECT_DUPLICATES, &jerr);
	if (!json_is_object(root)) { // the scenario parser's own message for what is not an object
		json_decref(root);
		return pool_scenario_parse(json, length, &out->scenario, err, err_size) == 0 ? 0 : -1;
	}
	json_t *game = json_incref(json_object_get(root, "game"));
	char *rest = NULL;
	if (game) {
		json_object_del(root, "game");
		rest = json_dumps(root, JSON_COMPACT);
	}
	json_decref(root);
	if (game && !rest) {
		json_decref(game);
		snprintf(err, err_size, "out of memory");
		return -1;
	}
	int status = rest ? pool_scenario_parse(rest, strlen(rest), &out->scenario, err, err_size)
	                  : pool_scenario_parse(json, length, &out->scenario, err, err_size);
	free(rest);
	if (status == 0 && game) {
		status = pool_game_json_parse(game, "game", &out->game, err, err_size);
		pool_error e;
		if (status == 0 && pool_game_check_balls(&out->game, out->scenario.balls, out->scenario.ball_count, &e) != POOL_OK) {
			snprintf(err, err_size, "%s", e.message);
			status = -1;
		}
		out->has_game = status == 0;
	}
	json_decref(game);
	if (status != 0) {
		aim_position_free(out);
		return -1;
	}
	out->cue_ball = out->scenario.has_strike ? out->scenario.strike_ball : out->has_game ? out->game.cue_ball : 0;
	return 0;
}

void aim_position_free(aim_position *p) {
	pool_scenario_free(&p->scenario);
	memset(p, 0, sizeof *p);
}

pool_aim_def aim_position_def(const aim_position *p) {
	pool_aim_def d = pool_default_aim_def();
	d.sim = p->scenario.def;
	d.balls = p->scenario.balls;
	d.ball_count = p->scenario.ball_count;
	d.cue_ball = p->cue_ball;
	d.game = p->has_game ? &p->game : NULL;
	return d;
}
