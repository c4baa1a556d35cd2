// libpool's own result as the reference where no closed form exists.
#include "reference.h"

#include <algorithm>
#include <cmath>

namespace pool_compare {

namespace {

BallSample to_sample(const pool_ball_state &s) {
	BallSample b;
	b.id = s.id;
	b.state = static_cast<int>(s.motion);
	b.pos = Eigen::Vector3d(s.pos.x, s.pos.y, s.pos.z);
	b.vel = Eigen::Vector3d(s.vel.x, s.vel.y, s.vel.z);
	b.omega = Eigen::Vector3d(s.omega.x, s.omega.y, s.omega.z);
	return b;
}

class LibpoolReference final : public Reference {
public:
	~LibpoolReference() override { pool_sim_destroy(sim_); }

	bool run(const Scenario &scenario, std::string *error) {
		// A time-stepped engine stops at a step boundary, up to one step past a shot's max_time,
		// and its state there is compared with the reference at that same instant: so the
		// reference runs kBeyondMaxTime longer, and only its events up to max_time count.
		const double max_time = scenario.parsed.def.max_time;
		pool_scenario extended = scenario.parsed; // shallow: setup only reads the balls
		extended.def.max_time = max_time + kBeyondMaxTime;
		pool_error e = {{0}};
		pool_result r = pool_scenario_setup(&extended, &sim_, &e);
		if (r == POOL_OK)
			r = pool_sim_run(sim_);
		if (r != POOL_OK) {
			*error = scenario.name + ": libpool reference failed: " +
			         (e.message[0] ? e.message : pool_result_str(r));
			return false;
		}
		const pool_stop_reason why = pool_sim_stop_reason(sim_);
		at_rest = why == POOL_STOP_REST && pool_sim_time(sim_) <= max_time;
		end_time = at_rest ? pool_sim_time(sim_) : max_time;
		known_until_ = why == POOL_STOP_REST ? HUGE_VAL : pool_sim_end_time(sim_);
		int count = 0;
		const pool_event *list = pool_sim_events(sim_, &count);
		for (int i = 0; i < count && list[i].time <= max_time; ++i) {
			exact_ = exact_ && list[i].type != POOL_EVENT_LINK_BEGIN;
			const int type = abi_event_type(list[i].type);
			if (type < 0)
				continue;
			const pool_ball_state *after = pool_sim_event_states(sim_, &list[i]);
			Event ev;
			ev.t = list[i].time;
			ev.type = type;
			ev.ball_a = list[i].ball_count > 0 ? after[0].id : -1;
			ev.ball_b = list[i].ball_count > 1 && type == POOL_ENGINE_EVENT_BALL_BALL ? after[1].id
			            : type == POOL_ENGINE_EVENT_BALL_CUSHION && list[i].rail != POOL_RAIL_NONE
			                ? POOL_ENGINE_CUSHION(list[i].rail)
			                : -1;
			events.push_back(ev);
			if (type == POOL_ENGINE_EVENT_BALL_TABLE && list[i].ball_count > 0) {
				const pool_ball_state &b = after[0];
				landings.push_back({ev.t, b.id, Eigen::Vector3d(b.pos.x, b.pos.y, b.pos.z)});
				const double g = scenario.parsed.def.params.g;
				if (b.motion == POOL_MOTION_AIRBORNE && b.vel.z > 0.0 && ev.t + b.vel.z / g <= max_time)
					apexes.push_back({ev.t + b.vel.z / g, b.id, b.pos.z + b.vel.z * b.vel.z / (2.0 * g)});
			}
		}
		std::stable_sort(apexes.begin(), apexes.end(), [](const Apex &a, const Apex &b) { return a.t < b.t; });
		return true;
	}

	std::string kind() const override { return "libpool"; }
	bool exact() const override { return exact_; }

	std::vector<BallSample> state_at(double t) const override {
		const int n = pool_sim_ball_count(sim_);
		std::vector<pool_ball_state> states(static_cast<size_t>(n));
		std::vector<BallSample> out;
		if (pool_sim_state_at(sim_, std::min(std::max(t, 0.0), known_until_), states.data()) != POOL_OK)
			return out;
		for (const pool_ball_state &s : states)
			out.push_back(to_sample(s));
		return out;
	}

private:
	static constexpr double kBeyondMaxTime = 1.0; ///< s, far more than any engine's step
	pool_sim *sim_ = nullptr;
	double known_until_ = 0.0; ///< s, states are exact up to here (infinite once at rest)
	bool exact_ = true;        ///< no cluster formed before max_time (LINK steps are first order)
};

} // namespace

int abi_event_type(int libpool_type) {
	switch (libpool_type) {
	case POOL_EVENT_SLIDE_ROLL: return POOL_ENGINE_EVENT_SLIDE_ROLL;
	case POOL_EVENT_ROLL_STOP: return POOL_ENGINE_EVENT_ROLL_STOP;
	case POOL_EVENT_BALL_BALL: return POOL_ENGINE_EVENT_BALL_BALL;
	case POOL_EVENT_BALL_CUSHION: return POOL_ENGINE_EVENT_BALL_CUSHION;
	case POOL_EVENT_POCKET: return POOL_ENGINE_EVENT_POCKET;
	case POOL_EVENT_BALL_TABLE: return POOL_ENGINE_EVENT_BALL_TABLE;
	default: return -1;
	}
}

std::unique_ptr<Reference> make_libpool_reference(const Scenario &scenario, std::string *error) {
	auto ref = std::make_unique<LibpoolReference>();
	if (!ref->run(scenario, error))
		return nullptr;
	return ref;
}

} // namespace pool_compare
