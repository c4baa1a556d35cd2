// libpool scenario: the files the commands, the comparison harness, Python and users exchange
// (docs/interfaces.md). A libpool-scenario/1 document is parsed and validated into what libpool
// needs (a pool_sim_def, the balls, a strike, a game's rules); a finished simulation is written as
// a libpool-result/1 document. Messages name the field as the file spells it ("balls[2].pos:
// overlaps ball 1 by 0.003 m"). Link libpool_scenario (it uses jansson, which this header does
// not expose), libpool_games and libpool.
#ifndef POOL_SCENARIO_H
#define POOL_SCENARIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pool/game.h"
#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// The "format" of a scenario document.
#define POOL_SCENARIO_FORMAT "libpool-scenario/1"
/// The "format" of a result document.
#define POOL_RESULT_FORMAT "libpool-result/1"
/// Most balls a scenario may hold: the overlap check is quadratic, and no table holds more than a
/// few dozen balls anyway.
#define POOL_SCENARIO_MAX_BALLS 10000
/// Largest magnitude of a number in a scenario: nothing on a pool table is 1e9 m, s or rad/s,
/// and larger values only overflow the quartic coefficients.
#define POOL_SCENARIO_MAX_ABS 1e9
/// A buffer this long holds every message of the parser whole (a shorter one gets it cut).
#define POOL_SCENARIO_MESSAGE_SIZE 512
/// Default limit on the size of a JSON input read from a file (64 MiB): scenarios are a few
/// kilobytes (10000 balls, the parser's limit, are about 1 MB), and a pool-sim result of a
/// 16-ball break sampled as finely as it can be (20000 grid instants) is under 10 MB. Parsing
/// takes up to about 20 times the input in memory (jansson, a 60 MiB array of zeros: 1.3 GB).
#define POOL_INPUT_DEFAULT_MAX ((size_t)64 << 20)

/// A strike as scenario files and batches write it: the cue's angles in degrees.
typedef struct pool_batch_strike {
	int32_t ball; ///< id of the struck ball
	double speed; ///< m/s
	double phi;   ///< degrees
	double theta; ///< degrees
	double a, b;  ///< m
} pool_batch_strike;

/// A parsed, validated scenario.
typedef struct pool_scenario {
	pool_sim_def def;          ///< table, params, airborne, max_time, max_events, models
	int ball_count;            ///< number of balls
	pool_ball_state *balls;    ///< owned; z = R where the file gave [x, y]
	bool has_strike;           ///< whether a strike is applied at t = 0
	int strike_ball;           ///< id of the struck ball
	pool_strike strike;        ///< cue parameters, angles in radians (degrees * POOL_DEGREE)
	pool_batch_strike written; ///< the same strike as the file gives it, angles in degrees
	bool has_game;             ///< "game" given: the shot is judged by these rules (needs a strike)
	pool_game_state game;      ///< the rules and the state before the shot
} pool_scenario;

/// Radians in a degree, the factor by which the parser converts strike.phi and strike.theta
/// (and table cut angles): x * POOL_DEGREE is bit for bit the parser's conversion of x.
#define POOL_DEGREE (3.14159265358979323846 / 180.0)

/// Parses and validates a scenario document of length bytes (no NUL needed). Returns 0, or -1
/// with a message naming the field in err (err_size bytes, POOL_SCENARIO_MESSAGE_SIZE is enough;
/// err may be NULL); on failure *scenario is empty. Planar scenarios (options.airborne false) are
/// checked with the library's own rules (a ball sits on the cloth, z = R, with no vertical
/// velocity). Airborne scenarios accept 3D positions with z >= R (within POOL_TOUCH_TOLERANCE;
/// "balls[i].pos: below the cloth") and vertical velocities and refuse 3D interpenetration. A
/// "table" may be a preset name. The library's messages about its def (def.airborne,
/// def.max_time...) are reported with the file's names (options.airborne...).
POOL_API int pool_scenario_parse(const char *json, size_t length, pool_scenario *scenario, char *err,
                                 size_t err_size);

/// Same, from a file ("-" = standard input) of at most POOL_INPUT_DEFAULT_MAX bytes. Files,
/// pipes, FIFOs, devices and standard input are read alike.
POOL_API int pool_scenario_load_file(const char *path, pool_scenario *scenario, char *err, size_t err_size);

/// Same with a limit of max_bytes bytes: a longer input is refused with "NAME: input is larger than
/// the limit of N bytes" (NAME the escaped path or "standard input").
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
	const pool_sim_def *def;     ///< optional; when set, "table", "ball_radius", "params" and
	                             ///< "models" are written too
	const pool_game_state *game; ///< optional; when set, the shot is judged under these rules and
	                             ///< "game" is written after "stats" (docs/interfaces.md "Games")
} pool_result_options;

/// The libpool-result/1 document of a finished (or stopped) simulation, malloc'd, NUL-terminated
/// (release it with free, or pool_scenario_text_free); NULL on allocation failure.
/// Byte-identical for identical simulations.
POOL_API char *pool_result_json(const pool_sim *sim, const pool_result_options *options);

/// Frees a text this library returned (pool_result_json), for callers that cannot reach the C
/// library's free (ctypes, other languages' bindings). NULL is ignored.
POOL_API void pool_scenario_text_free(char *text);

#ifdef __cplusplus
}
#endif

#endif
