// Per-step cost of the Bullet plugin: one ball (2 m/s slide) and a 16-ball break (8 m/s), each
// run several times at dt = 1e-3 and 1e-4; prints the median and minimum microseconds per step and
// the machine. Usage: pool-bench-bullet [PLUGIN.so] [REPEATS]
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "pool/pool.h"
#include "pool_engine_plugin.h"
#include "selftest_support.h"

namespace {

std::string cpu_model() {
	std::ifstream in("/proc/cpuinfo");
	std::string line;
	while (std::getline(in, line))
		if (line.rfind("model name", 0) == 0)
			return line.substr(line.find(':') + 2);
	return "unknown cpu";
}

// A WPA 9 ft 8-ball rack from libpool (frozen, gap 0) and the cue ball, struck at 8 m/s.
std::string break_json() {
	const pool_table_def table = pool_default_table_def();
	const pool_params params = pool_default_params();
	pool_ball_state balls[16];
	const int n = pool_rack(POOL_RACK_8BALL, &table, &params, 0.0, balls, 16);
	std::string json = "{\"format\":\"libpool-scenario/1\",\"balls\":[";
	char buf[160];
	for (int i = 0; i < n; ++i) {
		std::snprintf(buf, sizeof buf, "%s{\"id\":%d,\"pos\":[%.17g,%.17g]}", i ? "," : "", (int)balls[i].id,
		              balls[i].pos.x, balls[i].pos.y);
		json += buf;
	}
	return json + "],\"strike\":{\"ball\":0,\"speed\":8.0,\"phi\":0.0}}";
}

const char *slide_json = "{\"format\":\"libpool-scenario/1\",\"table\":{\"length\":14.0},"
                         "\"balls\":[{\"id\":0,\"pos\":[0.5,0.635],\"vel\":[2,0,0]}]}";

// Microseconds per step of advancing `seconds` of simulated time (creation not counted).
double run_once(const pool_engine_api *api, const std::string &json, double dt, double seconds) {
	pool_engine_config config{dt, 0};
	char err[512] = {0};
	void *engine = api->create(json.c_str(), &config, err, sizeof err);
	if (!engine) {
		std::fprintf(stderr, "create: %s\n", err);
		std::exit(1);
	}
	const auto t0 = std::chrono::steady_clock::now();
	api->advance(engine, seconds);
	const auto t1 = std::chrono::steady_clock::now();
	pool_engine_stats st{};
	api->stats(engine, &st);
	api->destroy(engine);
	return std::chrono::duration<double, std::micro>(t1 - t0).count() / double(st.steps);
}

} // namespace

int main(int argc, char **argv) {
	const char *path = argc > 1 && argv[1][0] ? argv[1] : POOL_BULLET_PLUGIN_PATH;
	const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 7;
	const pool_engine_api *api = pool_plugin::load_plugin(path, "bullet");
	if (!api)
		return 1;
	struct utsname u {};
	uname(&u);
	std::printf("machine: %s, %s %s %s\n", cpu_model().c_str(), u.sysname, u.release, u.machine);
	std::printf("plugin: %s\n", path);
	std::printf("%-28s %8s %10s %12s %12s\n", "case", "dt", "sim s", "median us", "min us");
	const std::string brk = break_json();
	struct Case {
		const char *name;
		std::string json;
		double dt, seconds;
	} cases[] = {
	    {"1 ball, 2 m/s slide", slide_json, 1e-3, 4.0},
	    {"1 ball, 2 m/s slide", slide_json, 1e-4, 1.0},
	    {"16 balls, 8 m/s break", brk, 1e-3, 4.0},
	    {"16 balls, 8 m/s break", brk, 1e-4, 1.0},
	};
	for (const Case &c : cases) {
		std::vector<double> t;
		for (int r = 0; r < repeats; ++r)
			t.push_back(run_once(api, c.json, c.dt, c.seconds));
		std::sort(t.begin(), t.end());
		std::printf("%-28s %8g %10g %12.3f %12.3f\n", c.name, c.dt, c.seconds, t[t.size() / 2], t[0]);
	}
	return 0;
}
