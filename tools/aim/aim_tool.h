// pool-aim's pieces, shared with the LCM shot planner (tools/lcm/aim_server.c): a position read
// from a scenario (position.c), the options a request may set (options.c), the ranked shots as
// JSON and text (report.c) and drawn on the table (svg.c). docs/commands.md "pool-aim".
#ifndef POOL_TOOLS_AIM_TOOL_H
#define POOL_TOOLS_AIM_TOOL_H

#include <stdbool.h>
#include <stddef.h>

#include "pool/aim.h"
#include "pool/scenario.h"

/// A position to plan: a scenario's balls, table and models, its "game" (without needing a
/// strike: the strike, if any, only names the cue ball), and the cue ball.
typedef struct aim_position {
	pool_scenario scenario;
	bool has_game;
	pool_game_state game;
	int32_t cue_ball; ///< the scenario's struck ball, else the game's cue ball, else 0
} aim_position;

/// Parses a libpool-scenario/1 document as a position. Returns 0, or -1 with the message naming
/// the field in err.
int aim_position_parse(const char *json, size_t length, aim_position *out, char *err, size_t err_size);
void aim_position_free(aim_position *p);

/// The search of a position with the library's defaults (pool_default_aim_def).
pool_aim_def aim_position_def(const aim_position *p);

/// Parses --noise (a preset name or NAME=SD pairs, pool_noise_parse); --kinds (names
/// comma-separated, "all"); --pocket (a pocket name). Return 0, or -1 with the message in err.
int aim_parse_noise(const char *spec, pool_noise *noise, char *err, size_t err_size);
int aim_parse_kinds(const char *spec, unsigned *kinds, char *err, size_t err_size);
int aim_parse_pocket(const char *name, pool_pocket *pocket, char *err, size_t err_size);

/// The ranked shots as the JSON list of docs/interfaces.md "Shot planning" (angles in degrees).
char *aim_report_json(const pool_aim_shot *shots, int count, int32_t cue_ball);
/// The same as a table, and the search's statistics, for people.
char *aim_report_text(const pool_aim_shot *shots, int count, const pool_aim_stats *stats);
/// The position and the shots drawn on the table: each shot's cue ball path (dashed) and potted
/// ball's path (solid) without noise, numbered by rank, and a legend.
char *aim_svg(const pool_aim_def *def, const pool_aim_shot *shots, int count);

#endif
