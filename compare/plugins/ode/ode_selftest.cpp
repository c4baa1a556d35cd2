// Self-test of the ODE plugin against closed forms (docs/physics.md, docs/engines.md), through the real
// module and its C ABI:  ode_selftest PATH/libpool_engine_ode.so [--bench]
// --bench prints the cost per step for 1 and 16 balls (median and minimum of 5 runs) instead.
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "pool_engine_plugin.h"
#include "selftest_support.h"

namespace {

using pool_plugin::fmt;

const pool_engine_api *api = nullptr;
int failures = 0;

// Defaults of docs/physics.md, which the scenarios below rely on.
const double kG = 9.81, kMuSlide = 0.2, kMuRoll = 0.01, kMuSpin = 0.0127, kR = 0.028575;
const double kPi = 3.14159265358979323846;

void check(bool ok, const char *what, double value, double bound) {
	std::printf("%-58s %12.6g  (bound %g)  %s\n", what, value, bound, ok ? "ok" : "FAIL");
	if (!ok)
		++failures;
}

// A scenario on a long test table so shots run their full course without cushions.
std::string big_table_scenario(const std::string &balls, const std::string &extra = "") {
	return fmt("{\"format\": \"libpool-scenario/1\", \"table\": {\"length\": 20.0, \"width\": 20.0},"
	           " \"balls\": [%s]%s}",
	           balls.c_str(), extra.c_str());
}

struct Run {
	void *engine = nullptr;
	std::vector<pool_engine_event> events;
	std::vector<pool_engine_ball> balls;
	pool_engine_stats stats{};
};

void *create(const std::string &json, double dt, std::string *error = nullptr) {
	pool_engine_config config = {dt, 0};
	char err[512] = {0};
	void *e = api->create(json.c_str(), &config, err, sizeof err);
	if (error)
		*error = err;
	if (!e && !error)
		std::printf("create failed: %s\n", err);
	return e;
}

void collect(Run *r) {
	int n = api->events(r->engine, nullptr, 0);
	r->events.resize(size_t(std::max(n, 0)));
	api->events(r->engine, r->events.data(), n);
	int nb = api->balls(r->engine, nullptr, 0);
	r->balls.resize(size_t(std::max(nb, 0)));
	api->balls(r->engine, r->balls.data(), nb);
	api->stats(r->engine, &r->stats);
}

const pool_engine_event *find_event(const Run &r, int type, int ball) {
	for (const auto &e : r.events)
		if (e.type == type && (ball < 0 || e.ball_a == ball))
			return &e;
	return nullptr;
}

// 2 m/s pure slide (no spin) along +x: rolling at t1 = 2 v0 / (7 mu g) with v = 5/7 v0,
// stop after a further (5/7 v0) / (mu_roll g), at x0 + slide distance + rolling distance.
void test_pure_slide() {
	const double v0 = 2.0, x0 = 1.0;
	const double t1 = 2.0 * v0 / (7.0 * kMuSlide * kG);
	const double v1 = 5.0 / 7.0 * v0;
	const double x1 = x0 + v0 * t1 - 0.5 * kMuSlide * kG * t1 * t1;
	const double t2 = t1 + v1 / (kMuRoll * kG);
	const double x2 = x1 + v1 * v1 / (2.0 * kMuRoll * kG);
	std::printf("pure slide closed form: roll at %.5f s (%.5f m/s), stop at %.4f s, x = %.4f m\n",
	            t1, v1, t2, x2);
	const double dts[3] = {1e-2, 1e-3, 1e-4};
	double onset_err[3], stop_err[3], pos_err[3], speed_err[3];
	for (int k = 0; k < 3; ++k) {
		Run r;
		r.engine = create(big_table_scenario(fmt("{\"id\": 0, \"pos\": [%g, 1.0], \"vel\": [%g, 0]}",
		                                         x0, v0)),
		                  dts[k]);
		if (!r.engine) {
			++failures;
			return;
		}
		// Speed just after rolling starts: step to the onset and read the ball.
		api->advance(r.engine, t1 + dts[k]);
		collect(&r);
		double speed = std::hypot(r.balls[0].vel[0], r.balls[0].vel[1]);
		speed_err[k] = speed - (v1 - kMuRoll * kG * (r.stats.sim_time - t1));
		api->run_to_rest(r.engine, 30.0);
		collect(&r);
		const pool_engine_event *roll = find_event(r, POOL_ENGINE_EVENT_SLIDE_ROLL, 0);
		const pool_engine_event *stop = find_event(r, POOL_ENGINE_EVENT_ROLL_STOP, 0);
		onset_err[k] = roll ? roll->t - t1 : 1e9;
		stop_err[k] = stop ? stop->t - t2 : 1e9;
		pos_err[k] = std::hypot(r.balls[0].pos[0] - x2, r.balls[0].pos[1] - 1.0);
		std::printf("  dt %-6g: onset %+.3e s, stop time %+.3e s, stop position %.3e m, speed at "
		            "onset %+.2e m/s, state %d, %lld steps\n",
		            dts[k], onset_err[k], stop_err[k], pos_err[k], speed_err[k], r.balls[0].state,
		            (long long)r.stats.steps);
		check(r.balls[0].state == 0, "pure slide: ball ends stationary (state)", r.balls[0].state, 0);
		api->destroy(r.engine);
	}
	check(std::fabs(onset_err[2]) < 1e-3, "pure slide: rolling onset error at dt 1e-4 (s)",
	      onset_err[2], 1e-3);
	check(onset_err[0] >= 0 && onset_err[0] <= 1e-2 + 1e-9,
	      "pure slide: onset error at dt 1e-2 within one step (s)", onset_err[0], 1e-2);
	check(std::fabs(onset_err[2]) < std::fabs(onset_err[1]) &&
	          std::fabs(onset_err[1]) < std::fabs(onset_err[0]),
	      "pure slide: onset error shrinks with dt (|e(1e-3)|)", onset_err[1], onset_err[0]);
	check(pos_err[2] < 3e-3, "pure slide: stop position error at dt 1e-4 (m)", pos_err[2], 3e-3);
	check(pos_err[1] < 5e-3, "pure slide: stop position error at dt 1e-3 (m)", pos_err[1], 5e-3);
	check(pos_err[2] <= pos_err[0], "pure slide: stop position error shrinks (dt 1e-4 vs 1e-2)",
	      pos_err[2], pos_err[0]);
	check(std::fabs(stop_err[2]) < 0.02, "pure slide: stop time error at dt 1e-4 (s)", stop_err[2],
	      0.02);
	check(std::fabs(speed_err[2]) < 1e-3, "pure slide: speed at onset, 5/7 v0 (m/s error)",
	      speed_err[2], 1e-3);
}

// Spin about z alone decays at 5 mu_spin g / (2R): rest at 2 R w0 / (5 mu_spin g).
void test_spin_decay() {
	const double w0 = 10.0, dt = 1e-4;
	const double t_stop = 2.0 * kR * w0 / (5.0 * kMuSpin * kG);
	Run r;
	r.engine = create(big_table_scenario(fmt("{\"id\": 0, \"pos\": [1, 1], \"omega\": [0, 0, %g]}",
	                                         w0)),
	                  dt);
	if (!r.engine) {
		++failures;
		return;
	}
	api->advance(r.engine, 0.5 * t_stop);
	collect(&r);
	const double w_half = r.balls[0].omega[2];
	check(std::fabs(w_half - 0.5 * w0) < 0.01, "z-spin: omega_z at half the stop time (rad/s)",
	      w_half, 0.5 * w0);
	check(r.balls[0].state == 1, "z-spin: state spinning", r.balls[0].state, 1);
	api->run_to_rest(r.engine, 5.0);
	collect(&r);
	check(std::fabs(r.stats.sim_time - t_stop) < 2e-3, "z-spin: rest time error (s)",
	      r.stats.sim_time - t_stop, 2e-3);
	api->destroy(r.engine);
}

// Frictionless elastic head-on hit: the object ball takes the cue ball's speed, momentum kept.
void test_head_on(double dt) {
	const double v0 = 2.0;
	std::string balls = fmt("{\"id\": 0, \"pos\": [0.5, 0.635], \"vel\": [%g, 0], \"omega\": [0, %.17g, 0]},"
	                        " {\"id\": 1, \"pos\": [1.0, 0.635]}",
	                        v0, v0 / kR);
	std::string json = fmt("{\"format\": \"libpool-scenario/1\", \"params\": {\"mu_ball\": 0,"
	                       " \"e_ball\": 1}, \"balls\": [%s]}",
	                       balls.c_str());
	Run r;
	r.engine = create(json, dt);
	if (!r.engine) {
		++failures;
		return;
	}
	double before[2] = {0, 0};
	bool hit = false;
	for (int k = 1; k < 200000 && !hit; ++k) {
		collect(&r);
		before[0] = r.balls[0].vel[0];
		before[1] = r.balls[1].vel[0];
		api->advance(r.engine, k * dt);
		hit = api->events(r.engine, nullptr, 0) > 0;
		collect(&r);
		if (hit && !find_event(r, POOL_ENGINE_EVENT_BALL_BALL, 0))
			hit = false;
	}
	// The contact is found at the start of a step and resolved in that same step.
	if (hit)
		api->advance(r.engine, r.stats.sim_time + dt);
	collect(&r);
	const double ratio = r.balls[1].vel[0] / before[0];
	const double p_before = before[0] + before[1], p_after = r.balls[0].vel[0] + r.balls[1].vel[0];
	std::printf("  head-on dt %g: hit %d, cue %.6f m/s before, object %.6f after, cue %.2e after\n",
	            dt, hit, before[0], r.balls[1].vel[0], r.balls[0].vel[0]);
	check(hit && ratio >= 0.99, fmt("head-on e=1 mu=0 dt %g: object/cue speed", dt).c_str(),
	      ratio, 0.99);
	check(std::fabs(p_after - p_before) / p_before < 2e-3,
	      fmt("head-on e=1 mu=0 dt %g: momentum change (relative)", dt).c_str(),
	      (p_after - p_before) / p_before, 2e-3);
	api->destroy(r.engine);
}

// A 30 degree shot must go straight (ODE's world-aligned friction box curves it otherwise).
void test_angle(double dt, double b_offset) {
	const double phi = 30.0;
	Run r;
	r.engine = create(big_table_scenario("{\"id\": 0, \"pos\": [1, 1]}",
	                                     fmt(", \"strike\": {\"ball\": 0, \"speed\": 1.5, \"phi\": %g,"
	                                         " \"b\": %g}",
	                                         phi, b_offset)),
	                  dt);
	if (!r.engine) {
		++failures;
		return;
	}
	api->run_to_rest(r.engine, 30.0);
	collect(&r);
	const double dx = r.balls[0].pos[0] - 1.0, dy = r.balls[0].pos[1] - 1.0;
	const double angle = std::atan2(dy, dx) * 180.0 / kPi;
	check(std::fabs(angle - phi) < 0.1 && std::hypot(dx, dy) > 1.0,
	      fmt("30 deg strike (b = %g m, dt %g): direction error (deg)", b_offset, dt).c_str(),
	      angle - phi, 0.1);
	api->destroy(r.engine);
}

// A sliding ball sent into the west cushion at an angle: contact when its centre reaches the
// touch distance d0 = sqrt(R^2 - (h - R)^2) from the nose line, and the velocities after it
// as Petit's law gives them for the state the closed form predicts at contact.
void test_cushion(double dt) {
	const double h = 0.03629, x0 = 0.5, vx0 = -2.0, vy0 = 0.5, e_c = 0.85, mu_c = 0.2;
	const double d0 = std::sqrt(kR * kR - (h - kR) * (h - kR));
	// Pure slide (no initial spin) lasts 2 |v0| / (7 mu g) = 0.30 s: still sliding at contact.
	const double v0 = std::hypot(vx0, vy0), ux = vx0 / v0, uy = vy0 / v0;
	const double a = 0.5 * kMuSlide * kG * (-ux); // x(t) = x0 + vx0 t + a t^2
	const double t_hit = (-vx0 - std::sqrt(vx0 * vx0 - 4.0 * a * (x0 - d0))) / (2.0 * a);
	const double s = v0 - kMuSlide * kG * t_hit, k_w = 5.0 * kMuSlide * kG * t_hit / (2.0 * kR);
	double v[3] = {s * ux, s * uy, 0.0};
	double w[3] = {-k_w * uy, k_w * ux, 0.0}; // (5 mu g t / 2R) (k x u)
	const double n[3] = {d0 / kR, 0.0, (kR - h) / kR};
	pool_plugin::petit_impact(n, e_c, mu_c, kR, v, w);
	v[2] = 0.0; // planar mode drops the vertical velocity the impact leaves
	Run r;
	r.engine = create(fmt("{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 3, \"pos\": "
	                      "[%g, 0.635], \"vel\": [%g, %g]}]}",
	                      x0, vx0, vy0),
	                  dt);
	if (!r.engine) {
		++failures;
		return;
	}
	api->advance(r.engine, t_hit + 1.5 * dt);
	collect(&r);
	const pool_engine_event *e = find_event(r, POOL_ENGINE_EVENT_BALL_CUSHION, 3);
	const double err = e ? e->t - t_hit : 1e9;
	check(e && err >= -1e-12 && err <= dt + 1e-12,
	      fmt("cushion (dt %g): contact time error, within one step (s)", dt).c_str(), err, dt);
	if (e)
		api->advance(r.engine, e->t + dt); // the contact is resolved in the step it is found
	collect(&r);
	double dv = 0.0, dw = 0.0;
	for (int k = 0; k < 3; ++k) {
		dv = std::max(dv, std::fabs(r.balls[0].vel[k] - v[k]));
		dw = std::max(dw, std::fabs(r.balls[0].omega[k] - w[k]) * kR);
	}
	std::printf("  cushion dt %g: after v (%.5f, %.5f) w (%.4f, %.4f, %.4f); Petit v (%.5f, %.5f) "
	            "w (%.4f, %.4f, %.4f)\n",
	            dt, r.balls[0].vel[0], r.balls[0].vel[1], r.balls[0].omega[0], r.balls[0].omega[1],
	            r.balls[0].omega[2], v[0], v[1], w[0], w[1], w[2]);
	const double tol = 10.0 * kMuSlide * kG * dt + 1e-3;
	check(dv < tol, fmt("cushion (dt %g): velocity after vs Petit (m/s)", dt).c_str(), dv, tol);
	check(dw < tol, fmt("cushion (dt %g): R * spin after vs Petit (m/s)", dt).c_str(), dw, tol);
	check(r.stats.max_penetration < v0 * dt + 1e-6,
	      fmt("cushion (dt %g): penetration below v dt (m)", dt).c_str(), r.stats.max_penetration,
	      v0 * dt);
	api->destroy(r.engine);
}

// A 30 degree cut with a rolling cue ball (e_ball 0.95, mu_ball 0.06): the object ball's
// direction and speed after contact against Petit's two-ball law at the exact contact.
void test_cut(double dt, double angle_bound) {
	const double v0 = 2.0, cut = 30.0 * kPi / 180.0, xc0 = 0.6, y0 = 0.635, e_b = 0.95, mu_b = 0.06;
	const double xo = 1.2, yo = y0 + 2.0 * kR * std::sin(cut);
	const double x_hit = xo - 2.0 * kR * std::cos(cut);
	// Rolling: x = xc0 + v0 t - mu_roll g t^2 / 2.
	const double a = 0.5 * kMuRoll * kG;
	const double t_hit = (v0 - std::sqrt(v0 * v0 - 4.0 * a * (x_hit - xc0))) / (2.0 * a);
	const double v = v0 - kMuRoll * kG * t_hit;
	double v1[3] = {v, 0, 0}, w1[3] = {0, v / kR, 0}, v2[3] = {0, 0, 0};
	const double n[3] = {(x_hit - xo) / (2.0 * kR), (y0 - yo) / (2.0 * kR), 0.0};
	double rel[3], vc[3], vcl = 0.0, reln = 0.0;
	for (int k = 0; k < 3; ++k) {
		rel[k] = v1[k] - v2[k];
		reln += rel[k] * n[k];
	}
	const double rw[3] = {kR * w1[0], kR * w1[1], kR * w1[2]};
	const double nxrw[3] = {n[1] * rw[2] - n[2] * rw[1], n[2] * rw[0] - n[0] * rw[2],
	                        n[0] * rw[1] - n[1] * rw[0]};
	for (int k = 0; k < 3; ++k) {
		vc[k] = rel[k] - reln * n[k] + nxrw[k];
		vcl += vc[k] * vc[k];
	}
	vcl = std::sqrt(vcl);
	const double p = (1.0 + e_b) * (-reln) / 2.0; // P / M1 with M1 / M2 = 1
	const bool slipping = vcl > 0.0 && 1.0 - 3.5 * mu_b * 2.0 * p / vcl >= 0.0;
	double v1n[3];
	for (int k = 0; k < 3; ++k)
		v1n[k] = slipping ? v1[k] + p * (n[k] - mu_b * vc[k] / vcl)
		                  : v1[k] + p * n[k] - 2.0 / 7.0 * vc[k] / 2.0;
	for (int k = 0; k < 3; ++k)
		v2[k] = v2[k] + (v1[k] - v1n[k]);
	const double want_angle = std::atan2(v2[1], v2[0]) * 180.0 / kPi, want_speed = std::hypot(v2[0], v2[1]);
	Run r;
	r.engine = create(fmt("{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": "
	                      "[%g, %.17g], \"vel\": [%g, 0], \"omega\": [0, %.17g, 0]}, {\"id\": 1, "
	                      "\"pos\": [%g, %.17g]}]}",
	                      xc0, y0, v0, v0 / kR, xo, yo),
	                  dt);
	if (!r.engine) {
		++failures;
		return;
	}
	api->advance(r.engine, t_hit + 1.5 * dt);
	collect(&r);
	const pool_engine_event *e = find_event(r, POOL_ENGINE_EVENT_BALL_BALL, 0);
	const double angle = std::atan2(r.balls[1].vel[1], r.balls[1].vel[0]) * 180.0 / kPi;
	const double speed = std::hypot(r.balls[1].vel[0], r.balls[1].vel[1]);
	std::printf("  cut dt %g: contact at %+.2e s, object ball %.4f deg %.5f m/s; Petit %.4f deg "
	            "%.5f m/s (%s)\n",
	            dt, e ? e->t - t_hit : 0.0, angle, speed, want_angle, want_speed,
	            slipping ? "slipping" : "sticking");
	check(e && std::fabs(angle - want_angle) < angle_bound,
	      fmt("30 deg cut (dt %g): object ball direction error (deg)", dt).c_str(), angle - want_angle,
	      angle_bound);
	check(std::fabs(speed / want_speed - 1.0) < 0.01,
	      fmt("30 deg cut (dt %g): object ball speed error (relative)", dt).c_str(),
	      speed / want_speed - 1.0, 0.01);
	api->destroy(r.engine);
}

// Into the corner and side pockets.
void test_pockets() {
	Run r;
	r.engine = create("{\"format\": \"libpool-scenario/1\", \"balls\": ["
	                  "{\"id\": 1, \"pos\": [0.3, 0.3], \"vel\": [-1.5, -1.5]},"
	                  "{\"id\": 2, \"pos\": [1.27, 0.4], \"vel\": [0, -2]},"
	                  "{\"id\": 3, \"pos\": [1.6, 1.0], \"vel\": [0, 2]}]}",
	                  1e-3);
	if (!r.engine) {
		++failures;
		return;
	}
	api->run_to_rest(r.engine, 20.0);
	collect(&r);
	check(find_event(r, POOL_ENGINE_EVENT_POCKET, 1) && r.balls[0].state == 6,
	      "pockets: ball 1 into the corner (state)", r.balls[0].state, 6);
	check(find_event(r, POOL_ENGINE_EVENT_POCKET, 2) && r.balls[1].state == 6,
	      "pockets: ball 2 into the side pocket (state)", r.balls[1].state, 6);
	check(!find_event(r, POOL_ENGINE_EVENT_POCKET, 3) && r.balls[2].state == 0 &&
	          find_event(r, POOL_ENGINE_EVENT_BALL_CUSHION, 3),
	      "pockets: ball 3 off the north cushion stays (state)", r.balls[2].state, 0);
	api->destroy(r.engine);
}

// Bad input is refused with the parser's message; NULLs and bad times do not crash.
void test_rejections() {
	struct Case {
		const char *json;
		double dt;
		const char *expect;
	} cases[] = {
		{"{", 1e-3, ""},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [1, 0.6]},"
		 " {\"id\": 1, \"pos\": [1.03, 0.6]}]}",
		 1e-3, "balls[1].pos"},
		{"{\"format\": \"libpool-scenario/1\", \"bogus\": 1, \"balls\": [{\"id\": 0, \"pos\": [1, 0.6]}]}",
		 1e-3, "bogus"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [1, 0.6]}],"
		 " \"strike\": {\"ball\": 0, \"speed\": 1, \"a\": 0.025, \"b\": 0.02}}",
		 1e-3, "strike"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [1, 0.6]}]}", 0.0,
		 "config.dt"},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [1, 0.6]}]}", NAN,
		 "config.dt"},
	};
	for (const Case &c : cases) {
		std::string err;
		void *e = create(c.json, c.dt, &err);
		bool ok = !e && !err.empty() && err.find(c.expect) != std::string::npos;
		std::printf("  rejected: %s\n", err.c_str());
		check(ok, fmt("bad input rejected, message names '%s'", c.expect).c_str(), e ? 1 : 0, 0);
		api->destroy(e);
	}
	char err[64];
	check(api->create(nullptr, nullptr, err, sizeof err) == nullptr, "NULL scenario rejected", 0, 0);
	check(api->advance(nullptr, 1.0) < 0 && api->run_to_rest(nullptr, 1.0) < 0 &&
	          api->balls(nullptr, nullptr, 0) < 0 && api->events(nullptr, nullptr, 0) < 0,
	      "NULL engine calls fail cleanly", 0, 0);
	api->destroy(nullptr);
	void *e = create("{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": [1, 0.6]}]}",
	                 1e-3);
	check(e && api->advance(e, NAN) < 0 && std::strlen(api->last_error(e)) > 0,
	      "advance(NaN) fails with a message", 0, 0);
	api->destroy(e);
}

// Two engines at once, destroyed in creation order (ODE's init/close refcount).
void test_two_engines() {
	std::string json = "{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"pos\": "
	                   "[1, 0.6], \"vel\": [1, 0]}]}";
	void *a = create(json, 1e-3), *b = create(json, 1e-3);
	api->advance(a, 0.5);
	api->destroy(a);
	api->advance(b, 0.5);
	void *c = create(json, 1e-3);
	api->advance(c, 0.5);
	pool_engine_ball bb, bc;
	api->balls(b, &bb, 1);
	api->balls(c, &bc, 1);
	check(a && b && c && bb.pos[0] == bc.pos[0], "two engines at once: same answer (x, m)",
	      bb.pos[0], bc.pos[0]);
	api->destroy(b);
	api->destroy(c);
}

std::string rack_scenario() {
	// Cue ball on the head spot, 15 balls in a triangle 0.1 mm apart, 8 m/s break.
	const double L = 2.54, W = 1.27, gap = 1e-4, d = 2.0 * kR + gap;
	std::string balls = fmt("{\"id\": 0, \"pos\": [%.9f, %.9f]}", L / 4, W / 2);
	int id = 1;
	for (int row = 0; row < 5; ++row)
		for (int k = 0; k <= row; ++k)
			balls += fmt(", {\"id\": %d, \"pos\": [%.9f, %.9f]}", id++,
			             3 * L / 4 + row * d * std::sqrt(3.0) / 2, W / 2 + (k - row / 2.0) * d);
	return fmt("{\"format\": \"libpool-scenario/1\", \"balls\": [%s], \"strike\": {\"ball\": 0,"
	           " \"speed\": 8.0}}",
	           balls.c_str());
}

double median(std::vector<double> v) {
	std::sort(v.begin(), v.end());
	return v[v.size() / 2];
}

void bench() {
	struct utsname u;
	uname(&u);
	std::string cpu = "?";
	std::ifstream info("/proc/cpuinfo");
	for (std::string line; std::getline(info, line);)
		if (line.rfind("model name", 0) == 0) {
			cpu = line.substr(line.find(':') + 2);
			break;
		}
	std::printf("machine: %s %s, %s\n", u.sysname, u.machine, cpu.c_str());
	struct Case {
		const char *name;
		std::string json;
		double dt, seconds;
	} cases[] = {
		{"1 ball rolling", big_table_scenario("{\"id\": 0, \"pos\": [1, 1], \"vel\": [1, 0]}"), 1e-4,
		 4.0},
		{"16-ball break", rack_scenario(), 1e-4, 4.0},
		{"16-ball break", rack_scenario(), 1e-3, 4.0},
	};
	for (const Case &c : cases) {
		std::vector<double> per_step;
		for (int run = 0; run < 5; ++run) {
			void *e = create(c.json, c.dt);
			auto t0 = std::chrono::steady_clock::now();
			api->advance(e, c.seconds);
			auto t1 = std::chrono::steady_clock::now();
			pool_engine_stats s;
			api->stats(e, &s);
			per_step.push_back(std::chrono::duration<double>(t1 - t0).count() / double(s.steps));
			api->destroy(e);
		}
		std::printf("%-16s dt %-6g: %.2f us/step median, %.2f us/step min (5 runs of %g s)\n", c.name,
		            c.dt, median(per_step) * 1e6, *std::min_element(per_step.begin(), per_step.end()) * 1e6,
		            c.seconds);
	}
}

} // namespace

int main(int argc, char **argv) {
	if (argc < 2) {
		std::fprintf(stderr, "usage: ode_selftest PATH/libpool_engine_ode.so [--bench]\n");
		return 2;
	}
	api = pool_plugin::load_plugin(argv[1], "ode");
	if (!api)
		return 1;
	if (argc > 2 && std::strcmp(argv[2], "--bench") == 0) {
		bench();
		return 0;
	}
	test_pure_slide();
	test_spin_decay();
	test_head_on(1e-3);
	test_head_on(1e-4);
	test_angle(1e-3, 0.0);
	test_angle(1e-3, 0.5 * kR);
	test_angle(1e-4, -0.4 * kR);
	test_cushion(1e-3);
	test_cut(1e-3, 1.0);
	test_cut(1e-4, 0.1);
	test_cushion(1e-4);
	test_pockets();
	test_rejections();
	test_two_engines();
	std::printf("%s: %d failure(s)\n", failures ? "FAILED" : "PASSED", failures);
	return failures ? 1 : 0;
}
