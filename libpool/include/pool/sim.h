// libpool: the event-driven simulation of a shot.
#ifndef POOL_SIM_H
#define POOL_SIM_H

#include <stdbool.h>
#include <stdint.h>

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/strike.h"
#include "pool/table.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Opaque simulation: a table, its balls, the event queue and the history of the shot.
typedef struct pool_sim pool_sim;

/// Overlap below which two balls count as touching, not interpenetrating (rounding of racks).
#define POOL_TOUCH_TOLERANCE 1e-9

/// Cushion law (docs/physics.md "Cushion" and "Models"). The values travel in files and messages:
/// they never change.
typedef enum pool_cushion_model {
	POOL_CUSHION_PETIT = 0,       ///< "petit": Petit's 3D impulse (the 2012 work's law, "thesis")
	POOL_CUSHION_MATHAVAN2010 = 1 ///< "mathavan2010": cushion and cloth contacts through the impact (the default)
} pool_cushion_model;

/// Ball-ball friction law.
typedef enum pool_ball_friction_model {
	POOL_BALL_FRICTION_CONSTANT = 0, ///< "constant": params.mu_ball (the 2012 work's law, "thesis")
	POOL_BALL_FRICTION_ALCIATORE = 1 ///< "alciatore": throw_a + throw_b exp(-throw_c v_rel) (the default)
} pool_ball_friction_model;

/// Squirt of an off-centre strike.
typedef enum pool_squirt_model {
	POOL_SQUIRT_NONE = 0,   ///< "none": the ball leaves along the cue (the default, and "thesis")
	POOL_SQUIRT_ENDMASS = 1 ///< "endmass": turned by the cue end mass (params.cue_end_mass)
} pool_squirt_model;

/// The laws of a simulation. pool_default_models() are the measured laws; a zero-initialised
/// pool_models is the "thesis" set, the 2012 work's laws (Petit cushions, constant mu_ball, no
/// squirt), which were the defaults before issue 25.
typedef struct pool_models {
	pool_cushion_model cushion;
	pool_ball_friction_model ball_ball_friction;
	pool_squirt_model squirt;
} pool_models;

/// The default laws: "mathavan2010" cushions, "alciatore" ball-ball friction, squirt "none".
POOL_API pool_models pool_default_models(void);

/// The "thesis" model set: "petit", "constant", "none" (all zero), the 2012 work's laws; a def with
/// them simulates bit for bit as libpool's defaults did before issue 25.
POOL_API pool_models pool_thesis_models(void);

/// Model set by name: "default" (pool_default_models) or "thesis" (pool_thesis_models);
/// POOL_ERR_UNKNOWN_PRESET for another name (*models unchanged), POOL_ERR_INVALID_ARGUMENT for NULL.
POOL_API pool_result pool_models_preset(const char *name, pool_models *models);

/// The name of model set i (0 "default", 1 "thesis"), NULL past the last: lists them for messages.
POOL_API const char *pool_models_preset_name(int i);

/// Model names as in docs/interfaces.md ("petit", "mathavan2010", "constant", "alciatore", "none",
/// "endmass"); "unknown" for a value out of range.
POOL_API const char *pool_cushion_model_name(pool_cushion_model model);
POOL_API const char *pool_ball_friction_model_name(pool_ball_friction_model model);
POOL_API const char *pool_squirt_model_name(pool_squirt_model model);

/// The model of that name, or -1 when the name is unknown (or NULL).
POOL_API int pool_cushion_model_from_name(const char *name);
POOL_API int pool_ball_friction_model_from_name(const char *name);
POOL_API int pool_squirt_model_from_name(const char *name);

/// Everything that defines a simulation apart from its balls.
typedef struct pool_sim_def {
	pool_table_def table;     ///< geometry
	pool_params params;       ///< physical parameters
	bool airborne;            ///< false: planar mode (vertical velocity dropped after each impulse)
	double max_time;          ///< s, the shot stops at this time even if balls still move
	int max_events;           ///< the shot stops after this many events
	pool_allocator allocator; ///< optional; zero means malloc/free
	pool_models models;       ///< the laws; pool_default_models() by default, zero is "thesis"
} pool_sim_def;

/// WPA 9 ft table, docs/physics.md parameters, planar, max_time 120 s, max_events 100000,
/// pool_default_models() (the measured laws; set models = pool_thesis_models() for the 2012 work's).
POOL_API pool_sim_def pool_default_sim_def(void);

/// Why the shot ended (or POOL_STOP_NONE while it runs).
typedef enum pool_stop_reason {
	POOL_STOP_NONE = 0,       ///< events remain
	POOL_STOP_REST = 1,       ///< every ball is at rest, pocketed or off the table
	POOL_STOP_MAX_TIME = 2,   ///< the next event would fall after max_time
	POOL_STOP_MAX_EVENTS = 3, ///< max_events were processed
} pool_stop_reason;

/// Lower-case name as written in result files' "stats.stop_reason": "none", "rest", "max_time",
/// "max_events"; "unknown" for a value out of range.
POOL_API const char *pool_stop_reason_name(pool_stop_reason reason);

/// Creates an empty simulation; validates the def (message names the field).
POOL_API pool_result pool_sim_create(const pool_sim_def *def, pool_sim **sim, pool_error *error);

/// Frees everything the simulation owns. NULL is a no-op.
POOL_API void pool_sim_destroy(pool_sim *sim);

/// Removes every ball and event to start a new shot, keeping allocated memory (so thousands of
/// candidate shots do not allocate). def may be NULL to keep the current one.
POOL_API pool_result pool_sim_reset(pool_sim *sim, const pool_sim_def *def, pool_error *error);

/// Adds a ball before the shot starts. Its motion state is derived from its velocities (the
/// given one is ignored); z defaults to nothing: pass pos.z = R for a ball on the cloth.
/// Rejects duplicate ids, non-finite numbers, balls off the table and overlaps beyond
/// POOL_TOUCH_TOLERANCE; the message calls the ball "balls[i]" with i its insertion index.
POOL_API pool_result pool_sim_add_ball(pool_sim *sim, const pool_ball_state *ball, pool_error *error);

/// Strikes a ball with the cue at the current time (t = 0 before the first step); records a
/// POOL_EVENT_STRIKE. The ball must be at rest on the cloth.
POOL_API pool_result pool_sim_strike(pool_sim *sim, int32_t ball_id, const pool_strike *strike,
                                     pool_error *error);

/// Processes the next event. Returns 1 when one was processed, 0 when the shot is over (see
/// pool_sim_stop_reason), or a negative pool_result.
POOL_API int pool_sim_step(pool_sim *sim);

/// Steps until the shot is over.
POOL_API pool_result pool_sim_run(pool_sim *sim);

/// Processes every event at or before time t (s), so pool_sim_state_at(sim, t, ...) is final.
POOL_API pool_result pool_sim_run_until(pool_sim *sim, double t);

/// What the last failed pool_sim_step, pool_sim_run, pool_sim_run_until, pool_sim_state_at or
/// pool_sim_states_at call met, in words: a LINK step whose LCP could not be solved (its instant,
/// its cluster's balls and contacts, the residual), memory running out (and when), a time asked
/// past the time processed (and that time); "" after such a call that succeeded. Valid until the
/// next call on the simulation; "sim: missing" for NULL.
POOL_API const char *pool_sim_last_error(const pool_sim *sim);

/// Why the shot ended so far.
POOL_API pool_stop_reason pool_sim_stop_reason(const pool_sim *sim);

/// s, time of the last processed event (0 before any).
POOL_API double pool_sim_time(const pool_sim *sim);

/// s, the instant the shot's final states belong to: max_time for a shot cut there (its balls
/// may still move; pool_sim_state_at is valid up to it), else pool_sim_time().
POOL_API double pool_sim_end_time(const pool_sim *sim);

/// Number of balls added.
POOL_API int pool_sim_ball_count(const pool_sim *sim);

/// Current states, by insertion index, each as of the last event that involved the ball
/// (use pool_sim_state_at for a common instant). Valid until the next call that changes the sim.
POOL_API const pool_ball_state *pool_sim_balls(const pool_sim *sim);

/// Exact state of every ball at time t (s), closed-form between events, by insertion index;
/// out must hold pool_sim_ball_count() states. t must not exceed the time up to which events
/// have been processed (any t once the shot is at rest); otherwise POOL_ERR_STATE.
POOL_API pool_result pool_sim_state_at(const pool_sim *sim, double t, pool_ball_state *out);

/// Exact states of every ball at each of `count` times (s), as pool_sim_state_at gives them, in
/// one call: out[k * pool_sim_ball_count() + i] is ball i (insertion index) at times[k]. out must
/// hold count * pool_sim_ball_count() states. Times need no order; each must be >= 0 and at most
/// the processed time (any once the shot is at rest). On an error (POOL_ERR_INVALID_ARGUMENT for
/// a NaN or negative time, POOL_ERR_STATE for one beyond the processed time) nothing is written
/// and *bad_index, when not NULL, receives the index of the first offending time.
POOL_API pool_result pool_sim_states_at(const pool_sim *sim, const double *times, int count, pool_ball_state *out,
                                        int *bad_index);

/// Processed events in time order; *count receives their number. Valid until the sim changes.
POOL_API const pool_event *pool_sim_events(const pool_sim *sim, int *count);

/// The after-states of an event's balls (event->ball_count of them).
POOL_API const pool_ball_state *pool_sim_event_states(const pool_sim *sim, const pool_event *event);

#ifdef __cplusplus
}
#endif

#endif
