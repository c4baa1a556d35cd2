// Every built engine plugin against the closed forms (PHYSICS.md, VALIDATION.md, ENGINES.md) and
// the conservation laws of a frictionless elastic hit; also the harness's own closed form.
// usage: test_compare_engines SCENARIO_DIR PLUGIN_DIR ENGINE...   (the engines that must exist)
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "plugin_loader.h"
#include "reference.h"
#include "runner.h"
#include "scenario_file.h"

using namespace pool_compare;

namespace {

int failures = 0;

#define CHECK(cond, ...)                                                                                   \
	do {                                                                                                   \
		if (!(cond)) {                                                                                     \
			++failures;                                                                                    \
			std::printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                    \
			std::printf(__VA_ARGS__);                                                                      \
			std::printf("\n");                                                                             \
		}                                                                                                  \
	} while (0)

std::string scenario_dir;

std::unique_ptr<Scenario> load(const std::string &name) {
	std::unique_ptr<Scenario> s;
	std::string error;
	if (!load_scenario(scenario_dir + "/" + name + ".json", &s, &error)) {
		std::printf("FAIL cannot load %s: %s\n", name.c_str(), error.c_str());
		++failures;
	}
	return s;
}

// ENGINES.md: a 2 m/s pure slide rolls at 0.29125 s at 5/7 of the speed, stops at 14.85 s after 10.901 m.
void closed_form_matches_engines_md() {
	auto s = load("slide");
	if (!s)
		return;
	auto ref = make_closed_form_reference(*s);
	CHECK(ref != nullptr, "the slide has a closed form");
	if (!ref)
		return;
	CHECK(ref->kind() == "closed-form", "%s", ref->kind().c_str());
	CHECK(ref->events.size() == 2, "%zu events", ref->events.size());
	const double mu = 0.2, g = 9.81;
	CHECK(std::fabs(ref->events[0].t - 4.0 / (7.0 * mu * g)) < 1e-15, "roll at %.17g", ref->events[0].t);
	CHECK(std::fabs(ref->events[0].t - 0.29125) < 1e-5, "roll at %.17g", ref->events[0].t);
	const BallSample at_roll = ref->state_at(ref->events[0].t)[0];
	CHECK(std::fabs(at_roll.vel.x() - 10.0 / 7.0) < 1e-12, "speed at roll %.17g", at_roll.vel.x());
	CHECK(std::fabs(at_roll.pos.x() - 0.5 - 12.0 * 4.0 / (49.0 * mu * g)) < 1e-12, "slide distance");
	CHECK(std::fabs(ref->end_time - 14.85) < 0.005, "stop at %.17g", ref->end_time);
	const double run = ref->state_at(ref->end_time)[0].pos.x() - 0.5;
	CHECK(std::fabs(run - 10.901) < 5e-4, "run %.17g m", run);
	CHECK(ref->at_rest, "at rest");
}

// VALIDATION.md 2: spin k = R w / v0 gives final speed v0 (5 + 2k) / 7 after 2 |1 - k| v0 / (7 mu g).
void closed_form_matches_validation_2() {
	for (const char *name : {"stun", "draw", "follow"}) {
		auto s = load(name);
		if (!s)
			continue;
		auto ref = make_closed_form_reference(*s);
		CHECK(ref != nullptr, "%s has a closed form", name);
		if (!ref)
			continue;
		const pool_params &p = s->parsed.def.params;
		Eigen::Vector3d v, w;
		strike_velocities(p, s->parsed.strike, true, &v, &w);
		const double v0 = v.norm(), k = p.ball_radius * w.y() / v0;
		const double t_roll = 2.0 * std::fabs(1.0 - k) * v0 / (7.0 * p.mu_slide * p.g);
		CHECK(std::fabs(ref->events[0].t - t_roll) < 1e-12, "%s: roll at %.17g, expected %.17g", name,
		      ref->events[0].t, t_roll);
		const double speed = ref->state_at(t_roll + 1e-9)[0].vel.x();
		CHECK(std::fabs(speed - v0 * (5.0 + 2.0 * k) / 7.0) < 1e-8, "%s: %.17g", name, speed);
	}
}

// The harness computes the strike itself; it must agree with libpool's.
void strike_matches_libpool() {
	const pool_params p = pool_default_params();
	const double R = p.ball_radius;
	const pool_strike strikes[] = {{2.0, 0.0, 0.0, 0.0, 0.0},          {1.5, 0.3, 0.0, 0.0, -0.5 * R},
	                               {3.0, 2.0, 0.0, 0.4 * R, 0.3 * R}, {2.0, -1.0, 0.2, -0.3 * R, 0.1 * R}};
	for (const pool_strike &s : strikes) {
		Eigen::Vector3d v, w;
		strike_velocities(p, s, false, &v, &w);
		pool_vec3 lv, lw;
		pool_error e = {{0}};
		CHECK(pool_strike_velocities(&p, &s, &lv, &lw, &e) == POOL_OK, "%s", e.message);
		CHECK((v - Eigen::Vector3d(lv.x, lv.y, lv.z)).norm() <= 1e-12 * (1.0 + v.norm()), "velocity");
		CHECK((w - Eigen::Vector3d(lw.x, lw.y, lw.z)).norm() <= 1e-12 * (1.0 + w.norm()), "spin");
	}
}

// Slide -> roll -> stop: error shrinking with the time step, libpool exact.
void engine_reproduces_slide(const Plugin &plugin) {
	auto s = load("slide");
	if (!s)
		return;
	auto ref = make_closed_form_reference(*s);
	const char *name = plugin.api->name;
	RunSettings settings;
	settings.min_timing_cpu = 0.0;
	if (plugin.api->event_driven) {
		const Record r = run_engine(*s, *ref, plugin, settings);
		CHECK(r.error.empty(), "%s: %s", name, r.error.c_str());
		CHECK(r.final_position_error <= 1e-9 * 10.901, "%s: %.3g m", name, r.final_position_error);
		CHECK(r.event_time_error <= 1e-9 * 14.85, "%s: %.3g s", name, r.event_time_error);
		CHECK(r.energy_error <= 1e-9 * 0.34, "%s: %.3g J", name, r.energy_error);
		CHECK(r.unmatched_events == 0, "%s: %d", name, r.unmatched_events);
		std::printf("  %s slide: position %.3g m, event time %.3g s\n", name, r.final_position_error,
		            r.event_time_error);
		return;
	}
	settings.dt = 1e-2;
	const Record coarse = run_engine(*s, *ref, plugin, settings);
	settings.dt = 1e-4;
	const Record fine = run_engine(*s, *ref, plugin, settings);
	CHECK(coarse.error.empty() && fine.error.empty(), "%s: %s %s", name, coarse.error.c_str(), fine.error.c_str());
	CHECK(fine.unmatched_events == 0, "%s reports slide_roll and roll_stop (%d missing)", name, fine.unmatched_events);
	CHECK(fine.final_position_error < coarse.final_position_error, "%s: %.3g m at 1e-4, %.3g m at 1e-2", name,
	      fine.final_position_error, coarse.final_position_error);
	CHECK(fine.event_time_error < coarse.event_time_error, "%s: %.3g s at 1e-4, %.3g s at 1e-2", name,
	      fine.event_time_error, coarse.event_time_error);
	CHECK(fine.final_position_error < 1e-3, "%s: %.3g m at 1e-4", name, fine.final_position_error);
	// Rolling onset is pure discretisation; the stop time also depends on the engine's rest
	// threshold (1e-3 m/s stops 10 ms early at a rolling deceleration of 0.098 m/s^2).
	CHECK(fine.slide_roll_time_error < 1e-3, "%s: roll onset %.3g s off at 1e-4", name, fine.slide_roll_time_error);
	CHECK(fine.stop_time_error < 2e-2, "%s: stop %.3g s off at 1e-4", name, fine.stop_time_error);
	CHECK(coarse.final_position_error < 0.05, "%s: %.3g m at 1e-2", name, coarse.final_position_error);
	std::printf("  %s slide: position %.3g m / %.3g m, event time %.3g s / %.3g s (roll onset %.3g s, stop %.3g s) "
	            "at dt 1e-2 / 1e-4\n",
	            name, coarse.final_position_error, fine.final_position_error, coarse.event_time_error,
	            fine.event_time_error, fine.slide_roll_time_error, fine.stop_time_error);
}

// Frictionless (cloth and ball-ball) elastic head-on hit: momentum conserved, speed handed over.
void engine_transfers_speed(const Plugin &plugin) {
	const std::string json = R"({
	  "format": "libpool-scenario/1",
	  "params": {"mu_ball": 0.0, "e_ball": 1.0, "mu_slide": 0.0, "mu_roll": 0.0, "mu_spin": 0.0},
	  "balls": [{"id": 0, "pos": [0.8, 0.635], "vel": [1.0, 0.0, 0.0]}, {"id": 1, "pos": [1.2, 0.635]}],
	  "options": {"max_time": 1.0}})";
	const char *name = plugin.api->name;
	const double R = 0.028575, t_hit = (0.4 - 2.0 * R) / 1.0;
	for (double dt : {1e-3, 1e-4}) {
		if (plugin.api->event_driven && dt < 1e-3)
			break;
		pool_engine_config config = {dt, 0};
		char err[512] = {0};
		void *engine = plugin.api->create(json.c_str(), &config, err, sizeof err);
		CHECK(engine != nullptr, "%s: %s", name, err);
		if (!engine)
			return;
		auto momentum_x = [&](double t, double *p, double *v0, double *v1) {
			CHECK(plugin.api->advance(engine, t) == 0, "%s: %s", name, plugin.api->last_error(engine));
			pool_engine_ball balls[2];
			CHECK(plugin.api->balls(engine, balls, 2) == 2, "%s: two balls", name);
			*v0 = balls[0].id == 0 ? balls[0].vel[0] : balls[1].vel[0];
			*v1 = balls[0].id == 0 ? balls[1].vel[0] : balls[0].vel[0];
			*p = *v0 + *v1; // equal masses
		};
		double p_before, p_after, a0, a1, b0, b1;
		momentum_x(t_hit - 0.02, &p_before, &b0, &b1);
		momentum_x(t_hit + 0.02, &p_after, &a0, &a1);
		CHECK(std::fabs(p_before - 1.0) < 1e-3, "%s dt %g: %.9g m/s before", name, dt, p_before);
		CHECK(std::fabs(p_after - p_before) < 1e-6, "%s dt %g: momentum %.12g -> %.12g", name, dt, p_before, p_after);
		CHECK(std::fabs(a1 - 1.0) < 0.02 && std::fabs(a0) < 0.02, "%s dt %g: after the hit %.6g and %.6g m/s", name,
		      dt, a0, a1);
		std::printf("  %s elastic dt %g: momentum change %.3g, speeds after %.6f / %.6f m/s\n", name, dt,
		            p_after - p_before, a0, a1);
		plugin.api->destroy(engine);
	}
}

} // namespace

int main(int argc, char **argv) {
	if (argc < 3) {
		std::fprintf(stderr, "usage: test_compare_engines SCENARIO_DIR PLUGIN_DIR ENGINE...\n");
		return 2;
	}
	scenario_dir = argv[1];
	closed_form_matches_engines_md();
	closed_form_matches_validation_2();
	strike_matches_libpool();
	for (int i = 3; i < argc; ++i) {
		Plugin plugin;
		std::string error;
		CHECK(load_plugin(argv[i], argv[2], &plugin, &error), "expected engine missing: %s", error.c_str());
		if (!plugin.api)
			continue;
		engine_reproduces_slide(plugin);
		engine_transfers_speed(plugin);
	}
	std::printf("%s (%d failures)\n", failures ? "FAILED" : "passed", failures);
	return failures ? 1 : 0;
}
