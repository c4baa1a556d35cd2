// Scenario families at scale (pool-compare --scale): the same kind of scene with 16 to 4,096
// balls, on a table whose area grows with the ball count (16 balls per standard 9 ft table area),
// for the question "as a table fills, where does time stepping overtake events?".
#ifndef POOL_COMPARE_SCALE_SCENARIOS_H
#define POOL_COMPARE_SCALE_SCENARIOS_H

#include <string>
#include <vector>

namespace pool_compare {

/// Largest ball count a family is generated with (POOL_SCALE_MAX_BALLS).
constexpr int kScaleMaxBalls = 4096;

/// Simulated time of every scale scenario (options.max_time), s: long enough for each family's
/// collisions to mix the scene (the predictability horizons of the time-stepped engines end well
/// inside it), short enough for a 1,024-ball run at dt 1e-5.
constexpr double kScaleWindow = 2.0;

/// The family names, in report order: "break", "gas".
const std::vector<std::string> &scale_families();

/// The scenario's name: "scale_<family>_<balls>".
std::string scale_scenario_name(const std::string &family, int balls);

/// The libpool-scenario/1 document of a family at a ball count in [2, kScaleMaxBalls]: the scene
/// of tools/common/scale_scene.h (pool_scale_scene: what each family holds) with max_time
/// kScaleWindow, the same text for the same arguments. False with *error for an unknown family
/// or a ball count out of range.
bool scale_scenario_json(const std::string &family, int balls, std::string *json, std::string *error);

} // namespace pool_compare

#endif
