#include "horizon.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

namespace pool_compare {

namespace {

bool off_play(int state) { return state == POOL_MOTION_POCKETED || state == POOL_MOTION_OFF_TABLE; }

// Balls by id, for matching two states of a thousand balls without a quadratic search.
std::vector<std::pair<int, const BallSample *>> by_id(const std::vector<BallSample> &balls) {
	std::vector<std::pair<int, const BallSample *>> index;
	index.reserve(balls.size());
	for (const BallSample &b : balls)
		index.push_back({b.id, &b});
	std::sort(index.begin(), index.end(),
	          [](const std::pair<int, const BallSample *> &x, const std::pair<int, const BallSample *> &y) {
		          return x.first < y.first;
	          });
	return index;
}

double median(std::vector<double> v) {
	std::sort(v.begin(), v.end());
	const size_t n = v.size();
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

} // namespace

bool horizon_applies(const Scenario &scenario, const Reference &reference) {
	return scenario.parsed.ball_count >= 3 && reference.has_truth() && reference.kind() == "libpool";
}

std::vector<double> horizon_times(double end_time) {
	std::vector<double> times;
	if (!(end_time > 0.0))
		return times;
	const double spacing = std::max(kHorizonSpacing, end_time / kHorizonMaxSamples);
	const int count = static_cast<int>(std::ceil(end_time / spacing - 1e-9));
	for (int k = 1; k < count; ++k)
		times.push_back(k * spacing);
	times.push_back(end_time);
	return times;
}

double off_play_distance(const Scenario &scenario) {
	const pool_table_def &t = scenario.parsed.def.table;
	return std::hypot(t.length, t.width);
}

double trajectory_distance(const std::vector<BallSample> &a, const std::vector<BallSample> &b,
                           double off_play_distance) {
	const auto index = by_id(b);
	double worst = 0.0;
	for (const BallSample &x : a) {
		auto it = std::lower_bound(index.begin(), index.end(), x.id,
		                           [](const std::pair<int, const BallSample *> &e, int id) { return e.first < id; });
		if (it == index.end() || it->first != x.id)
			return std::numeric_limits<double>::infinity();
		const BallSample &y = *it->second;
		if (off_play(x.state) || off_play(y.state)) {
			if (off_play(x.state) != off_play(y.state))
				worst = std::max(worst, off_play_distance);
			continue;
		}
		worst = std::max(worst, (x.pos - y.pos).head<2>().norm());
	}
	return b.size() > a.size() ? std::numeric_limits<double>::infinity() : worst;
}

Horizon departure(const ErrorTrack &track, double threshold) {
	Horizon h;
	for (size_t k = 0; k < track.t.size(); ++k)
		if (track.error[k] > threshold) {
			h.seconds = track.t[k];
			return h;
		}
	h.censored = true;
	h.seconds = track.t.empty() ? kNone : track.t.back();
	return h;
}

bool self_horizons(const Scenario &scenario, const Reference &reference, std::vector<SelfHorizon> *out,
                   std::string *error) {
	out->clear();
	const std::vector<double> times = horizon_times(reference.end_time);
	std::vector<std::vector<BallSample>> base;
	for (double t : times)
		base.push_back(reference.state_at(t));
	const int lead = scenario.parsed.has_strike ? scenario.parsed.strike_ball : -1;
	const double far = off_play_distance(scenario);
	for (double size : kSelfPerturbations) {
		SelfHorizon self;
		self.perturbation = size;
		std::vector<std::vector<double>> runs; // [run][instant]
		for (int k = 0; k < kSelfDirections; ++k) {
			const double turn = static_cast<double>(k) / kSelfDirections, angle = 2.0 * M_PI * turn;
			const std::string json = scenario.parsed.has_strike
			                             ? perturbed_json(scenario.json, lead, size * std::cos(angle), size * std::sin(angle))
			                             : perturbed_all_json(scenario.json, size, turn);
			std::unique_ptr<Scenario> moved;
			std::string why;
			// A direction that puts a ball into another is no scenario: left out.
			if (json.empty() || !parse_scenario(scenario.name, json, &moved, &why))
				continue;
			std::unique_ptr<Reference> other = make_libpool_reference(*moved, &why);
			if (!other)
				continue;
			std::vector<double> errors;
			for (size_t i = 0; i < times.size(); ++i)
				errors.push_back(trajectory_distance(other->state_at(times[i]), base[i], far));
			runs.push_back(std::move(errors));
		}
		if (runs.empty()) {
			*error = scenario.name + ": libpool with its start moved by " + std::to_string(size) +
			         " m ran in no direction";
			return false;
		}
		self.runs = static_cast<int>(runs.size());
		self.track.t = times;
		for (size_t i = 0; i < times.size(); ++i) {
			std::vector<double> at;
			for (const std::vector<double> &run : runs)
				at.push_back(run[i]);
			self.track.error.push_back(median(at));
		}
		self.horizon = departure(self.track, kHorizonThreshold);
		out->push_back(std::move(self));
	}
	return true;
}

} // namespace pool_compare
