// The comparison's chaos and scale results: predictability horizons (libpool against itself and
// every time-stepped run against libpool), the cost per simulated second against the ball count
// at equal predictability, and where time stepping wins. Printed, in report.md and in
// DIR/horizon.json (with the error tracks the plots draw).
#ifndef POOL_COMPARE_SCALE_REPORT_H
#define POOL_COMPARE_SCALE_REPORT_H

#include <string>
#include <vector>

#include "horizon.h"
#include "metrics.h"

namespace pool_compare {

/// A time-stepped engine's cheapest run that predicts a scene as long as libpool does when its lead
/// ball starts `perturbation` elsewhere.
struct EqualPredictability {
	std::string engine;
	const Record *run = nullptr;  ///< null: no swept step gets there
	const Record *best = nullptr; ///< the run with the longest horizon (when none gets there)
};

/// The coarsest swept time step from which every finer step of the engine keeps a horizon at least
/// the self horizon (a censored self horizon needs a censored run). One entry per time-stepped
/// engine of the scenario, in record order.
std::vector<EqualPredictability> equal_predictability(const std::vector<Record> &records,
                                                      const ScenarioHorizons &horizons, double perturbation);

/// CPU seconds per simulated second of a run (NaN without both).
double cpu_per_sim_second(const Record &record);

/// Per scenario with horizons: libpool against itself for each perturbation, then every
/// time-stepped run: its horizon and CPU per simulated second ("" when none).
std::string horizon_table(const std::vector<Record> &records, const std::vector<ScenarioHorizons> &horizons,
                          bool markdown);

/// Per scale family and ball count: libpool's CPU per simulated second and each time-stepped
/// engine's at equal predictability (against libpool with its lead ball `perturbation` elsewhere),
/// and which is cheaper ("" when no scale scenario ran).
std::string scale_table(const std::vector<Record> &records, const std::vector<ScenarioHorizons> &horizons,
                        double perturbation, bool markdown);

/// One paragraph: where (at which ball counts, for which family) a time-stepped engine at equal
/// predictability costs less CPU per simulated second than libpool, or that it never does ("" when no
/// scale scenario ran).
std::string scale_verdict(const std::vector<Record> &records, const std::vector<ScenarioHorizons> &horizons,
                          double perturbation);

/// Writes DIR/horizon.json: the threshold, each scenario's self horizons and runs with their error
/// tracks, and the scale summary (equal predictability per perturbation).
bool write_horizon_json(const std::string &path, const std::vector<Record> &records,
                        const std::vector<ScenarioHorizons> &horizons, std::string *error);

} // namespace pool_compare

#endif
