// Runs one scenario on one engine at one time step and measures it against the reference.
#ifndef POOL_COMPARE_RUNNER_H
#define POOL_COMPARE_RUNNER_H

#include "metrics.h"
#include "plugin_loader.h"

namespace pool_compare {

/// How to run and time one engine.
struct RunSettings {
	double dt = 1e-3;              ///< s, for time-stepped engines
	int spread_runs = 0;           ///< perturbed runs for the predictability study (0: none)
	double perturbation = 1e-6;    ///< m, how far each perturbed run moves the lead ball
	double min_timing_cpu = 0.2;   ///< s, repeat short runs (setup included) until this much CPU time passed
	int max_repetitions = 2000;    ///< cap of those repetitions
	int min_repetitions = 1;       ///< timed runs at least, however long (pool-compare --repeat)
	int max_samples = 150;         ///< cap of the instants at which states are compared
	/// Instants at which the distance to the reference is tracked for the predictability horizon
	/// (horizon_times; empty: not measured). They do not enter the other metrics.
	std::vector<double> horizon_times;
};

/// The measured record. A failing engine gives a record whose error field says why.
Record run_engine(const Scenario &scenario, const Reference &reference, const Plugin &plugin,
                  const RunSettings &settings);

/// The record of a run before it ran: scenario, engine, description, reference, dt.
Record blank_record(const Scenario &scenario, const Reference &reference, const Plugin &plugin,
                    const RunSettings &settings);

/// The scenario's models the plugin cannot express ("cushion=mathavan2010", ...), from its
/// optional POOL_ENGINE_MODELS_ENTRY export. False (and *out empty) when the plugin does not say.
bool unsupported_models(const Scenario &scenario, const Plugin &plugin, std::vector<std::string> *out);

/// Instants (s) at which the states are compared: 0, every reference event, and 30 ms after
/// each collision; at most max_samples of them, all before end_time.
std::vector<double> sample_times(const Reference &reference, int max_samples);

/// Process CPU time, s.
double cpu_now();

} // namespace pool_compare

#endif
