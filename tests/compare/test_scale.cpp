// The comparison at scale and the predictability horizon (pool-compare --scale, docs/comparison.md):
// - the generated families hold what they promise, checked independently of the generator
//   (ball counts, table area, gaps between balls, the gas's rolling quarter, the off-axis cue);
// - the horizon's pieces (instants, departure, distance between trajectories) on hand-made cases;
// - libpool against itself obeys two laws whatever its physics: a scene without collisions or
//   cushions moved by d stays exactly d away (translation), and small offsets grow in proportion
//   to their size (the linear response of a smooth flow: 1 nm and 1 um tracks differ by 1000x
//   while far below a ball's size);
// - engine runs: libpool's plugin stays exactly on its reference; a time-stepped engine cannot
//   depart 1 cm before the first collision (one ball sliding has an error of order v dt);
// - equal predictability takes the coarsest step from which every finer one qualifies.
// usage: test_scale SCENARIO_DIR PLUGIN_DIR ENGINE...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "horizon.h"
#include "metrics.h"
#include "plugin_loader.h"
#include "reference.h"
#include "results_io.h"
#include "runner.h"
#include "scale_report.h"
#include "scale_scenarios.h"
#include "scenario_file.h"

#include "compare_test.h"

using namespace pool_compare;

namespace {

using namespace compare_test;

double smallest_gap(const pool_scenario &s, int from) {
	double best = HUGE_VAL;
	for (int i = from; i < s.ball_count; ++i)
		for (int j = i + 1; j < s.ball_count; ++j)
			best = std::min(best, std::hypot(s.balls[i].pos.x - s.balls[j].pos.x, s.balls[i].pos.y - s.balls[j].pos.y));
	return best;
}

void families() {
	const pool_table_def standard = pool_default_table_def();
	const double R = pool_default_params().ball_radius;
	for (const std::string &family : scale_families())
		for (int n : {2, 3, 16, 64, 1024}) {
			std::string json, again, error;
			CHECK(scale_scenario_json(family, n, &json, &error), "%s %d: %s", family.c_str(), n, error.c_str());
			CHECK(scale_scenario_json(family, n, &again, &error) && again == json, "%s %d: not the same text twice",
			      family.c_str(), n);
			// The shared parser refuses overlapping balls and balls off the cloth.
			auto s = from_text(scale_scenario_name(family, n), json);
			if (!s)
				continue;
			const pool_scenario &p = s->parsed;
			const pool_table_def &t = p.def.table;
			CHECK(p.ball_count == n, "%s %d: %d balls", family.c_str(), n, p.ball_count);
			const double area = t.length * t.width, expected = standard.length * standard.width * n / 16.0;
			CHECK(std::fabs(area - expected) <= 1e-12 * expected && std::fabs(t.length - 2.0 * t.width) <= 1e-12,
			      "%s %d: table %g x %g m, area %g (expected %g)", family.c_str(), n, t.length, t.width, area, expected);
			CHECK(t.corner_mouth == 0.0 && t.side_mouth == 0.0, "%s %d: mouths %g %g", family.c_str(), n,
			      t.corner_mouth, t.side_mouth);
			CHECK(p.def.max_time == kScaleWindow, "%s %d: max_time %g", family.c_str(), n, p.def.max_time);
			// The laws ODE and Bullet express: with libpool's defaults they would run other ones.
			const pool_models thesis = pool_thesis_models();
			CHECK(p.def.models.cushion == thesis.cushion && p.def.models.ball_ball_friction == thesis.ball_ball_friction &&
			          p.def.models.squirt == thesis.squirt,
			      "%s %d: not the thesis models", family.c_str(), n);
			if (family == "gas") {
				int moving = 0;
				for (int i = 0; i < n; ++i) {
					const pool_ball_state &b = p.balls[i];
					const double v = std::hypot(b.vel.x, b.vel.y);
					if (v == 0.0)
						continue;
					++moving;
					// Rolling: the contact point's velocity v + R k x w is zero.
					const double slip = std::hypot(b.vel.x - R * b.omega.y, b.vel.y + R * b.omega.x);
					CHECK(v >= 0.5 && v <= 2.0 && slip <= 1e-12, "gas %d: ball %d at %g m/s, slip %g", n, b.id, v, slip);
				}
				CHECK(moving == n / 4, "gas %d: %d balls moving", n, moving);
				CHECK(smallest_gap(p, 0) >= 2.0 * R + 3e-3, "gas %d: balls %g m apart", n, smallest_gap(p, 0));
				CHECK(!p.has_strike, "gas %d: a strike", n);
			} else {
				CHECK(p.has_strike && p.strike_ball == 0 && p.strike.speed == 6.0, "break %d: strike", n);
				const pool_ball_state &cue = p.balls[0];
				CHECK(std::fabs(cue.pos.y - (0.5 * t.width + 5e-3)) <= 1e-12, "break %d: cue ball at y %g", n, cue.pos.y);
				if (n >= 16)
					CHECK(std::fabs(p.balls[1].pos.x - cue.pos.x - 1.27) <= 1e-12, "break %d: cue ball %g m before the apex",
					      n, p.balls[1].pos.x - cue.pos.x);
				if (n >= 3) // the rack: neighbours exactly 0.1 mm apart
					CHECK(std::fabs(smallest_gap(p, 1) - (2.0 * R + 1e-4)) <= 1e-12, "break %d: rack pitch %.15g", n,
					      smallest_gap(p, 1));
			}
		}
	std::string json, error;
	CHECK(!scale_scenario_json("crowd", 16, &json, &error) && error.find("crowd") != std::string::npos, "%s",
	      error.c_str());
	CHECK(!scale_scenario_json("gas", 1, &json, &error) && error.find("outside [2, 4096]") != std::string::npos, "%s",
	      error.c_str());
	CHECK(!scale_scenario_json("break", 4097, &json, &error), "4097 balls accepted");
}

BallSample at(int id, double x, double y, int state = 0) {
	BallSample b;
	b.id = id;
	b.state = state;
	b.pos = Eigen::Vector3d(x, y, 0.028575);
	return b;
}

void horizon_pieces() {
	const std::vector<double> t2 = horizon_times(2.0);
	CHECK(t2.size() == 400 && std::fabs(t2[0] - 5e-3) < 1e-15 && t2.back() == 2.0, "%zu instants, %g .. %g", t2.size(),
	      t2.front(), t2.back());
	const std::vector<double> t10 = horizon_times(10.0);
	CHECK(t10.size() == 1000 && std::fabs(t10[1] - t10[0] - 0.01) < 1e-12, "10 s: %zu instants", t10.size());
	CHECK(horizon_times(0.0).empty(), "a scene of no time has instants");

	ErrorTrack track;
	track.t = {0.1, 0.2, 0.3};
	track.error = {1e-3, 0.01, 0.02};
	Horizon h = departure(track, 0.01);
	CHECK(h.seconds == 0.3 && !h.censored, "departure %g (an error equal to the threshold has not departed)", h.seconds);
	track.error = {1e-3, 2e-3, 3e-3};
	h = departure(track, 0.01);
	CHECK(h.censored && h.seconds == 0.3, "censored at %g", h.seconds);

	const std::vector<BallSample> a = {at(0, 1.0, 1.0), at(1, 2.0, 0.5), at(2, 0.0, 0.0, POOL_MOTION_POCKETED)};
	std::vector<BallSample> b = {at(1, 2.3, 0.9), at(0, 1.0, 1.0), at(2, 5.0, 5.0, POOL_MOTION_POCKETED)};
	CHECK(std::fabs(trajectory_distance(a, b, 9.0) - 0.5) < 1e-15, "distance %g (3-4-5, balls out of order)",
	      trajectory_distance(a, b, 9.0));
	b[2].state = 0;
	CHECK(trajectory_distance(a, b, 9.0) == 9.0, "pocketed in one only: %g", trajectory_distance(a, b, 9.0));
	b.pop_back();
	CHECK(std::isinf(trajectory_distance(a, b, 9.0)), "a missing ball: %g", trajectory_distance(a, b, 9.0));
}

// Three balls rolling side by side, far from each other and from the cushions for the whole
// scene: moving every ball by d moves every trajectory by exactly d.
const char kParallel[] = R"({"format": "libpool-scenario/1", "table": {"length": 6.0, "width": 3.0},
  "balls": [{"id": 0, "pos": [2.0, 1.0], "vel": [0.8, 0, 0], "omega": [0, 27.996500437445, 0]},
            {"id": 1, "pos": [2.0, 1.5], "vel": [0.6, 0, 0], "omega": [0, 20.997375328084, 0]},
            {"id": 2, "pos": [2.0, 2.0], "vel": [0.7, 0, 0], "omega": [0, 24.496937882765, 0]}],
  "options": {"max_time": 1.5}})";

void translation() {
	auto s = from_text("parallel", kParallel);
	if (!s)
		return;
	std::string error;
	auto ref = make_libpool_reference(*s, &error);
	CHECK(ref && horizon_applies(*s, *ref), "parallel: %s", error.c_str());
	if (!ref)
		return;
	std::vector<SelfHorizon> self;
	CHECK(self_horizons(*s, *ref, &self, &error), "%s", error.c_str());
	CHECK(self.size() == kSelfPerturbations.size(), "%zu self horizons", self.size());
	for (const SelfHorizon &h : self) {
		double worst = 0.0;
		for (double e : h.track.error)
			worst = std::max(worst, std::fabs(e - h.perturbation) / h.perturbation);
		// Rounding of positions of a few metres: 1e-15 m against the 1 nm offset.
		CHECK(worst <= 1e-5 && h.horizon.censored && h.runs == kSelfDirections,
		      "moved %g m: distance off by %.3g of it, censored %d, %d runs", h.perturbation, worst, h.horizon.censored,
		      h.runs);
	}
}

// m: offsets far below a ball's size change no collision's partners or order, so the flow is
// smooth and they grow in proportion (measured: 1 um / 1 nm = 1000.0 to 4 digits up to 1 mm; near
// 1 cm, 910-1030).
constexpr double kLinearRegime = 1e-3;

// The frozen break: offsets of 1 nm and 1 um grow in proportion while the 1 um one stays below
// kLinearRegime; larger offsets depart sooner.
void linear_response() {
	auto s = load("break");
	if (!s)
		return;
	std::string error;
	auto ref = make_libpool_reference(*s, &error);
	std::vector<SelfHorizon> self;
	CHECK(ref && self_horizons(*s, *ref, &self, &error), "break: %s", error.c_str());
	if (self.size() != 3)
		return;
	double worst = 0.0;
	int compared = 0;
	for (size_t k = 0; k < self[0].track.t.size(); ++k)
		if (self[1].track.error[k] < kLinearRegime && self[0].track.error[k] > 0.0) {
			worst = std::max(worst, std::fabs(self[1].track.error[k] / self[0].track.error[k] / 1000.0 - 1.0));
			++compared;
		}
	std::printf("  break: self horizons %g / %g / %g s (1 nm / 1 um / 1 mm); 1 um over 1 nm within %.2g of 1000 at "
	            "%d instants\n",
	            self[0].horizon.seconds, self[1].horizon.seconds, self[2].horizon.seconds, worst, compared);
	CHECK(compared > 100 && worst <= 1e-3, "1 um / 1 nm ratio off 1000 by %.3g (%d instants)", worst, compared);
	CHECK(self[2].horizon.seconds <= self[1].horizon.seconds && self[1].horizon.seconds <= self[0].horizon.seconds,
	      "horizons not ordered: %g %g %g", self[0].horizon.seconds, self[1].horizon.seconds, self[2].horizon.seconds);
}

void engine_tracks(const std::vector<Plugin> &plugins) {
	auto s = load("break");
	if (!s)
		return;
	std::string error;
	auto ref = make_libpool_reference(*s, &error);
	if (!ref)
		return;
	double first_collision = HUGE_VAL;
	for (const Event &e : ref->events)
		if (e.type == POOL_ENGINE_EVENT_BALL_BALL || e.type == POOL_ENGINE_EVENT_BALL_CUSHION)
			first_collision = std::min(first_collision, e.t);
	for (const Plugin &plugin : plugins) {
		RunSettings settings;
		settings.dt = 1e-3;
		settings.min_timing_cpu = 0.0;
		settings.horizon_times = horizon_times(ref->end_time);
		const Record r = run_engine(*s, *ref, plugin, settings);
		const std::string name = plugin.api->name;
		CHECK(r.error.empty() && r.track.t.size() == settings.horizon_times.size(), "%s: %s, %zu instants",
		      name.c_str(), r.error.c_str(), r.track.t.size());
		if (r.track.t.empty())
			continue;
		std::printf("  break / %s: horizon %g s (first collision %g s)\n", name.c_str(), r.horizon_seconds,
		            first_collision);
		if (plugin.api->event_driven) {
			const double worst = *std::max_element(r.track.error.begin(), r.track.error.end());
			CHECK(worst == 0.0 && r.horizon_censored, "%s: %g m from its own reference", name.c_str(), worst);
		} else {
			CHECK(r.horizon_seconds >= first_collision, "%s departs at %g s, before the first collision at %g s",
			      name.c_str(), r.horizon_seconds, first_collision);
		}
		Record back;
		CHECK(record_from_wire(record_wire(r), &back, &error) && back.track.t == r.track.t &&
		          back.track.error == r.track.error && back.horizon_seconds == r.horizon_seconds &&
		          back.horizon_censored == r.horizon_censored && back.balls == 16,
		      "%s: the horizon changed on the wire", name.c_str());
		CHECK(record_json(r).find("\"horizon_seconds\":") != std::string::npos, "%s: no horizon_seconds",
		      name.c_str());
	}
}

Record stepped(const std::string &engine, double dt, double horizon, bool censored, double cpu) {
	Record r;
	r.scenario = "scale_gas_64";
	r.engine = engine;
	r.dt = dt;
	r.horizon_seconds = horizon;
	r.horizon_censored = censored;
	r.cpu_seconds = cpu;
	r.sim_seconds = 2.0;
	return r;
}

void predictability_choice() {
	ScenarioHorizons h;
	h.scenario = "scale_gas_64";
	h.balls = 64;
	h.family = "gas";
	h.end_time = 2.0;
	SelfHorizon mm;
	mm.perturbation = 1e-3;
	mm.horizon.seconds = 0.3;
	SelfHorizon um;
	um.perturbation = 1e-6;
	um.horizon.seconds = 2.0;
	um.horizon.censored = true;
	h.self = {um, mm};
	Record lib;
	lib.scenario = h.scenario;
	lib.engine = "libpool";
	lib.event_driven = true;
	lib.cpu_seconds = 0.5;
	lib.sim_seconds = 2.0;
	// A lucky coarse step (1e-2) does not count: 1e-3 falls short, so only 1e-4 and finer qualify.
	std::vector<Record> records = {lib, stepped("ode", 1e-2, 0.5, false, 0.01), stepped("ode", 1e-3, 0.1, false, 0.1),
	                               stepped("ode", 1e-4, 0.6, false, 1.0), stepped("ode", 1e-5, 2.0, true, 10.0)};
	auto eq = equal_predictability(records, h, 1e-3);
	CHECK(eq.size() == 1 && eq[0].run && eq[0].run->dt == 1e-4, "1 mm: %s",
	      eq.empty() || !eq[0].run ? "none" : std::to_string(eq[0].run->dt).c_str());
	// A censored self horizon needs a censored run.
	eq = equal_predictability(records, h, 1e-6);
	CHECK(eq.size() == 1 && eq[0].run && eq[0].run->dt == 1e-5, "1 um: %s",
	      eq.empty() || !eq[0].run ? "none" : std::to_string(eq[0].run->dt).c_str());
	std::string verdict = scale_verdict(records, {h}, 1e-3);
	CHECK(verdict.find("At no ball count") != std::string::npos, "verdict: %s", verdict.c_str());
	records[3].cpu_seconds = 0.2; // ODE at 1e-4 now cheaper than libpool's 0.5 s
	verdict = scale_verdict(records, {h}, 1e-3);
	CHECK(verdict.find("gas at 64 balls: ode at dt 1e-04") != std::string::npos, "verdict: %s", verdict.c_str());
	const std::string table = scale_table(records, {h}, 1e-3, false);
	CHECK(table.find("ode (2.5x)") != std::string::npos, "table:\n%s", table.c_str());
}

} // namespace

int main(int argc, char **argv) {
	if (argc < 3) {
		std::fprintf(stderr, "usage: test_scale SCENARIO_DIR PLUGIN_DIR ENGINE...\n");
		return 2;
	}
	scenario_dir = argv[1];
	const std::vector<Plugin> plugins = load_plugins(argc, argv, 3, argv[2]);
	families();
	horizon_pieces();
	translation();
	linear_response();
	engine_tracks(plugins);
	predictability_choice();
	return finish();
}
