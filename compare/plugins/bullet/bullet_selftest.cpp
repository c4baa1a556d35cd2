// Self-test of the Bullet plugin through its C ABI, loaded from the built module (argv[1]):
// the closed-form pure slide with errors shrinking with dt, a frictionless elastic head-on hit
// (speed transfer, momentum, no energy gain), a 30-degree shot that stays straight (the
// box-friction trap), cushion and pocket events, determinism, and rejection of bad input.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "pool_engine_plugin.h"
#include "selftest_support.h"

namespace {

using pool_plugin::fmt;

const pool_engine_api *api = nullptr;
int failures = 0;

#define CHECK(cond, ...)                                                                  \
	do {                                                                                  \
		if (!(cond)) {                                                                    \
			std::printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                   \
			std::printf(__VA_ARGS__);                                                     \
			std::printf("\n");                                                            \
			++failures;                                                                   \
		}                                                                                 \
	} while (0)

const double kR = 0.028575, kM = 0.17, kG = 9.81;
const double kPi = 3.14159265358979323846;

/// One engine instance, destroyed with the scope.
struct Run {
	void *engine = nullptr;
	std::string error;
	Run(const std::string &json, double dt) {
		pool_engine_config config{dt, 0};
		char err[512] = {0};
		engine = api->create(json.c_str(), &config, err, sizeof err);
		error = err;
	}
	~Run() { api->destroy(engine); }
	std::vector<pool_engine_ball> balls() const {
		std::vector<pool_engine_ball> out(size_t(api->balls(engine, nullptr, 0)));
		api->balls(engine, out.data(), int(out.size()));
		return out;
	}
	std::vector<pool_engine_event> events() const {
		std::vector<pool_engine_event> out(size_t(api->events(engine, nullptr, 0)));
		api->events(engine, out.data(), int(out.size()));
		return out;
	}
	int count(int type) const {
		int n = 0;
		for (const auto &e : events())
			n += e.type == type;
		return n;
	}
};

double speed(const pool_engine_ball &b) { return std::hypot(b.vel[0], b.vel[1]); }

double kinetic(const std::vector<pool_engine_ball> &balls) {
	double e = 0.0;
	for (const auto &b : balls)
		e += 0.5 * kM * (b.vel[0] * b.vel[0] + b.vel[1] * b.vel[1] + b.vel[2] * b.vel[2]) +
		     0.5 * 0.4 * kM * kR * kR *
		         (b.omega[0] * b.omega[0] + b.omega[1] * b.omega[1] + b.omega[2] * b.omega[2]);
	return e;
}

// --- Pure slide: 2 m/s, no spin (docs/physics.md closed form) -------------------------------------

struct SlideErrors {
	double t_roll, v_roll, t_stop, distance;
};

SlideErrors slide(double dt) {
	const double mu_s = 0.2, mu_r = 0.01, v0 = 2.0;
	const double t_roll = 2.0 * v0 / (7.0 * mu_s * kG);
	const double v_roll = 5.0 / 7.0 * v0;
	const double t_stop = t_roll + v_roll / (mu_r * kG);
	const double dist = v0 * t_roll - 0.5 * mu_s * kG * t_roll * t_roll + v_roll * v_roll / (2.0 * mu_r * kG);
	const std::string json = fmt(
	    "{\"format\":\"libpool-scenario/1\",\"table\":{\"length\":14.0},"
	    "\"params\":{\"g\":9.81,\"mu_slide\":0.2,\"mu_roll\":0.01},"
	    "\"balls\":[{\"id\":0,\"pos\":[0.5,0.635],\"vel\":[%.17g,0,0]}]}",
	    v0);
	Run run(json, dt);
	SlideErrors e{1e9, 1e9, 1e9, 1e9};
	CHECK(run.engine, "create failed: %s", run.error.c_str());
	if (!run.engine)
		return e;
	// Step until the slide_roll event, to read the speed at that instant.
	double v_at_roll = -1.0, t_event = -1.0;
	for (int k = 1; k < int(1.0 / dt) && t_event < 0.0; ++k) {
		CHECK(api->advance(run.engine, k * dt) == 0, "advance failed");
		for (const auto &ev : run.events())
			if (ev.type == POOL_ENGINE_EVENT_SLIDE_ROLL) {
				t_event = ev.t;
				v_at_roll = speed(run.balls()[0]);
			}
	}
	CHECK(t_event > 0.0, "no slide_roll event at dt %g", dt);
	CHECK(api->run_to_rest(run.engine, 30.0) == 0, "run_to_rest failed");
	double t_stopped = -1.0;
	for (const auto &ev : run.events())
		if (ev.type == POOL_ENGINE_EVENT_ROLL_STOP)
			t_stopped = ev.t;
	CHECK(t_stopped > 0.0, "no roll_stop event at dt %g", dt);
	const auto balls = run.balls();
	CHECK(balls.size() == 1 && balls[0].state == 0, "ball not stationary (state %d)", balls[0].state);
	CHECK(run.count(POOL_ENGINE_EVENT_SLIDE_ROLL) == 1 && run.count(POOL_ENGINE_EVENT_ROLL_STOP) == 1,
	      "expected one slide_roll and one roll_stop, got %d / %d",
	      run.count(POOL_ENGINE_EVENT_SLIDE_ROLL), run.count(POOL_ENGINE_EVENT_ROLL_STOP));
	CHECK(std::fabs(balls[0].pos[1] - 0.635) < 1e-9, "ball left its line: y = %.9f", balls[0].pos[1]);
	e.t_roll = std::fabs(t_event - t_roll);
	e.v_roll = std::fabs(v_at_roll - v_roll);
	e.t_stop = std::fabs(t_stopped - t_stop);
	e.distance = std::fabs((balls[0].pos[0] - 0.5) - dist);
	std::printf("slide dt %-6g: t_roll %.6f (err %.2e s)  v_roll %.6f (err %.2e)  t_stop %.5f "
	            "(err %.2e s)  distance %.6f (err %.2e m)\n",
	            dt, t_event, e.t_roll, v_at_roll, e.v_roll, t_stopped, e.t_stop,
	            balls[0].pos[0] - 0.5, e.distance);
	return e;
}

void test_slide() {
	const double dts[3] = {1e-2, 1e-3, 1e-4};
	SlideErrors e[3];
	for (int i = 0; i < 3; ++i)
		e[i] = slide(dts[i]);
	// Each error shrinks with dt, or is already at rounding level (the rolling speed is exact at
	// any dt: the cloth's impulse conserves angular momentum about the contact point).
	for (int i = 1; i < 3; ++i) {
		CHECK(e[i].t_roll < e[i - 1].t_roll || e[i].t_roll < 1e-12, "t_roll error did not shrink");
		CHECK(e[i].v_roll < e[i - 1].v_roll || e[i].v_roll < 1e-9, "v_roll error did not shrink");
		CHECK(e[i].t_stop < e[i - 1].t_stop || e[i].t_stop < 1e-12, "t_stop error did not shrink");
		CHECK(e[i].distance < e[i - 1].distance || e[i].distance < 1e-9, "distance error did not shrink");
	}
	// First-order bounds: an event is seen at the end of the step it falls in, and the
	// semi-implicit Euler path lags by about a dt / 2 over each phase.
	for (int i = 0; i < 3; ++i) {
		CHECK(e[i].t_roll <= 1.0001 * dts[i], "t_roll error %.3g > dt %g", e[i].t_roll, dts[i]);
		CHECK(e[i].v_roll <= 1e-9, "v_roll error %.3g", e[i].v_roll);
		CHECK(e[i].t_stop <= 2.0 * dts[i], "t_stop error %.3g > 2 dt (dt %g)", e[i].t_stop, dts[i]);
		CHECK(e[i].distance <= 1.5 * dts[i], "distance error %.3g m > 1.5 dt m/s (dt %g)", e[i].distance, dts[i]);
	}
}

// --- Head-on, frictionless, elastic ----------------------------------------------------------

void headon(double v, double dt) {
	const double x0 = 0.5, gap = 0.05;
	const std::string json = fmt(
	    "{\"format\":\"libpool-scenario/1\",\"params\":{\"mu_ball\":0,\"e_ball\":1},"
	    "\"balls\":[{\"id\":0,\"pos\":[%.17g,0.635],\"vel\":[%.17g,0,0]},"
	    "{\"id\":1,\"pos\":[%.17g,0.635]}]}",
	    x0, v, x0 + 2.0 * kR + gap);
	Run run(json, dt);
	CHECK(run.engine, "create failed: %s", run.error.c_str());
	if (!run.engine)
		return;
	std::vector<pool_engine_ball> before = run.balls(), after;
	for (int k = 1; k < 100000; ++k) {
		CHECK(api->advance(run.engine, k * dt) == 0, "advance failed");
		after = run.balls();
		if (speed(after[1]) > 0.0)
			break;
		before = after;
	}
	const double v_cue = before[0].vel[0], v_obj = after[1].vel[0];
	const double p_before = kM * (before[0].vel[0] + before[1].vel[0]);
	const double p_after = kM * (after[0].vel[0] + after[1].vel[0]);
	// In the impact step the cloth's friction (mu_slide m g each) still acts on both balls.
	const double friction = 2.0 * kM * 0.2 * kG * dt;
	const double e_before = kinetic(before), e_after = kinetic(after);
	std::printf("head-on %4.1f m/s dt %g: cue %.6f -> object %.6f m/s (ratio %.6f), cue after %.6f, "
	            "momentum change %.2e (friction bound %.2e), energy %.6f -> %.6f J\n",
	            v, dt, v_cue, v_obj, v_obj / v_cue, after[0].vel[0], p_after - p_before, friction,
	            e_before, e_after);
	CHECK(v_obj >= 0.99 * v_cue, "object ball got %.6f of %.6f m/s", v_obj, v_cue);
	CHECK(v_obj <= v_cue * (1.0 + 1e-9), "object ball faster than the cue ball: %.9f > %.9f", v_obj, v_cue);
	CHECK(std::fabs(after[0].vel[0]) <= 0.01 * v_cue, "cue ball kept %.6f m/s", after[0].vel[0]);
	CHECK(std::fabs(p_after - p_before) <= friction + 1e-12, "momentum changed by %.3g", p_after - p_before);
	CHECK(e_after <= e_before * (1.0 + 1e-12), "energy grew: %.9f -> %.9f J", e_before, e_after);
	CHECK(run.count(POOL_ENGINE_EVENT_BALL_BALL) == 1, "expected 1 ball_ball event, got %d",
	      run.count(POOL_ENGINE_EVENT_BALL_BALL));
	pool_engine_stats st{};
	api->stats(run.engine, &st);
	CHECK(st.max_penetration <= v * dt + 1e-12, "penetration %.3g m > v dt", st.max_penetration);
}

// --- 30-degree shot stays straight -----------------------------------------------------------

void test_straight() {
	// A cue strike at phi = 30 deg with follow (b > 0): no side spin, so the path is a line.
	const std::string json =
	    "{\"format\":\"libpool-scenario/1\",\"table\":{\"length\":14.0,\"width\":8.0},"
	    "\"params\":{\"g\":9.81,\"mu_slide\":0.2,\"mu_roll\":0.01},"
	    "\"balls\":[{\"id\":0,\"pos\":[0.5,0.5]}],"
	    "\"strike\":{\"ball\":0,\"speed\":0.8,\"phi\":30.0,\"theta\":0.0,\"a\":0.0,\"b\":0.01}}";
	Run run(json, 1e-3);
	CHECK(run.engine, "create failed: %s", run.error.c_str());
	if (!run.engine)
		return;
	CHECK(api->run_to_rest(run.engine, 60.0) == 0, "run_to_rest failed");
	const auto b = run.balls();
	const double dx = b[0].pos[0] - 0.5, dy = b[0].pos[1] - 0.5;
	const double angle = std::atan2(dy, dx) * 180.0 / kPi;
	std::printf("30-degree shot: travelled %.4f m at %.6f deg (error %.2e deg), state %d\n",
	            std::hypot(dx, dy), angle, angle - 30.0, b[0].state);
	CHECK(std::hypot(dx, dy) > 3.0, "ball travelled only %.3f m", std::hypot(dx, dy));
	CHECK(std::fabs(angle - 30.0) < 0.1, "direction %.4f deg", angle);
	CHECK(b[0].state == 0, "not at rest");
	CHECK(run.count(POOL_ENGINE_EVENT_BALL_CUSHION) == 0, "hit a cushion");
}

// --- Cushion and pocket ----------------------------------------------------------------------

void test_cushion_and_pocket() {
	// Straight into the south cushion at x = 1.0, and straight into the south side pocket.
	const std::string json =
	    "{\"format\":\"libpool-scenario/1\","
	    "\"balls\":[{\"id\":3,\"pos\":[1.0,0.3],\"vel\":[0,-1.5,0]},"
	    "{\"id\":7,\"pos\":[1.27,0.3],\"vel\":[0,-1.5,0]}]}";
	Run run(json, 1e-3);
	CHECK(run.engine, "create failed: %s", run.error.c_str());
	if (!run.engine)
		return;
	double vy_in = 0.0, vy_out = 0.0;
	for (int k = 1; k <= 1000; ++k) {
		const double vy = run.balls()[0].vel[1];
		CHECK(api->advance(run.engine, k * 1e-3) == 0, "advance failed");
		const double now = run.balls()[0].vel[1];
		if (vy < 0.0 && now > 0.0) {
			vy_in = vy;
			vy_out = now;
			break;
		}
	}
	std::printf("cushion: v_y %.4f -> %.4f m/s\n", vy_in, vy_out);
	CHECK(vy_in < 0.0 && vy_out > 0.0, "no rebound");
	CHECK(api->run_to_rest(run.engine, 60.0) == 0, "run_to_rest failed");
	const auto b = run.balls();
	CHECK(b[0].state == 0 && b[0].pos[1] > 0.0, "ball 3 state %d y %.4f", b[0].state, b[0].pos[1]);
	CHECK(b[1].state == 6, "ball 7 not pocketed (state %d)", b[1].state);
	bool cushion = false, pocket = false;
	for (const auto &e : run.events()) {
		cushion |= e.type == POOL_ENGINE_EVENT_BALL_CUSHION && e.ball_a == 3;
		pocket |= e.type == POOL_ENGINE_EVENT_POCKET && e.ball_a == 7;
		CHECK(!(e.type == POOL_ENGINE_EVENT_BALL_CUSHION && e.ball_a == 7), "ball 7 hit a cushion in the mouth");
	}
	CHECK(cushion, "no ball_cushion event");
	CHECK(pocket, "no pocket event");
	// Contact found with the ball's centre at the touch distance sqrt(R^2 - (h - R)^2) = 26.9 mm
	// from the nose line, not at R: the capsule reproduces libpool's nose.
	pool_engine_stats st{};
	api->stats(run.engine, &st);
	CHECK(st.max_penetration < 1.5e-3, "penetration %.3g m", st.max_penetration);
}

// --- Cushion impulse against Petit's law (docs/physics.md) -----------------------------------------

// A ball rolling (with side spin) into the south cushion: the rebound one step after the
// contact must be Petit's impulse with libpool's nose normal, v_z dropped (planar mode).
void cushion_petit(double spin_z) {
	const double dt = 1e-4, h = 0.03629, e = 0.85, mu = 0.2, V = 1.5;
	const double dh = std::sqrt(kR * kR - (h - kR) * (h - kR));
	const std::string json = fmt(
	    "{\"format\":\"libpool-scenario/1\",\"balls\":[{\"id\":0,\"pos\":[1.0,%.17g],"
	    "\"vel\":[0,%.17g,0],\"omega\":[%.17g,0,%.17g]}]}",
	    dh + 0.003, -V, V / kR, spin_z);
	Run run(json, dt);
	CHECK(run.engine, "create failed: %s", run.error.c_str());
	if (!run.engine)
		return;
	pool_engine_ball before{}, after{};
	for (int k = 1; k <= 1000; ++k) {
		before = run.balls()[0];
		CHECK(api->advance(run.engine, k * dt) == 0, "advance failed");
		after = run.balls()[0];
		if (after.vel[1] > 0.0)
			break;
	}
	double v2[3] = {before.vel[0], before.vel[1], 0.0};
	double w2[3] = {before.omega[0], before.omega[1], before.omega[2]};
	const double n[3] = {0.0, dh / kR, (kR - h) / kR}; // from the nose point to the centre
	pool_plugin::petit_impact(n, e, mu, kR, v2, w2);
	const double dv = std::hypot(after.vel[0] - v2[0], after.vel[1] - v2[1]);
	const double w2_norm = std::sqrt(w2[0] * w2[0] + w2[1] * w2[1] + w2[2] * w2[2]);
	const double dw = std::sqrt((after.omega[0] - w2[0]) * (after.omega[0] - w2[0]) +
	                            (after.omega[1] - w2[1]) * (after.omega[1] - w2[1]) +
	                            (after.omega[2] - w2[2]) * (after.omega[2] - w2[2]));
	std::printf("cushion (w_z %5.1f): v after (%.4f, %.4f), Petit (%.4f, %.4f): |dv| %.2e m/s; "
	            "|dw| %.2e rad/s of %.1f\n",
	            spin_z, after.vel[0], after.vel[1], v2[0], v2[1], dv, dw, w2_norm);
	// One step of cloth friction and rolling resistance, and the normal of a contact found
	// after up to V dt of penetration, separate the two.
	CHECK(dv < 0.01 * V, "rebound differs from Petit's by %.3g m/s", dv);
	CHECK(dw < 0.02 * w2_norm, "spin differs from Petit's by %.3g rad/s", dw);
}

// --- A break: robustness and determinism ------------------------------------------------------

std::string break_json() {
	std::string balls = "{\"id\":0,\"pos\":[0.635,0.635]}";
	const double d = 2.0 * kR + 1e-7;
	int id = 1;
	for (int row = 0; row < 5; ++row)
		for (int k = 0; k <= row; ++k)
			balls += fmt(",{\"id\":%d,\"pos\":[%.17g,%.17g]}", id++, 1.905 + row * d * std::sqrt(3.0) / 2.0,
			             0.635 + (k - 0.5 * row) * d);
	return "{\"format\":\"libpool-scenario/1\",\"balls\":[" + balls +
	       "],\"strike\":{\"ball\":0,\"speed\":8.0,\"phi\":0.0}}";
}

void test_break() {
	const std::string json = break_json();
	std::vector<pool_engine_ball> first;
	for (int pass = 0; pass < 2; ++pass) {
		Run run(json, 1e-3);
		CHECK(run.engine, "create failed: %s", run.error.c_str());
		if (!run.engine)
			return;
		CHECK(api->advance(run.engine, 4.0) == 0, "advance failed: %s", api->last_error(run.engine));
		const auto b = run.balls();
		CHECK(b.size() == 16, "%zu balls", b.size());
		int on_table = 0;
		for (const auto &x : b) {
			on_table += x.state != 6 && x.state != 7;
			CHECK(x.state != 7, "ball %d left the table", x.id);
			CHECK(std::isfinite(x.pos[0]) && std::isfinite(x.pos[1]), "non-finite ball %d", x.id);
		}
		pool_engine_stats st{};
		api->stats(run.engine, &st);
		if (pass == 0) {
			std::printf("break 8 m/s, 4 s at dt 1e-3: %d events, %d balls on the table, max "
			            "penetration %.3g m, %lld steps\n",
			            int(run.events().size()), on_table, st.max_penetration, (long long)st.steps);
			first = b;
		} else {
			bool same = true;
			for (size_t i = 0; i < b.size(); ++i)
				same = same && std::memcmp(b[i].pos, first[i].pos, sizeof b[i].pos) == 0;
			CHECK(same, "two identical runs differ");
		}
		CHECK(st.steps == 4000, "steps %lld", (long long)st.steps);
		CHECK(run.count(POOL_ENGINE_EVENT_BALL_BALL) >= 15, "only %d ball_ball events",
		      run.count(POOL_ENGINE_EVENT_BALL_BALL));
	}
}

// --- Bad input -------------------------------------------------------------------------------

void expect_rejected(const char *json, double dt, const char *needle) {
	pool_engine_config config{dt, 0};
	char err[512] = {0};
	void *e = api->create(json, &config, err, sizeof err);
	CHECK(!e, "accepted: %s", json ? json : "(null)");
	api->destroy(e);
	CHECK(err[0] != 0, "no message for %s", json ? json : "(null)");
	CHECK(!needle || std::strstr(err, needle), "message \"%s\" lacks \"%s\"", err, needle);
}

void test_bad_input() {
	const char *ok = "{\"format\":\"libpool-scenario/1\",\"balls\":[{\"id\":0,\"pos\":[0.5,0.5]}]}";
	expect_rejected("{", 1e-3, nullptr);
	expect_rejected(nullptr, 1e-3, nullptr);
	expect_rejected("{\"format\":\"libpool-scenario/1\",\"balls\":[{\"id\":0,\"pos\":[0.5,0.5]},"
	                "{\"id\":1,\"pos\":[0.51,0.5]}]}",
	                1e-3, "overlaps");
	expect_rejected("{\"format\":\"libpool-scenario/1\",\"bogus\":1,\"balls\":[]}", 1e-3, "bogus");
	expect_rejected("{\"format\":\"libpool-scenario/1\",\"params\":{\"mu_slide\":-1},\"balls\":[]}", 1e-3,
	                "mu_slide");
	expect_rejected(ok, 0.0, "dt");
	expect_rejected(ok, NAN, "dt");
	// The engine itself survives nonsense calls.
	Run run(ok, 1e-3);
	CHECK(run.engine, "create failed: %s", run.error.c_str());
	CHECK(api->advance(run.engine, NAN) != 0, "advance(NaN) accepted");
	CHECK(api->advance(run.engine, 1e300) != 0, "advance(1e300) accepted");
	CHECK(api->advance(run.engine, -1.0) == 0, "advance into the past failed");
	CHECK(api->run_to_rest(run.engine, 1.0) == 0, "run_to_rest failed");
	CHECK(api->balls(run.engine, nullptr, 0) == 1, "ball count");
	api->destroy(nullptr);
	CHECK(api->advance(nullptr, 1.0) != 0, "advance(NULL) accepted");
}

} // namespace

int main(int argc, char **argv) {
	if (argc < 2) {
		std::fprintf(stderr, "usage: bullet_selftest PATH/libpool_engine_bullet.so\n");
		return 2;
	}
	api = pool_plugin::load_plugin(argv[1], "bullet");
	if (!api)
		return 1;
	test_bad_input();
	test_slide();
	headon(2.0, 1e-3);
	headon(10.0, 1e-3);
	headon(2.0, 1e-4);
	headon(10.0, 1e-4);
	test_straight();
	test_cushion_and_pocket();
	cushion_petit(0.0);
	cushion_petit(40.0);
	test_break();
	std::printf("%s (%d failures)\n", failures ? "FAILED" : "OK", failures);
	// The module stays loaded (Bullet keeps static state): no dlclose.
	return failures ? 1 : 0;
}
