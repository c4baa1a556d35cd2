// Scenario files (libpool-scenario/1) and result files (libpool-result/1): parsing, validation
// and writing, shared by pool-sim, the comparison harness and the LCM services.
// Uses jansson; libpool itself never parses JSON.
#ifndef POOL_SCENARIO_H
#define POOL_SCENARIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "pool/game.h"
#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A parsed, validated scenario. Angles of the strike are already in radians.
typedef struct pool_scenario {
	pool_sim_def def;        ///< table, params, airborne, max_time, max_events, models
	int ball_count;          ///< number of balls
	pool_ball_state *balls;  ///< owned; z = R where the file gave [x, y]
	bool has_strike;         ///< whether a strike is applied at t = 0
	int strike_ball;         ///< id of the struck ball
	pool_strike strike;      ///< cue parameters (radians)
	bool has_game;           ///< "game" given: the shot is judged by these rules (needs a strike)
	pool_game_state game;    ///< the rules and the state before the shot (game_json.h)
} pool_scenario;

/// Parses and validates a scenario document. Returns 0, or -1 with a message naming the field
/// in err (e.g. "balls[2].pos: overlaps ball 1 by 0.003 m"). On failure *scenario is empty.
/// Planar scenarios (options.airborne false) are checked with the library's own rules (a ball
/// must sit on the cloth, z = R, with no vertical velocity). Airborne scenarios accept 3D
/// positions with z >= R (within POOL_TOUCH_TOLERANCE; "balls[i].pos: below the cloth") and
/// vertical velocities and refuse 3D interpenetration. A "table" may be a preset name. The
/// library's messages about its def (def.airborne, def.max_time...) are reported with the
/// file's names (options.airborne...).
POOL_API int pool_scenario_parse(const char *json, size_t length, pool_scenario *scenario, char *err,
                        size_t err_size);

/// Same, from a file ("-" = standard input) of at most POOL_INPUT_DEFAULT_MAX bytes (64 MiB;
/// read_input.h). Files, pipes, FIFOs, devices and standard input are read alike.
POOL_API int pool_scenario_load_file(const char *path, pool_scenario *scenario, char *err,
                            size_t err_size);

/// Same with a limit of max_bytes bytes: a longer input is refused with "NAME: input is larger
/// than the limit of N bytes" (NAME the escaped path or "standard input").
POOL_API int pool_scenario_load_file_limit(const char *path, size_t max_bytes, pool_scenario *scenario,
                                  char *err, size_t err_size);

/// Releases what parse allocated; safe on a zeroed or already-freed scenario.
POOL_API void pool_scenario_free(pool_scenario *scenario);

/// Puts the scenario's balls and strike into a simulation (reset with the scenario's def).
/// Creates *sim when it is NULL. Returns POOL_OK or an error with its message in err.
POOL_API pool_result pool_scenario_setup(const pool_scenario *scenario, pool_sim **sim, pool_error *err);

/// Options of the result writer.
typedef struct pool_result_options {
	double sample_dt; ///< s; > 0 adds "samples": trajectories sampled every sample_dt
	bool pretty;      ///< indent the JSON
	const pool_sim_def *def; ///< optional; when set, "table" and "ball_radius" are written too,
	                         ///< and "models" when they are not the defaults (models_json.h)
	const pool_game_state *game; ///< optional; when set, the shot is judged under these rules and
	                             ///< "game" is written after "stats" (docs/interfaces.md "Games")
} pool_result_options;

/// The libpool-result/1 document of a finished (or stopped) simulation, malloc'd, NUL-terminated;
/// NULL on allocation failure. Byte-identical for identical simulations.
POOL_API char *pool_result_json(const pool_sim *sim, const pool_result_options *options);

#ifdef __cplusplus
}
#endif

#endif
