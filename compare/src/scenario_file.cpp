#include "scenario_file.h"

#include <jansson.h>

#include "read_input.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace pool_compare {

int Scenario::index_of(int id) const {
	for (int i = 0; i < parsed.ball_count; ++i)
		if (parsed.balls[i].id == id)
			return i;
	return -1;
}

int Scenario::lead_ball_id() const {
	if (parsed.has_strike)
		return parsed.strike_ball;
	int best = parsed.ball_count > 0 ? parsed.balls[0].id : 0;
	double best_speed = -1.0;
	for (int i = 0; i < parsed.ball_count; ++i) {
		const pool_vec3 &v = parsed.balls[i].vel;
		double speed = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
		if (speed > best_speed) {
			best_speed = speed;
			best = parsed.balls[i].id;
		}
	}
	return best;
}

bool parse_scenario(const std::string &name, const std::string &json, std::unique_ptr<Scenario> *out,
                    std::string *error) {
	auto scenario = std::make_unique<Scenario>();
	char message[512] = {0};
	if (pool_scenario_parse(json.data(), json.size(), &scenario->parsed, message, sizeof message) != 0) {
		*error = name + ": " + message;
		return false;
	}
	scenario->name = name;
	scenario->json = json;
	*out = std::move(scenario);
	return true;
}

bool load_scenario(const std::string &path, std::unique_ptr<Scenario> *out, std::string *error) {
	// The commands' input limit (read_input.h): a scenario is kilobytes; /dev/zero or a runaway
	// file is refused with a message instead of filling the memory.
	char *data = nullptr;
	size_t length = 0;
	char message[512] = {0};
	if (pool_read_input(path.c_str(), POOL_INPUT_DEFAULT_MAX, &data, &length, message, sizeof message) != 0) {
		*error = message;
		return false;
	}
	std::ostringstream text;
	text.write(data, (std::streamsize)length);
	free(data);
	std::string stem = path.substr(path.find_last_of('/') + 1);
	if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".json") == 0)
		stem.resize(stem.size() - 5);
	if (!parse_scenario(stem, text.str(), out, error)) {
		*error = path + error->substr(stem.size());
		return false;
	}
	(*out)->path = path;
	return true;
}

namespace {

// The document with each ball moved by move(index in the list, id) = (dx, dy), or "" when it is
// not a scenario's JSON or no ball moved.
template <typename Move>
std::string moved_json(const std::string &json, Move move) {
	json_error_t jerr;
	json_t *root = json_loadb(json.data(), json.size(), 0, &jerr);
	if (!root)
		return "";
	bool moved = false;
	size_t i;
	json_t *ball;
	json_array_foreach(json_object_get(root, "balls"), i, ball) {
		json_t *ball_id = json_object_get(ball, "id");
		json_t *pos = json_object_get(ball, "pos");
		double dx = 0.0, dy = 0.0;
		if (!json_is_integer(ball_id) || json_array_size(pos) < 2 ||
		    !move(i, static_cast<int>(json_integer_value(ball_id)), &dx, &dy))
			continue;
		json_array_set_new(pos, 0, json_real(json_number_value(json_array_get(pos, 0)) + dx));
		json_array_set_new(pos, 1, json_real(json_number_value(json_array_get(pos, 1)) + dy));
		moved = true;
	}
	std::string result;
	char *text = moved ? json_dumps(root, JSON_COMPACT | JSON_REAL_PRECISION(17)) : nullptr;
	if (text) {
		result = text;
		free(text);
	}
	json_decref(root);
	return result;
}

} // namespace

std::string perturbed_json(const std::string &json, int id, double dx, double dy) {
	return moved_json(json, [&](size_t, int ball, double *x, double *y) {
		*x = dx;
		*y = dy;
		return ball == id;
	});
}

std::string perturbed_all_json(const std::string &json, double distance, double turn) {
	// Golden-ratio steps spread the directions evenly whatever the number of balls.
	const double golden = 0.6180339887498949;
	return moved_json(json, [&](size_t index, int, double *x, double *y) {
		const double angle = 2.0 * M_PI * std::fmod(turn + golden * static_cast<double>(index), 1.0);
		*x = distance * std::cos(angle);
		*y = distance * std::sin(angle);
		return true;
	});
}

} // namespace pool_compare
