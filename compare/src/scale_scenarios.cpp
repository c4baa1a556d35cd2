#include "scale_scenarios.h"

#include <jansson.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "pool/pool.h"

namespace pool_compare {

namespace {

constexpr double kRackGap = 1e-4;          ///< m between racked neighbours (pool-bench-shot's gap break)
constexpr double kCueToApex = 1.27;        ///< m, head spot to foot spot of the standard table
constexpr double kCueOffset = 5e-3;        ///< m, the cue ball's line beside the rack's axis
constexpr double kBreakSpeed = 6.0;        ///< m/s of the cue, as compare/scenarios/break.json
constexpr double kGasGap = 3e-3;           ///< m between gas balls: a 1 mm move never makes them touch
constexpr double kGasRailMargin = 0.01;    ///< m, gas balls start this far inside R of the rail lines
constexpr double kGasSpeedMin = 0.5, kGasSpeedMax = 2.0; ///< m/s, rolling balls of the gas

// splitmix64: a fixed generator, so the families are the same text on every platform (the
// standard library's distributions are not).
class Random {
public:
	explicit Random(uint64_t seed) : state_(seed) {}
	double uniform(double lo, double hi) {
		uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
		z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
		z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
		z ^= z >> 31;
		return lo + (hi - lo) * static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
	}

private:
	uint64_t state_;
};

json_t *pair(double x, double y) { return json_pack("[ff]", x, y); }
json_t *triple(double x, double y, double z) { return json_pack("[fff]", x, y, z); }

json_t *ball(int id, double x, double y) {
	json_t *b = json_object();
	json_object_set_new(b, "id", json_integer(id));
	json_object_set_new(b, "pos", pair(x, y));
	return b;
}

// Table of balls / 16 standard areas, the standard 2:1 shape, pocketless.
json_t *table(int balls, double *length, double *width) {
	const pool_table_def standard = pool_default_table_def();
	const double scale = std::sqrt(static_cast<double>(balls) / kScaleBallsPerTable);
	*length = standard.length * scale;
	*width = standard.width * scale;
	json_t *t = json_object();
	json_object_set_new(t, "length", json_real(*length));
	json_object_set_new(t, "width", json_real(*width));
	json_object_set_new(t, "cushion_height", json_real(standard.cushion_height));
	json_object_set_new(t, "corner_mouth", json_real(0.0));
	json_object_set_new(t, "side_mouth", json_real(0.0));
	return t;
}

void break_balls(int balls, double length, double width, double radius, json_t *list, json_t *root) {
	const double apex_x = 0.75 * length, apex_y = 0.5 * width, pitch = 2.0 * radius + kRackGap;
	// The standard table's head spot (on a table shorter than the standard one, its first quarter),
	// kCueOffset to the side: a break straight down the rack's axis of symmetry has exactly
	// simultaneous contacts (the apex ball meets the two balls behind it at one instant), where
	// pairwise events are ill-posed.
	json_array_append_new(list, ball(0, apex_x - std::min(kCueToApex, 0.5 * length), apex_y + kCueOffset));
	int id = 1;
	for (int row = 0; id < balls; ++row) {
		// A partial last row takes the middle sites of its full row (the lattice keeps every
		// neighbour 0.1 mm away; centring it off the sites would put balls into the row before).
		const int in_row = std::min(row + 1, balls - id), first = (row + 1 - in_row) / 2;
		const double x = apex_x + row * pitch * std::sqrt(3.0) / 2.0;
		for (int k = first; k < first + in_row; ++k)
			json_array_append_new(list, ball(id++, x, apex_y + (k - 0.5 * row) * pitch));
	}
	json_object_set_new(root, "strike",
	                    json_pack("{si sf sf sf sf sf}", "ball", 0, "speed", kBreakSpeed, "phi", 0.0, "theta", 0.0, "a",
	                              0.0, "b", 0.0));
}

void gas_balls(int balls, double length, double width, double radius, json_t *list) {
	Random random(0x9A5000ull + static_cast<uint64_t>(balls));
	const double margin = radius + kGasRailMargin, min_distance = 2.0 * radius + kGasGap;
	std::vector<double> xs, ys;
	while (static_cast<int>(xs.size()) < balls) {
		const double x = random.uniform(margin, length - margin), y = random.uniform(margin, width - margin);
		bool clear = true;
		for (size_t k = 0; k < xs.size() && clear; ++k)
			clear = std::hypot(x - xs[k], y - ys[k]) >= min_distance;
		if (!clear)
			continue;
		const int id = static_cast<int>(xs.size());
		xs.push_back(x);
		ys.push_back(y);
		json_t *b = ball(id, x, y);
		if (id < balls / 4) {
			// Rolling: no slip at the contact, v + R k x w = 0.
			const double speed = random.uniform(kGasSpeedMin, kGasSpeedMax), angle = random.uniform(0.0, 2.0 * M_PI);
			const double vx = speed * std::cos(angle), vy = speed * std::sin(angle);
			json_object_set_new(b, "vel", triple(vx, vy, 0.0));
			json_object_set_new(b, "omega", triple(-vy / radius, vx / radius, 0.0));
		}
		json_array_append_new(list, b);
	}
}

} // namespace

const std::vector<std::string> &scale_families() {
	static const std::vector<std::string> families = {"break", "gas"};
	return families;
}

std::string scale_scenario_name(const std::string &family, int balls) {
	return "scale_" + family + "_" + std::to_string(balls);
}

bool scale_scenario_json(const std::string &family, int balls, std::string *json, std::string *error) {
	if (family != "break" && family != "gas") {
		*error = "unknown scale family '" + family + "' (break, gas)";
		return false;
	}
	if (balls < 2 || balls > kScaleMaxBalls) {
		*error = "scale ball count " + std::to_string(balls) + " is outside [2, " + std::to_string(kScaleMaxBalls) + "]";
		return false;
	}
	const double radius = pool_default_params().ball_radius;
	json_t *root = json_object();
	json_object_set_new(root, "format", json_string("libpool-scenario/1"));
	json_object_set_new(root, "name", json_string(scale_scenario_name(family, balls).c_str()));
	double length = 0.0, width = 0.0;
	json_t *t = table(balls, &length, &width);
	const std::string what =
	    family == "break"
	        ? "a centre-ball break at 6 m/s, 5 mm beside the axis of a rack of " + std::to_string(balls - 1) +
	              " balls 0.1 mm apart"
	        : std::to_string(balls) + " balls, a quarter of them rolling at 0.5-2 m/s";
	json_object_set_new(root, "description",
	                    json_string(("pool-compare --scale: " + what + " on a pocketless table of " +
	                                 std::to_string(balls) + " / 16 standard areas; the first 2 s.")
	                                    .c_str()));
	json_object_set_new(root, "table", t);
	json_t *list = json_array();
	if (family == "break")
		break_balls(balls, length, width, radius, list, root);
	else
		gas_balls(balls, length, width, radius, list);
	json_object_set_new(root, "balls", list);
	json_object_set_new(root, "options", json_pack("{sf}", "max_time", kScaleWindow));
	char *text = json_dumps(root, JSON_INDENT(1) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17));
	json_decref(root);
	if (!text) {
		*error = "out of memory generating " + scale_scenario_name(family, balls);
		return false;
	}
	*json = text;
	free(text);
	return true;
}

} // namespace pool_compare
