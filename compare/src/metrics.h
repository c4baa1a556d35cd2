// Errors of an engine's run against a reference: positions, directions and energy at sample
// instants, event times, missed and phantom collisions.
#ifndef POOL_COMPARE_METRICS_H
#define POOL_COMPARE_METRICS_H

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "reference.h"

namespace pool_compare {

/// "No value" of optional measurements (written as null).
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

/// One trajectory's distance from another over time.
struct ErrorTrack {
	std::vector<double> t;     ///< s, increasing
	std::vector<double> error; ///< m, the largest planar distance over the balls at t
};

/// One record of results.json: a scenario run by one engine at one time step.
struct Record {
	std::string scenario;      ///< file stem
	std::string engine;        ///< plugin name
	std::string description;   ///< the plugin's one-line description (what it can't model)
	std::string reference;     ///< "closed-form" or "libpool"
	std::string error;         ///< why the run failed ("" when it ran)
	std::string outcome = "ok"; ///< "ok"; "failed" (the engine reported an error or gave back no
	                            ///< valid state: error says which); "crashed" (killed by a signal),
	                            ///< "exited" (called exit), "timed_out" (killed after the time limit)
	double wall_seconds = kNone; ///< s, wall-clock time of the whole run (timing and spread runs included)
	bool event_driven = false; ///< dt is then null
	double dt = kNone;         ///< s

	double cpu_seconds = kNone;       ///< median CPU time of a run (advance and run_to_rest), s
	double cpu_seconds_min = kNone;   ///< fastest of the repetitions, s
	int repetitions = 0;              ///< timed runs
	double setup_cpu_seconds = kNone; ///< CPU time of create() (parsing, world building), s
	double sim_seconds = kNone;       ///< simulated time reached, s
	long long steps = 0;              ///< time steps (events for event-driven engines)

	double final_position_error = kNone; ///< m, max over balls, at rest / at max_time
	double event_position_error = kNone; ///< m, max over balls and sample instants
	double direction_error_deg = kNone;  ///< deg, max angle between velocities (moving balls)
	double energy_error = kNone;         ///< J, max |E - E_ref| over sample instants away from collisions
	double event_time_error = kNone;     ///< s, max of the three below
	double first_contact_time_error = kNone; ///< s, first ball-ball or ball-cushion contact
	double slide_roll_time_error = kNone;    ///< s, each reference slide->roll vs the engine's nearest
	double stop_time_error = kNone;          ///< s, each ball's last roll_stop
	double collision_time_error = kNone;     ///< s, each reference collision vs the nearest same one
	int unmatched_events = 0;            ///< reference slide_roll / stop events the engine lacks
	int missed_collisions = 0;           ///< reference ball pairs / (ball, rail) contacts not produced
	int phantom_collisions = 0;          ///< pairs / (ball, rail) contacts the reference does not have
	bool cushions_by_rail = true;        ///< false: the engine names no rail, cushion contacts keyed by ball only
	int simultaneous_contacts = 0;       ///< reference ball-ball contacts at the same instant as another
	                                     ///< of the same ball (libpool resolves them in sequence)
	int collisions_reference = 0;        ///< collision events of the reference
	int collisions_engine = 0;           ///< collision events the engine reported
	int pocket_mismatches = 0;           ///< balls pocketed in one and not the other
	double max_penetration = kNone;      ///< m, from the plugin's stats and the sampled states

	int engine_messages = 0;         ///< lines the engine printed (kept in DIR/engines.log)

	// Airborne motion (docs/physics.md "Airborne", "Ball-cloth"): landings on the cloth, matched in
	// order per ball (the k-th landing of a ball in the engine with its k-th in the reference).
	int landings_reference = 0;           ///< landings (BALL_TABLE events) of the reference
	int landings_engine = 0;              ///< landings the engine reported
	double landing_time_error = kNone;    ///< s, max over the matched landings
	double landing_position_error = kNone; ///< m, max xy distance at the reference's landing instants
	double bounce_height_error = kNone;   ///< m, max |z - z_ref| at the reference's apex instants
	std::string reference_error;          ///< why there is no reference (reference "none")
	/// The scenario's models the engine cannot express ("cushion=mathavan2010", ...; it ran with
	/// its own laws instead, so the errors include the difference of the laws). models_known
	/// false: the plugin does not say (no POOL_ENGINE_MODELS_ENTRY), written as null.
	std::vector<std::string> unsupported_models;
	bool models_known = false;

	int spread_runs = 0;             ///< perturbed runs (0: not measured)
	double spread_perturbation = kNone; ///< m, displacement of the lead ball in each run
	double spread_rms = kNone;       ///< m, RMS over runs and balls of the final-position change
	double spread_max = kNone;       ///< m, largest final-position change

	double consistency_error = kNone; ///< m, final positions against the same engine at its finest dt

	// Persistent contact (LINK): only from plugins with the POOL_ENGINE_LINK_ENTRY export (null
	// otherwise). A libpool reference that took LINK steps is not exact (first-order LCP steps
	// inside the contact): its rows measure agreement between engines, not errors.
	double link_cpu_share = kNone;  ///< share of the run's step time spent in link steps (median of the timed runs)
	long long link_steps = -1;      ///< LCP solves of the measured run (-1: the plugin does not say)
	long long link_events = -1;     ///< link_begin, link_step and link_end events
	long long link_clusters = -1;   ///< clusters formed
	int reference_exact = -1;       ///< 1 closed form or libpool without LINK steps, 0 libpool with them, -1 no reference
	std::vector<BallSample> final_balls; ///< final states (not written; for consistency_error)

	// Scale and chaos (pool-compare --scale; docs/comparison.md "Predictability horizon").
	int balls = 0;                   ///< balls in the scenario
	std::string family;              ///< scale family ("break", "gas") of a generated scenario, else ""
	double horizon_seconds = kNone;  ///< s, until the engine's trajectory departs 1 cm from the reference's
	                                 ///< (NaN: not measured: fewer than 3 balls, or no libpool reference)
	bool horizon_censored = false;   ///< it never departed: horizon_seconds is the end of the scene
	ErrorTrack track;                ///< that distance over time (written to horizon.json, not results.json)

	/// Simulated seconds per CPU second.
	double speed() const { return sim_seconds / cpu_seconds; }
};

/// An open interval of time (s).
struct TimeWindow {
	double from;
	double to;
};

/// Largest lag (s) between a reference collision and an engine collision taken for the same one.
/// Measured timing errors reach 0.37 s (cut30 at dt 1e-2); anything further apart is another
/// collision.
constexpr double kMaxCollisionLag = 0.5;

/// The instants at which directions and energies are not compared: from each reference
/// collision to the engine's nearest collision of the same key (same pair, same ball and rail)
/// within kMaxCollisionLag, and around every engine collision, widened by max(3 dt, 1 ms)
/// (dt NaN: 1 ms).
std::vector<TimeWindow> collision_windows(const std::vector<Event> &reference, const std::vector<Event> &engine,
                                          double dt);

/// Accumulates the comparison of sampled engine states with the reference.
class StateErrors {
public:
	/// skip: instants where directions and energies are not compared (collision_windows).
	StateErrors(const pool_params &params, const std::vector<TimeWindow> &skip);
	/// Compares one instant (the engine's time t; reference state at the same t); engine balls
	/// are matched by id.
	void add(double t, const std::vector<BallSample> &engine, const std::vector<BallSample> &reference);

	double position_error = 0.0;  ///< m, max over instants and balls (xy)
	double direction_error = kNone; ///< deg
	double energy_error = 0.0;    ///< J, away from collisions
	double penetration = 0.0;     ///< m, deepest ball-ball overlap seen
	int missing_balls = 0;        ///< reference balls the engine did not report

private:
	pool_params params_;
	std::vector<TimeWindow> skip_;
};

/// Largest xy distance between the same balls of two states (infinity if a ball is missing).
double max_position_error(const std::vector<BallSample> &engine, const std::vector<BallSample> &reference);

/// Fills the event fields of a record (times, missed and phantom collisions).
void compare_events(const std::vector<Event> &engine, const Reference &reference, Record *record);

/// Fills landings_reference, landings_engine and landing_time_error: each ball's k-th landing
/// (BALL_TABLE event) in the engine against its k-th in the reference, for every k both have.
void compare_landings(const std::vector<Event> &engine, const Reference &reference, Record *record);

/// Balls pocketed (or off the table) in one state but not in the other.
int pocket_mismatches(const std::vector<BallSample> &engine, const std::vector<BallSample> &reference);

} // namespace pool_compare

#endif
