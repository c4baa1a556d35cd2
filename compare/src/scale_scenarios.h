// Scenario families at scale (pool-compare --scale): the same kind of scene with 16 to 4,096
// balls, on a table whose area grows with the ball count (16 balls per standard 9 ft table area),
// for the question "as a table fills, where does time stepping overtake events?".
#ifndef POOL_COMPARE_SCALE_SCENARIOS_H
#define POOL_COMPARE_SCALE_SCENARIOS_H

#include <string>
#include <vector>

namespace pool_compare {

/// Largest ball count a family is generated with.
constexpr int kScaleMaxBalls = 4096;

/// Balls per standard table area (WPA 9 ft, 2.54 x 1.27 m): a racked 8-ball table.
constexpr int kScaleBallsPerTable = 16;

/// Simulated time of every scale scenario (options.max_time), s: long enough for each family's
/// collisions to mix the scene (the predictability horizons of the time-stepped engines end well
/// inside it), short enough for a 1,024-ball run at dt 1e-5.
constexpr double kScaleWindow = 2.0;

/// The family names, in report order: "break", "gas".
const std::vector<std::string> &scale_families();

/// The scenario's name: "scale_<family>_<balls>".
std::string scale_scenario_name(const std::string &family, int balls);

/// The libpool-scenario/1 document of a family at a ball count in [2, kScaleMaxBalls], the same
/// text for the same arguments (its own random generator, seeded by the ball count). Both
/// families play on a table of balls / 16 standard areas (2:1, pocketless: corner and side
/// mouths 0, so every ball stays in play for the whole window):
/// - "break": the cue ball 1.27 m before the apex (or a quarter of the length before it on a table
///   shorter than the standard one) of a triangular rack of balls - 1 object balls (rows of 1, 2,
///   3, ... balls, the last one partial, on its middle sites) 0.1 mm apart, apex at 3/4 of the
///   length; a centre-ball strike at 6 m/s along the table, the cue ball 5 mm beside the rack's
///   axis (on the axis, the apex ball would meet the two balls behind it at one instant).
/// - "gas": balls at uniformly random places at least 3 mm apart (and 1 cm inside the cushion
///   lines), a quarter of them rolling at 0.5-2 m/s in random directions, the rest at rest.
/// False with *error for an unknown family or a ball count out of range.
bool scale_scenario_json(const std::string &family, int balls, std::string *json, std::string *error);

} // namespace pool_compare

#endif
