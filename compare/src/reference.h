// What an engine is measured against: the closed form of PHYSICS.md where one exists (a single
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

/// Ground truth of one scenario.
class Reference {
public:
	virtual ~Reference() = default;
	/// "closed-form" or "libpool" (the "reference" field of results).
	virtual std::string kind() const = 0;
	/// Every ball's state at time t >= 0, in the scenario's ball order: exact up to end_time and
	/// at least one second past it (where a time-stepped engine may stop, a step past max_time).
	virtual std::vector<BallSample> state_at(double t) const = 0;

	std::vector<Event> events; ///< the ABI-visible events, in time order
	double end_time = 0.0;     ///< s, when every ball is at rest, else the scenario's max_time
	bool at_rest = false;      ///< whether the shot ends at rest before max_time
};

/// The closed form for the scenario, or nullptr when none applies (several balls, airborne
/// mode, zero cloth friction, or a path that reaches a cushion).
std::unique_ptr<Reference> make_closed_form_reference(const Scenario &scenario);

/// libpool's exact result (runs the simulation to rest or max_time). nullptr and *error on failure.
std::unique_ptr<Reference> make_libpool_reference(const Scenario &scenario, std::string *error);

/// Velocity and spin a cue strike gives a ball at rest (PHYSICS.md "Cue strike", computed here
/// independently of libpool); planar drops the vertical velocity.
void strike_velocities(const pool_params &params, const pool_strike &strike, bool planar,
                       Eigen::Vector3d *vel, Eigen::Vector3d *omega);

/// Kinetic energy (translation + rotation) of balls still on the table, J.
double kinetic_energy(const std::vector<BallSample> &balls, const pool_params &params);

/// Maps a libpool event type to the plugin ABI's kinds; -1 for kinds engines don't report.
int abi_event_type(int libpool_type);

} // namespace pool_compare

#endif
