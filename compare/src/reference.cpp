// libpool's own result as the reference where no closed form exists.
#include "reference.h"

#include <algorithm>

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
		pool_error e = {{0}};
		pool_result r = pool_scenario_setup(&scenario.parsed, &sim_, &e);
		if (r == POOL_OK)
			r = pool_sim_run(sim_);
		if (r != POOL_OK) {
			*error = scenario.name + ": libpool reference failed: " +
			         (e.message[0] ? e.message : pool_result_str(r));
			return false;
		}
		const pool_stop_reason why = pool_sim_stop_reason(sim_);
		at_rest = why == POOL_STOP_REST;
		end_time = why == POOL_STOP_MAX_TIME ? scenario.parsed.def.max_time : pool_sim_time(sim_);
		int count = 0;
		const pool_event *list = pool_sim_events(sim_, &count);
		for (int i = 0; i < count; ++i) {
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
		}
		return true;
	}

	std::string kind() const override { return "libpool"; }

	std::vector<BallSample> state_at(double t) const override {
		const int n = pool_sim_ball_count(sim_);
		std::vector<pool_ball_state> states(static_cast<size_t>(n));
		std::vector<BallSample> out;
		if (pool_sim_state_at(sim_, std::min(std::max(t, 0.0), end_time), states.data()) != POOL_OK)
			return out;
		for (const pool_ball_state &s : states)
			out.push_back(to_sample(s));
		return out;
	}

private:
	pool_sim *sim_ = nullptr;
};

} // namespace

int abi_event_type(int libpool_type) {
	switch (libpool_type) {
	case POOL_EVENT_SLIDE_ROLL: return POOL_ENGINE_EVENT_SLIDE_ROLL;
	case POOL_EVENT_ROLL_STOP: return POOL_ENGINE_EVENT_ROLL_STOP;
	case POOL_EVENT_BALL_BALL: return POOL_ENGINE_EVENT_BALL_BALL;
	case POOL_EVENT_BALL_CUSHION: return POOL_ENGINE_EVENT_BALL_CUSHION;
	case POOL_EVENT_POCKET: return POOL_ENGINE_EVENT_POCKET;
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
