// The predictability horizon of a chaotic scene: how long a trajectory stays within 1 cm of the
// reference's. A break or a gas of balls is chaotic (each collision multiplies a small offset by
// about the distance between balls over their radius), so a final position after seconds says
// little: libpool itself ends millimetres away when its cue ball starts 1 um elsewhere. The
// horizon says instead for how long an engine predicts the scene, beside how long libpool
// predicts it when its own start is known to 1 nm, 1 um or 1 mm.
#ifndef POOL_COMPARE_HORIZON_H
#define POOL_COMPARE_HORIZON_H

#include <array>
#include <string>
#include <vector>

#include "metrics.h"
#include "reference.h"
#include "scenario_file.h"

namespace pool_compare {

/// Distance (m, the largest over the balls, in the plane) at which two trajectories of one scene
/// count as departed: 1 cm, a third of a ball's radius (the figure; any threshold well
/// above the 1 mm start offset and well below a ball's size tells the same story).
constexpr double kHorizonThreshold = 0.01;

/// Spacing of the instants at which trajectories are compared, s: the resolution of a horizon.
constexpr double kHorizonSpacing = 5e-3;

/// At most this many instants per run (a longer scene is sampled more coarsely).
constexpr int kHorizonMaxSamples = 1000;

/// How far libpool's struck ball starts elsewhere when libpool is measured against itself, m:
/// 1 nm, 1 um, 1 mm. In a scene without a strike (a gas of moving balls) every ball starts that
/// far elsewhere, each in its own direction: an engine's errors start at every moving ball, and
/// so does a measured table's uncertainty.
constexpr std::array<double, 3> kSelfPerturbations = {1e-9, 1e-6, 1e-3};

/// Directions (evenly spread in the plane) of each of those displacements; the track is their
/// median, so a direction along the struck ball's path (a pure shift in time) does not decide it.
constexpr int kSelfDirections = 8;

/// When a track departs.
struct Horizon {
	double seconds = kNone; ///< first sampled instant with error > threshold, or the last instant (censored)
	bool censored = false;  ///< it never departed: seconds is then a lower bound (the end of the scene)
};

/// libpool against itself, its struck ball (or every ball) moved by `perturbation` at t = 0.
struct SelfHorizon {
	double perturbation = 0.0; ///< m
	int runs = 0;              ///< directions that made a valid scenario (the others overlapped a ball)
	ErrorTrack track;          ///< median over the runs at each instant
	Horizon horizon;           ///< of that median track
};

/// A scenario's horizon study: libpool against itself for each of kSelfPerturbations.
struct ScenarioHorizons {
	std::string scenario;         ///< its name
	int balls = 0;                ///< its ball count
	std::string family;           ///< its scale family, "" for a scenario file
	double end_time = 0.0;        ///< s, the end of the reference (rest or max_time)
	std::vector<SelfHorizon> self; ///< one per perturbation, smallest first
};

/// Whether horizons are measured for a scenario: 3 or more balls (where collisions chain) and a
/// libpool reference.
bool horizon_applies(const Scenario &scenario, const Reference &reference);

/// Instants in (0, end_time] every kHorizonSpacing (or end_time / kHorizonMaxSamples), end_time
/// included.
std::vector<double> horizon_times(double end_time);

/// The largest planar distance between the same balls (matched by id) of two states. A ball out of
/// play (pocketed, off the table) in both counts 0; in one only, `off_play_distance` (the trajectories
/// have departed: the table's diagonal); missing from one, infinity.
double trajectory_distance(const std::vector<BallSample> &a, const std::vector<BallSample> &b,
                           double off_play_distance);

/// The table's diagonal, m: what a ball in play in one trajectory and out of it in the other counts.
double off_play_distance(const Scenario &scenario);

/// When the track first exceeds the threshold (no interpolation: the resolution is the spacing of
/// its instants). An empty track is censored at NaN.
Horizon departure(const ErrorTrack &track, double threshold);

/// libpool against itself for each of kSelfPerturbations, on horizon_times(reference.end_time).
/// False with *error when the scenario cannot be perturbed or libpool fails on every direction.
bool self_horizons(const Scenario &scenario, const Reference &reference, std::vector<SelfHorizon> *out,
                   std::string *error);

} // namespace pool_compare

#endif
