// The "game" of scenario and result files (docs/interfaces.md "Games", docs/games.md): the rules
// and the state before a shot in a scenario, the judged shot in a result. Shared by pool-sim,
// pool-batch, pool-sensitivity, pool-game and the LCM services.
#ifndef POOL_TOOLS_GAME_JSON_H
#define POOL_TOOLS_GAME_JSON_H

#include <jansson.h>
#include <stddef.h>

#include "json_writer.h"
#include "pool/game.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A state as a file gives it when it says nothing: a shot in the middle of a rack (no break,
/// nothing in hand, open table, no fouls, no points, cue balls 0 and 1).
pool_game_state pool_game_json_default_state(pool_game_rules rules);

/// Parses a "game" object, {"rules": NAME, "state": {...}} (path names it in messages, e.g.
/// "game"), into *state and checks its ranges. Returns 0, or -1 with a message naming the field
/// ("game.state.fouls: must be an integer") in err.
int pool_game_json_parse(const json_t *game, const char *path, pool_game_state *state, char *err,
                         size_t err_size);

/// Parses a "state" object alone for the given rules (pool-game's strategy replies carry none).
int pool_game_json_parse_state(const json_t *object, const char *path, pool_game_rules rules,
                               pool_game_state *state, char *err, size_t err_size);

/// Writes a state object: the fields of its game, so it reads back to the same state.
void pool_jw_game_state(pool_jw *w, const pool_game_state *state);

/// Writes a judged shot's object: rules, legal, fouls, outcome, reason, ball_in_hand,
/// behind_head_string, rerack_option, pass_option, points, first_hit, rails_after_contact,
/// cue_cushions, pocketed, pockets, off_table, spot and the next shot's state.
void pool_jw_game_result(pool_jw *w, pool_game_rules rules, const pool_game_result *result);

/// The fouls as names joined by sep ("scratch no_rail"); out holds size bytes.
void pool_game_foul_list(uint32_t fouls, const char *sep, char *out, size_t size);

/// Pocket by name ("ne"), or POOL_POCKET_NONE.
pool_pocket pool_game_pocket_from_name(const char *name);

#ifdef __cplusplus
}
#endif

#endif
