#include "metrics.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace pool_compare {

namespace {

const BallSample *find_ball(const std::vector<BallSample> &balls, int id) {
	for (const BallSample &b : balls)
		if (b.id == id)
			return &b;
	return nullptr;
}

double planar_distance(const Eigen::Vector3d &a, const Eigen::Vector3d &b) {
	return (a - b).head<2>().norm();
}

bool off_play(int state) { return state == 6 || state == 7; }

bool is_collision(int type) {
	return type == POOL_ENGINE_EVENT_BALL_BALL || type == POOL_ENGINE_EVENT_BALL_CUSHION;
}

// Events around which directions and energies are not compared: collisions and landings.
bool is_impact(int type) { return is_collision(type) || type == POOL_ENGINE_EVENT_BALL_TABLE; }

// What a collision is about, independent of its time: the ball pair, or the ball and the cushion
// (its rail, POOL_ENGINE_CUSHION) when `rails`, else the ball and "a cushion".
using CollisionKey = std::tuple<int, int, int>;
CollisionKey key_of(const Event &e, bool rails) {
	if (e.type == POOL_ENGINE_EVENT_BALL_BALL)
		return {e.type, std::min(e.ball_a, e.ball_b), std::max(e.ball_a, e.ball_b)};
	return {e.type, e.ball_a, rails ? e.ball_b : -1};
}

// Whether every cushion contact of both lists names its rail (plugins may report only "a cushion").
bool rails_known(const std::vector<Event> &a, const std::vector<Event> &b) {
	for (const std::vector<Event> *list : {&a, &b})
		for (const Event &e : *list)
			if (e.type == POOL_ENGINE_EVENT_BALL_CUSHION && e.ball_b > -2)
				return false;
	return true;
}

double max_or_none(double a, double b) {
	if (std::isnan(a))
		return b;
	if (std::isnan(b))
		return a;
	return std::max(a, b);
}

// Smallest |t - e.t| over engine events accepted by `same`; NaN if none.
template <typename Pred>
double nearest(const std::vector<Event> &engine, double t, Pred same) {
	double best = kNone;
	for (const Event &e : engine)
		if (same(e))
			best = std::isnan(best) ? std::fabs(e.t - t) : std::min(best, std::fabs(e.t - t));
	return best;
}

} // namespace

std::vector<TimeWindow> collision_windows(const std::vector<Event> &reference, const std::vector<Event> &engine,
                                          double dt) {
	const double guard = std::max(3.0 * (std::isnan(dt) ? 0.0 : dt), 1e-3);
	const bool rails = rails_known(reference, engine);
	std::vector<TimeWindow> windows;
	// Each reference collision with the engine's nearest one of the same key: between the two,
	// one side has had the collision and the other not yet.
	for (const Event &r : reference) {
		if (!is_impact(r.type))
			continue;
		const CollisionKey k = key_of(r, rails);
		double lo = r.t, hi = r.t;
		const Event *match = nullptr;
		// A counterpart further away than kMaxCollisionLag is another collision (the engine
		// missed this one): skipping everything in between would hide where outcomes diverge.
		for (const Event &e : engine)
			if (is_impact(e.type) && key_of(e, rails) == k && std::fabs(e.t - r.t) <= kMaxCollisionLag &&
			    (!match || std::fabs(e.t - r.t) < std::fabs(match->t - r.t)))
				match = &e;
		if (match) {
			lo = std::min(lo, match->t);
			hi = std::max(hi, match->t);
		}
		windows.push_back({lo - guard, hi + guard});
	}
	// Every engine collision (phantoms included).
	for (const Event &e : engine)
		if (is_impact(e.type))
			windows.push_back({e.t - guard, e.t + guard});
	return windows;
}

StateErrors::StateErrors(const pool_params &params, const std::vector<TimeWindow> &skip)
    : params_(params), skip_(skip) {}

void StateErrors::add(double t, const std::vector<BallSample> &engine, const std::vector<BallSample> &reference) {
	for (const BallSample &r : reference) {
		const BallSample *e = find_ball(engine, r.id);
		if (!e) {
			++missing_balls;
			position_error = std::numeric_limits<double>::infinity();
			continue;
		}
		position_error = std::max(position_error, planar_distance(e->pos, r.pos));
	}
	// Directions and energies mean little near a collision, when one side may have resolved it
	// and the other not yet (a cushion hit at 8 m/s takes 2 J, a late one turns the velocity by
	// up to 180 degrees): that is timing, measured by the event times. The instants 30 ms after
	// each collision measure them on the way out.
	bool near_collision = false;
	for (const TimeWindow &w : skip_)
		near_collision = near_collision || (t > w.from && t < w.to);
	if (!near_collision) {
		energy_error =
		    std::max(energy_error, std::fabs(kinetic_energy(engine, params_) - kinetic_energy(reference, params_)));
		for (const BallSample &r : reference) {
			const BallSample *e = find_ball(engine, r.id);
			if (!e || off_play(r.state) || off_play(e->state))
				continue;
			const Eigen::Vector2d a = r.vel.head<2>(), b = e->vel.head<2>();
			if (a.norm() < 0.05 || b.norm() < 0.05)
				continue;
			const double cross = a.x() * b.y() - a.y() * b.x();
			const double angle = std::atan2(std::fabs(cross), a.dot(b)) * 180.0 / M_PI;
			direction_error = max_or_none(direction_error, angle);
		}
	}

	const double diameter = 2.0 * params_.ball_radius;
	for (size_t i = 0; i < engine.size(); ++i)
		for (size_t j = i + 1; j < engine.size(); ++j) {
			if (off_play(engine[i].state) || off_play(engine[j].state))
				continue;
			penetration = std::max(penetration, diameter - (engine[i].pos - engine[j].pos).norm());
		}
}

double max_position_error(const std::vector<BallSample> &engine, const std::vector<BallSample> &reference) {
	double worst = 0.0;
	for (const BallSample &r : reference) {
		const BallSample *e = find_ball(engine, r.id);
		worst = std::max(worst, e ? planar_distance(e->pos, r.pos) : std::numeric_limits<double>::infinity());
	}
	return worst;
}

void compare_landings(const std::vector<Event> &engine, const Reference &ref, Record *rec) {
	std::map<int, std::vector<double>> ref_times, eng_times;
	for (const Event &e : ref.events)
		if (e.type == POOL_ENGINE_EVENT_BALL_TABLE)
			ref_times[e.ball_a].push_back(e.t);
	for (const Event &e : engine)
		if (e.type == POOL_ENGINE_EVENT_BALL_TABLE && (ref.at_rest || e.t <= ref.end_time + 1e-9))
			eng_times[e.ball_a].push_back(e.t);
	rec->landings_reference = rec->landings_engine = 0;
	rec->landing_time_error = kNone;
	for (const auto &[ball, list] : ref_times)
		rec->landings_reference += static_cast<int>(list.size());
	for (const auto &[ball, list] : eng_times)
		rec->landings_engine += static_cast<int>(list.size());
	for (const auto &[ball, list] : ref_times) {
		auto it = eng_times.find(ball);
		if (it == eng_times.end())
			continue;
		for (size_t k = 0; k < list.size() && k < it->second.size(); ++k)
			rec->landing_time_error = max_or_none(rec->landing_time_error, std::fabs(it->second[k] - list[k]));
	}
}

int pocket_mismatches(const std::vector<BallSample> &engine, const std::vector<BallSample> &reference) {
	int count = 0;
	for (const BallSample &r : reference) {
		const BallSample *e = find_ball(engine, r.id);
		if (e && off_play(e->state) != off_play(r.state))
			++count;
	}
	return count;
}

void compare_events(const std::vector<Event> &engine_all, const Reference &ref, Record *rec) {
	// A shot cut at max_time: an engine stepping past it may report events the reference never
	// reached. A shot run to rest keeps all (an engine may stop later than the reference).
	const std::vector<Event> &reference = ref.events;
	std::vector<Event> engine;
	for (const Event &e : engine_all)
		if (ref.at_rest || e.t <= ref.end_time + 1e-9)
			engine.push_back(e);

	const bool rails = rails_known(reference, engine);
	rec->cushions_by_rail = rails;
	std::set<CollisionKey> ref_keys, eng_keys;
	rec->collisions_reference = rec->collisions_engine = 0;
	for (const Event &e : reference)
		if (is_collision(e.type)) {
			ref_keys.insert(key_of(e, rails));
			++rec->collisions_reference;
		}
	for (const Event &e : engine)
		if (is_collision(e.type)) {
			eng_keys.insert(key_of(e, rails));
			++rec->collisions_engine;
		}
	rec->missed_collisions = rec->phantom_collisions = 0;
	for (const CollisionKey &k : ref_keys)
		rec->missed_collisions += eng_keys.count(k) == 0;
	for (const CollisionKey &k : eng_keys)
		rec->phantom_collisions += ref_keys.count(k) == 0;

	// Contacts libpool resolves one after the other although they happen at the same instant (a
	// ball hitting two touching balls, a frozen rack): its order is one admissible outcome.
	rec->simultaneous_contacts = 0;
	for (size_t i = 0; i < reference.size(); ++i) {
		const Event &a = reference[i];
		if (a.type != POOL_ENGINE_EVENT_BALL_BALL)
			continue;
		for (size_t j = 0; j < reference.size(); ++j) {
			const Event &b = reference[j];
			if (j != i && b.type == POOL_ENGINE_EVENT_BALL_BALL && std::fabs(a.t - b.t) <= 1e-9 &&
			    (a.ball_a == b.ball_a || a.ball_a == b.ball_b || a.ball_b == b.ball_a || a.ball_b == b.ball_b)) {
				++rec->simultaneous_contacts;
				break;
			}
		}
	}

	rec->unmatched_events = 0;
	rec->first_contact_time_error = rec->slide_roll_time_error = rec->stop_time_error = kNone;
	rec->collision_time_error = kNone;

	auto first_collision = [](const std::vector<Event> &list) -> const Event * {
		for (const Event &e : list)
			if (is_collision(e.type))
				return &e;
		return nullptr;
	};
	const Event *ref_first = first_collision(reference), *eng_first = first_collision(engine);
	if (ref_first && eng_first)
		rec->first_contact_time_error = std::fabs(eng_first->t - ref_first->t);

	std::map<int, double> ref_last_stop, eng_last_stop;
	for (const Event &r : reference) {
		if (r.type == POOL_ENGINE_EVENT_SLIDE_ROLL) {
			const double d = nearest(engine, r.t, [&](const Event &e) {
				return e.type == POOL_ENGINE_EVENT_SLIDE_ROLL && e.ball_a == r.ball_a;
			});
			if (std::isnan(d))
				++rec->unmatched_events;
			rec->slide_roll_time_error = max_or_none(rec->slide_roll_time_error, d);
		} else if (r.type == POOL_ENGINE_EVENT_ROLL_STOP) {
			ref_last_stop[r.ball_a] = r.t;
		} else if (is_collision(r.type)) {
			const CollisionKey k = key_of(r, rails);
			const double d =
			    nearest(engine, r.t, [&](const Event &e) { return is_collision(e.type) && key_of(e, rails) == k; });
			rec->collision_time_error = max_or_none(rec->collision_time_error, d);
		}
	}
	for (const Event &e : engine)
		if (e.type == POOL_ENGINE_EVENT_ROLL_STOP)
			eng_last_stop[e.ball_a] = e.t;
	for (const auto &[ball, t] : ref_last_stop) {
		auto it = eng_last_stop.find(ball);
		if (it == eng_last_stop.end()) {
			++rec->unmatched_events;
			continue;
		}
		rec->stop_time_error = max_or_none(rec->stop_time_error, std::fabs(it->second - t));
	}
	rec->event_time_error =
	    max_or_none(max_or_none(rec->first_contact_time_error, rec->slide_roll_time_error), rec->stop_time_error);
}

} // namespace pool_compare
