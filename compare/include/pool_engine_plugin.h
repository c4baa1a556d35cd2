// The engine plugin ABI of the comparison harness: one small C interface per engine, loaded
// from a shared module (dlopen) by name or path, so new engines need no harness rebuild.
//
// A plugin exports one symbol:
//     const pool_engine_api *pool_engine_plugin(void);
// and everything else goes through the returned table.
#ifndef POOL_ENGINE_PLUGIN_H
#define POOL_ENGINE_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Bumped on any incompatible change; the harness refuses other versions.
#define POOL_ENGINE_ABI_VERSION 1

/// Name of the symbol a plugin exports.
#define POOL_ENGINE_ENTRY "pool_engine_plugin"

/// Settings the harness passes to create().
typedef struct pool_engine_config {
	double dt;       ///< s, time step of time-stepped engines (ignored by event-driven ones)
	uint64_t flags;  ///< reserved, 0
} pool_engine_config;

/// One ball as the engine sees it (state codes as pool_motion: 0 stationary, 1 spinning,
/// 2 sliding, 3 rolling, 4 airborne, 6 pocketed, 7 off table).
typedef struct pool_engine_ball {
	int32_t id;       ///< scenario id
	int32_t state;    ///< motion state code
	double pos[3];    ///< m
	double vel[3];    ///< m/s
	double omega[3];  ///< rad/s
} pool_engine_ball;

/// Event kinds an engine reports (the subset of libpool's it can detect).
typedef enum pool_engine_event_type {
	POOL_ENGINE_EVENT_BALL_BALL = 4,    ///< first step of a new ball-ball contact
	POOL_ENGINE_EVENT_BALL_CUSHION = 5, ///< first step of a new ball-cushion contact
	POOL_ENGINE_EVENT_SLIDE_ROLL = 1,   ///< slip fell below the rolling threshold
	POOL_ENGINE_EVENT_ROLL_STOP = 2,    ///< speed fell to zero / below the rest threshold
	POOL_ENGINE_EVENT_POCKET = 7,       ///< ball fell into a pocket
	/// A flying ball lands on the cloth (or a strike or cushion presses it into the cloth):
	/// first step of a new ball-cloth contact approaching it; ball_b = -1. Airborne mode only.
	/// Added without changing the ABI version: plugins that never report it are as before.
	POOL_ENGINE_EVENT_BALL_TABLE = 6,
} pool_engine_event_type;

/// An event as an engine detected it.
typedef struct pool_engine_event {
	double t;        ///< s
	int32_t type;    ///< pool_engine_event_type
	int32_t ball_a;  ///< id
	int32_t ball_b;  ///< id of the other ball; for BALL_CUSHION the cushion as
	                 ///< POOL_ENGINE_CUSHION(rail), or -1 if the engine does not say; else -1
} pool_engine_event;

/// ball_b of a ball-cushion event that says which rail was hit: rail 0 south (y = 0), 1 north
/// (y = W), 2 west (x = 0), 3 east (x = L), as libpool's pool_rail. -1 still means "a cushion"
/// (plugins written before this convention), so the struct and ABI version are unchanged.
#define POOL_ENGINE_CUSHION(rail) (-2 - (int32_t)(rail))

/// Counters an engine reports.
typedef struct pool_engine_stats {
	int64_t steps;           ///< time steps taken (events for event-driven engines)
	double max_penetration;  ///< m, deepest ball-ball or ball-cushion interpenetration seen
	double sim_time;         ///< s, simulated time reached
} pool_engine_stats;

/// The function table a plugin returns. Every function returns 0 on success or a negative
/// value with a message in err (create) / from last_error (the others).
typedef struct pool_engine_api {
	int abi_version;          ///< POOL_ENGINE_ABI_VERSION
	const char *name;         ///< "libpool", "ode", "bullet", ...
	const char *description;  ///< one line: engine, version, what it can't model
	int event_driven;         ///< 1 for exact event-driven engines (dt ignored)

	/// Builds the engine from a libpool-scenario/1 JSON document (strike applied as initial
	/// velocities). NULL on failure with a message in err.
	void *(*create)(const char *scenario_json, const pool_engine_config *config, char *err,
	                size_t err_size);
	/// Advances to absolute time t (s).
	int (*advance)(void *engine, double t);
	/// Advances until every ball is at rest or max_time is reached.
	int (*run_to_rest)(void *engine, double max_time);
	/// Writes up to capacity balls; returns how many the engine has.
	int (*balls)(void *engine, pool_engine_ball *out, int capacity);
	/// Events detected so far; returns how many (writes up to capacity).
	int (*events)(void *engine, pool_engine_event *out, int capacity);
	/// Counters so far.
	void (*stats)(void *engine, pool_engine_stats *out);
	/// Message of the last failure.
	const char *(*last_error)(void *engine);
	/// Frees the engine; NULL is a no-op.
	void (*destroy)(void *engine);
} pool_engine_api;

/// The one exported entry point.
typedef const pool_engine_api *(*pool_engine_entry_fn)(void);

/// Optional second export, looked up by name (added without changing the ABI version: a plugin
/// without it says nothing about models, and its records have "unsupported_models": null):
///     int pool_engine_unsupported_models(const char *scenario_json, char *out, size_t out_size);
/// Writes into out the models the scenario selects (its "models" object, docs/physics.md
/// "Models") that the engine cannot express, as "kind=name" separated by commas
/// ("cushion=mathavan2010,squirt=endmass"; "" when it expresses them all) and returns how many,
/// or -1 with the parser's message in out for a scenario it cannot read. The engine still runs
/// such a scenario with the laws it has; the harness records the list next to the errors.
#define POOL_ENGINE_MODELS_ENTRY "pool_engine_unsupported_models"

/// The optional models query.
typedef int (*pool_engine_models_fn)(const char *scenario_json, char *out, size_t out_size);

/// Optional third export, looked up by name (added without changing the ABI version: a plugin
/// without it says nothing, and its records have "link_cpu_share": null):
///     int pool_engine_link_stats(void *engine, pool_engine_link_info *out);
/// What the engine's persistent-contact steps (libpool's LINK, docs/physics.md) cost in the run so
/// far. The plugin times its own calls (the library has no clock): step_seconds is the time of
/// every simulation step, link_seconds the part spent in steps that produced a link event.
/// Returns 0, or -1 when it cannot say.
#define POOL_ENGINE_LINK_ENTRY "pool_engine_link_stats"

/// Persistent-contact counters of one run (POOL_ENGINE_LINK_ENTRY).
typedef struct pool_engine_link_info {
	double step_seconds;  ///< s, wall-clock time of every simulation step of the run
	double link_seconds;  ///< s, the part of it in steps that produced a link event
	int64_t link_steps;   ///< LCP solves (libpool: pool_link_stats.steps)
	int64_t link_events;  ///< link_begin, link_step and link_end events
	int64_t clusters;     ///< clusters formed (link_begin events)
} pool_engine_link_info;

/// The optional persistent-contact query.
typedef int (*pool_engine_link_fn)(void *engine, pool_engine_link_info *out);

#ifdef __cplusplus
}
#endif

#endif
