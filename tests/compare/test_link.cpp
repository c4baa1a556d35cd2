// Persistent contact (LINK) in the comparison harness: every built engine on the LINK scenarios
// (compare/scenarios/link: push, rest_on_two, slide_off, airborne_break). No exact solution
// exists for these scenes, so the checks are what must hold whatever the truth: every engine
// finishes every scene; libpool forms clusters in every scene (each was built to need one) and
// says so (its reference is marked not exact, its link share is reported and is a share); the
// engines agree on where the pushed ball of `push` ends, within kPushAgreement, and end the
// stacked scenes within kStackAgreement of libpool.
// usage: test_link SCENARIO_DIR PLUGIN_DIR ENGINE...   (SCENARIO_DIR holds the LINK scenarios)
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "metrics.h"
#include "plugin_loader.h"
#include "reference.h"
#include "results_io.h"
#include "runner.h"
#include "scenario_file.h"

#include "compare_test.h"

using namespace pool_compare;

namespace {

using namespace compare_test;

const char *const kScenarios[] = {"push", "rest_on_two", "slide_off", "airborne_break"};

/// s, the step of the time-stepped engines here: the finest that keeps the airborne break's runs
/// near a second each.
constexpr double kStep = 1e-4;

/// m, how far apart any two engines may put the pushed ball (id 1) of `push` at rest. Measured
/// (pool-compare --link, final positions): ODE 10.2 / 7.2 / 6.7 mm and Bullet 6.1 / 4.8 / 4.7 mm
/// from libpool at dt 1e-3 / 1e-4 / 1e-5, 2.4 mm from each other at 1e-4. Both engines converge
/// (0.5 and 0.1 mm from their own 1e-5 run at 1e-4), so what remains is a difference of models
/// (libpool's first-order 1 ms LINK steps against each engine's contact solver), not of steps:
/// 1 cm is 1.5 times the converged worst (ODE) and 2.7 % of the pushed ball's 0.37 m of travel.
constexpr double kPushAgreement = 1e-2;

/// m, how far from libpool a time-stepped engine may leave the balls of the stacked scenes
/// (rest_on_two, slide_off: a ball bearing on others) at rest, at kStep. Measured (final
/// positions, largest ball): ODE 13.6 / 6.3 mm, Bullet 3.7 / 1.5 mm; Bullet was 117 / 119 mm off
/// while its plugin took a ball's contact with a ball it bears on for an impact at every step
/// (closing at g dt > rest_speed) and so dropped the lower ball's cloth friction throughout.
constexpr double kStackAgreement = 3e-2;

/// The pushed ball of `push`.
constexpr int kPushedBall = 1;

const BallSample *ball(const std::vector<BallSample> &balls, int id) {
	for (const BallSample &b : balls)
		if (b.id == id)
			return &b;
	return nullptr;
}

struct Runs {
	std::map<std::string, std::map<std::string, Record>> by_scenario; // scenario -> engine -> record
};

void run_all(const std::vector<Plugin> &plugins, Runs *runs) {
	for (const char *name : kScenarios) {
		auto s = load(name);
		if (!s)
			continue;
		std::string error;
		auto ref = make_libpool_reference(*s, &error);
		CHECK(ref != nullptr, "%s: libpool reference failed: %s", name, error.c_str());
		if (!ref)
			continue;
		// Each scene was built so that contact persists: libpool must have formed a cluster, and
		// its reference must then not claim to be exact.
		CHECK(ref->has_truth() && !ref->exact(), "%s: the libpool reference took no LINK step (exact %d)", name,
		      ref->exact());
		for (const Plugin &plugin : plugins) {
			RunSettings settings;
			settings.dt = kStep;
			settings.min_timing_cpu = 0.02; // a few timed runs for the share's median, not a benchmark
			const Record r = run_engine(*s, *ref, plugin, settings);
			CHECK(r.error.empty() && r.outcome == "ok", "%s / %s: %s", name, plugin.api->name, r.error.c_str());
			CHECK(r.reference == "libpool" && r.reference_exact == 0, "%s / %s: reference %s, exact %d", name,
			      plugin.api->name, r.reference.c_str(), r.reference_exact);
			std::printf("  %s / %s: final position vs libpool %.3g m, cpu %.3g ms, link share %.3g, link steps "
			            "%lld (%lld clusters)\n",
			            name, plugin.api->name, r.final_position_error, 1e3 * r.cpu_seconds, r.link_cpu_share,
			            r.link_steps, r.link_clusters);
			runs->by_scenario[name][plugin.api->name] = r;
		}
	}
}

// libpool reports its link share, a share, and the clusters its events show; engines without the
// export report nothing (null), not zero.
void link_fields(const Runs &runs) {
	for (const auto &[scenario, engines] : runs.by_scenario)
		for (const auto &[engine, r] : engines) {
			if (engine == "libpool") {
				CHECK(std::isfinite(r.link_cpu_share) && r.link_cpu_share >= 0.0 && r.link_cpu_share <= 1.0,
				      "%s: libpool link share %g", scenario.c_str(), r.link_cpu_share);
				CHECK(r.link_clusters >= 1 && r.link_steps >= 1 && r.link_events >= 2 * r.link_clusters,
				      "%s: libpool link steps %lld, events %lld, clusters %lld", scenario.c_str(), r.link_steps,
				      r.link_events, r.link_clusters);
			} else {
				CHECK(std::isnan(r.link_cpu_share) && r.link_steps < 0, "%s / %s: link share %g, steps %lld without "
				      "the export", scenario.c_str(), engine.c_str(), r.link_cpu_share, r.link_steps);
			}
			// The new fields survive the child process's wire and are written (null when unknown).
			Record back;
			std::string error;
			CHECK(record_from_wire(record_wire(r), &back, &error), "%s: wire: %s", engine.c_str(), error.c_str());
			CHECK(back.link_steps == r.link_steps && back.link_clusters == r.link_clusters &&
			          back.reference_exact == r.reference_exact &&
			          (std::isnan(r.link_cpu_share) ? std::isnan(back.link_cpu_share)
			                                        : back.link_cpu_share == r.link_cpu_share),
			      "%s / %s: link fields changed on the wire", scenario.c_str(), engine.c_str());
			const std::string json = record_json(r);
			CHECK(json.find("\"link_cpu_share\":") != std::string::npos &&
			          json.find("\"reference_exact\":false") != std::string::npos,
			      "%s / %s: record %s", scenario.c_str(), engine.c_str(), json.c_str());
		}
}

// Every pair of engines puts the pushed ball within kPushAgreement of each other.
void push_agreement(const Runs &runs) {
	auto it = runs.by_scenario.find("push");
	if (it == runs.by_scenario.end())
		return;
	for (const auto &[a, ra] : it->second)
		for (const auto &[b, rb] : it->second) {
			if (a >= b)
				continue;
			const BallSample *pa = ball(ra.final_balls, kPushedBall), *pb = ball(rb.final_balls, kPushedBall);
			CHECK(pa && pb, "push: %s or %s lost ball %d", a.c_str(), b.c_str(), kPushedBall);
			if (!pa || !pb)
				continue;
			const double d = (pa->pos - pb->pos).head<2>().norm();
			std::printf("  push: pushed ball %s vs %s: %.3g m\n", a.c_str(), b.c_str(), d);
			CHECK(d <= kPushAgreement, "push: %s and %s put the pushed ball %.3g m apart (bound %.3g m)", a.c_str(),
			      b.c_str(), d, kPushAgreement);
		}
}

// The stacked scenes end where libpool ends them, within kStackAgreement, for every engine.
void stack_agreement(const Runs &runs) {
	for (const char *name : {"rest_on_two", "slide_off"}) {
		auto it = runs.by_scenario.find(name);
		if (it == runs.by_scenario.end())
			continue;
		for (const auto &[engine, r] : it->second) {
			if (engine == "libpool")
				continue;
			CHECK(r.final_position_error <= kStackAgreement, "%s / %s: final positions %.3g m from libpool (bound %.3g m)",
			      name, engine.c_str(), r.final_position_error, kStackAgreement);
		}
	}
}

} // namespace

int main(int argc, char **argv) {
	if (argc < 3) {
		std::fprintf(stderr, "usage: test_link SCENARIO_DIR PLUGIN_DIR ENGINE...\n");
		return 2;
	}
	scenario_dir = argv[1];
	const std::vector<Plugin> plugins = load_plugins(argc, argv, 3, argv[2]);
	bool has_libpool = false;
	for (const Plugin &p : plugins)
		has_libpool = has_libpool || std::string(p.api->name) == "libpool";
	CHECK(has_libpool, "the libpool plugin is not built");
	Runs runs;
	run_all(plugins, &runs);
	link_fields(runs);
	push_agreement(runs);
	stack_agreement(runs);
	return finish();
}
