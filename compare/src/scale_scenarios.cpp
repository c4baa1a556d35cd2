#include "scale_scenarios.h"

#include <jansson.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

extern "C" {
#include "scale_scene.h"
}

namespace pool_compare {

namespace {

json_t *triple(pool_vec3 v) { return json_pack("[fff]", v.x, v.y, v.z); }

} // namespace

const std::vector<std::string> &scale_families() {
	static const std::vector<std::string> families = {"break", "gas"};
	return families;
}

std::string scale_scenario_name(const std::string &family, int balls) {
	return "scale_" + family + "_" + std::to_string(balls);
}

bool scale_scenario_json(const std::string &family, int balls, std::string *json, std::string *error) {
	const pool_params params = pool_default_params();
	pool_table_def table;
	std::vector<pool_ball_state> states(static_cast<size_t>(std::max(balls, 0)));
	bool has_strike = false;
	pool_strike strike;
	char message[256];
	if (balls > kScaleMaxBalls || pool_scale_scene(family.c_str(), balls, &params, &table, states.data(), &has_strike,
	                                               &strike, message, sizeof message) != 0) {
		*error = balls > kScaleMaxBalls ? "scale ball count " + std::to_string(balls) + " is outside [2, " +
		                                      std::to_string(kScaleMaxBalls) + "]"
		                                : message;
		return false;
	}
	json_t *root = json_object();
	json_object_set_new(root, "format", json_string("libpool-scenario/1"));
	json_object_set_new(root, "name", json_string(scale_scenario_name(family, balls).c_str()));
	const std::string what =
	    family == "break"
	        ? "a centre-ball break at 6 m/s, 5 mm beside the axis of a rack of " + std::to_string(balls - 1) +
	              " balls 0.1 mm apart"
	        : std::to_string(balls) + " balls, a quarter of them rolling at 0.5-2 m/s";
	json_object_set_new(root, "description",
	                    json_string(("pool-compare --scale: " + what + " on a pocketless table of " +
	                                 std::to_string(balls) + " / 16 standard areas; the first 2 s.")
	                                    .c_str()));
	json_object_set_new(root, "table",
	                    json_pack("{sf sf sf sf sf}", "length", table.length, "width", table.width, "cushion_height",
	                              table.cushion_height, "corner_mouth", table.corner_mouth, "side_mouth",
	                              table.side_mouth));
	// The laws ODE and Bullet implement, as every scenario of the comparison (comparison.md
	// "Scenarios and models"): with the defaults the engines would run other laws than libpool.
	json_object_set_new(root, "models", json_string("thesis"));
	json_t *list = json_array();
	for (const pool_ball_state &s : states) {
		json_t *b = json_object();
		json_object_set_new(b, "id", json_integer(s.id));
		json_object_set_new(b, "pos", json_pack("[ff]", s.pos.x, s.pos.y));
		if (s.vel.x != 0.0 || s.vel.y != 0.0) {
			json_object_set_new(b, "vel", triple(s.vel));
			json_object_set_new(b, "omega", triple(s.omega));
		}
		json_array_append_new(list, b);
	}
	if (has_strike)
		json_object_set_new(root, "strike",
		                    json_pack("{si sf sf sf sf sf}", "ball", 0, "speed", strike.speed, "phi", strike.phi, "theta",
		                              strike.theta, "a", strike.a, "b", strike.b));
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
