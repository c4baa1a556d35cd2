// What an engine is measured against: the closed form of docs/physics.md where one exists (a single
// ball on the cloth that meets no cushion), otherwise libpool's exact event-driven result.
#ifndef POOL_COMPARE_REFERENCE_H
#define POOL_COMPARE_REFERENCE_H

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

#include "pool_engine_plugin.h"
#include "scenario_file.h"

namespace pool_compare {

/// One ball at one instant (world frame, SI units); state codes as pool_engine_ball.
struct BallSample {
	int id = 0;
	int state = 0;
	Eigen::Vector3d pos = Eigen::Vector3d::Zero();
	Eigen::Vector3d vel = Eigen::Vector3d::Zero();
	Eigen::Vector3d omega = Eigen::Vector3d::Zero();
};

/// An event in the plugin ABI's terms (pool_engine_event_type; ball_b = -1 for one-ball events).
struct Event {
	double t = 0.0;
	int type = 0;
	int ball_a = -1;
	int ball_b = -1;
};

/// A ball landing on the cloth (an ABI BALL_TABLE event of the reference) and where.
struct Landing {
	double t = 0.0;
	int ball = -1;
	Eigen::Vector3d pos = Eigen::Vector3d::Zero();
};

/// The top of a flight: the highest point of a ball's centre between two landings.
struct Apex {
	double t = 0.0;
	int ball = -1;
	double z = 0.0; ///< m, height of the centre
};

/// Settling rule of the airborne closed form (docs/physics.md "Ball-cloth"): a rebound whose flight
/// 2 v_z' / g would last less than this settles on the cloth instead (v_z = 0, z = R). With
/// e_table < 1 the flight times shrink geometrically (ratio e_table), so a bounce sequence ends
/// after at most 1 + log(t_first / kSettleFlightTime) / log(1 / e_table) landings (10 for the
/// 0.2 m drop at e_table 0.5). libpool is to use the same threshold.
constexpr double kSettleFlightTime = 1e-3;

/// Ground truth of one scenario.
class Reference {
public:
	virtual ~Reference() = default;
	/// "closed-form" or "libpool" (the "reference" field of results).
	virtual std::string kind() const = 0;
	/// Every ball's state at time t >= 0, in the scenario's ball order: exact up to end_time and
	/// at least one second past it (where a time-stepped engine may stop, a step past max_time).
	virtual std::vector<BallSample> state_at(double t) const = 0;

	/// False for a scenario without ground truth (NoReference): engines run, nothing is scored.
	virtual bool has_truth() const { return true; }
	/// Why there is no ground truth ("" when there is).
	virtual std::string why_none() const { return ""; }
	/// False when the ground truth is itself approximate: libpool's result with LINK steps
	/// (persistent contact advanced by first-order LCP steps, docs/physics.md "LINK"), for which no
	/// exact solution exists.
	virtual bool exact() const { return has_truth(); }

	std::vector<Event> events; ///< the ABI-visible events, in time order
	std::vector<Landing> landings; ///< every landing on the cloth, in time order (airborne mode)
	std::vector<Apex> apexes;      ///< the top of every rising flight, in time order (airborne mode)
	double end_time = 0.0;     ///< s, when every ball is at rest, else the scenario's max_time
	bool at_rest = false;      ///< whether the shot ends at rest before max_time
};

/// The closed form for the scenario, or nullptr when none applies (several balls, airborne
/// mode, zero cloth friction, a path that reaches a cushion, or squirt on an off-centre strike).
std::unique_ptr<Reference> make_closed_form_reference(const Scenario &scenario);

/// libpool's exact result (runs the simulation to rest or max_time). nullptr and *error on failure.
std::unique_ptr<Reference> make_libpool_reference(const Scenario &scenario, std::string *error);

/// The airborne closed form for the scenario (options.airborne, one ball, no cushion on its
/// path), or nullptr: flight r(t) = r0 + v0 t - g t^2 k / 2 with w constant, each landing (z = R,
/// v_z < 0) a Petit impact with the cloth (cloth_impact), a rebound too short to fly
/// kSettleFlightTime settles, then the on-cloth closed form (slide, roll, stop). A strike is
/// applied with its vertical velocity (an elevated cue drives the ball into the cloth at t = 0).
std::unique_ptr<Reference> make_airborne_closed_form_reference(const Scenario &scenario);

/// A scenario without ground truth (its reference engine failed: why says so): kind() "none",
/// no states; the engines still run (to max_time) and their rows say "no reference".
std::unique_ptr<Reference> make_no_reference(const Scenario &scenario, const std::string &why);

/// Petit's impact of a ball with the cloth (docs/physics.md "Collisions": obstacle, n = k,
/// N = e_table, mu = mu_table): v, w just before -> just after. Needs v_z < 0. Implemented here
/// from the specification, independently of libpool. Returns true when the contact slipped
/// throughout (s >= 0), false when it stuck.
bool cloth_impact(const pool_params &params, Eigen::Vector3d *v, Eigen::Vector3d *w);

/// Velocity and spin a cue strike gives a ball at rest (docs/physics.md "Cue strike", computed here
/// independently of libpool); planar drops the vertical velocity.
void strike_velocities(const pool_params &params, const pool_strike &strike, bool planar,
                       Eigen::Vector3d *vel, Eigen::Vector3d *omega);

/// Kinetic energy (translation + rotation) of balls still on the table, J.
double kinetic_energy(const std::vector<BallSample> &balls, const pool_params &params);

/// Maps a libpool event type to the plugin ABI's kinds; -1 for kinds engines don't report.
int abi_event_type(int libpool_type);

} // namespace pool_compare

#endif
