#include "runner.h"

#include "horizon.h"

#include <time.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace pool_compare {

namespace {

// One engine instance; every call into the engine that simulates is timed.
class EngineRun {
public:
	explicit EngineRun(const Plugin &plugin) : api_(plugin.api), link_stats_(plugin.link_stats) {}
	~EngineRun() {
		if (engine_)
			api_->destroy(engine_);
	}
	EngineRun(const EngineRun &) = delete;
	EngineRun &operator=(const EngineRun &) = delete;

	bool create(const std::string &json, double dt, std::string *error) {
		pool_engine_config config = {dt, 0};
		char message[512] = {0};
		const double t0 = cpu_now();
		engine_ = api_->create(json.c_str(), &config, message, sizeof message);
		setup_cpu = cpu_now() - t0;
		if (!engine_)
			*error = std::string("create failed: ") + (message[0] ? message : "no message");
		return engine_ != nullptr;
	}

	bool advance(double t, std::string *error) {
		const double t0 = cpu_now();
		const int r = api_->advance(engine_, t);
		cpu += cpu_now() - t0;
		return check(r, "advance", error);
	}

	bool run_to_rest(double max_time, std::string *error) {
		const double t0 = cpu_now();
		const int r = api_->run_to_rest(engine_, max_time);
		cpu += cpu_now() - t0;
		return check(r, "run_to_rest", error);
	}

	// Runs the rest of the shot the way the reference ended: to rest, or to its max_time.
	bool finish(const Reference &ref, double max_time, std::string *error) {
		return ref.at_rest ? run_to_rest(max_time, error) : advance(ref.end_time, error);
	}

	// The balls of the scenario, checked: a count the plugin did not write (more than the scenario
	// has, more than it filled in, negative), a ball the scenario lacks or reported twice, or a
	// non-finite position, velocity or spin is an error, not a state to score.
	bool balls(const Scenario &scenario, std::vector<BallSample> *out, std::string *error) const {
		out->clear();
		const int expected = scenario.parsed.ball_count;
		std::vector<pool_engine_ball> raw(static_cast<size_t>(std::max(64, expected)), unwritten_ball());
		const int n = api_->balls(engine_, raw.data(), static_cast<int>(raw.size()));
		if (n < 0)
			return fail(error, "balls() returned " + std::to_string(n));
		if (n > expected)
			return fail(error, "balls() reported " + std::to_string(n) + " balls, the scenario has " +
			                       std::to_string(expected));
		std::vector<int> seen;
		for (int i = 0; i < n; ++i) {
			const pool_engine_ball &b = raw[static_cast<size_t>(i)];
			if (b.id == kUnwritten && b.state == kUnwritten)
				return fail(error, "balls() returned " + std::to_string(n) + " but wrote only " + std::to_string(i) +
				                       " balls");
			if (scenario.index_of(b.id) < 0)
				return fail(error, "balls() reported ball id " + std::to_string(b.id) + ", not in the scenario");
			if (std::find(seen.begin(), seen.end(), b.id) != seen.end())
				return fail(error, "balls() reported ball id " + std::to_string(b.id) + " twice");
			seen.push_back(b.id);
			for (int k = 0; k < 3; ++k)
				if (!std::isfinite(b.pos[k]) || !std::isfinite(b.vel[k]) || !std::isfinite(b.omega[k]))
					return fail(error, "non-finite state of ball " + std::to_string(b.id) + " (pos " +
					                       triple(b.pos) + ", vel " + triple(b.vel) + ", omega " + triple(b.omega) + ")");
			BallSample s;
			s.id = b.id;
			s.state = b.state;
			s.pos = Eigen::Vector3d(b.pos);
			s.vel = Eigen::Vector3d(b.vel);
			s.omega = Eigen::Vector3d(b.omega);
			out->push_back(s);
		}
		return true;
	}

	// Events, checked like the balls: a count it did not write or a non-finite time is an error.
	bool events(std::vector<Event> *out, std::string *error) const {
		out->clear();
		std::vector<pool_engine_event> raw(256, unwritten_event());
		int n = api_->events(engine_, raw.data(), static_cast<int>(raw.size()));
		if (n > static_cast<int>(raw.size()) && n <= kMaxEvents) {
			raw.assign(static_cast<size_t>(n), unwritten_event());
			const int again = api_->events(engine_, raw.data(), n);
			if (again != n)
				return fail(error, "events() reported " + std::to_string(n) + " events, then " + std::to_string(again));
		}
		if (n < 0)
			return fail(error, "events() returned " + std::to_string(n));
		if (n > static_cast<int>(raw.size()))
			return fail(error, "events() reported " + std::to_string(n) + " events (more than " +
			                       std::to_string(kMaxEvents) + ")");
		for (int i = 0; i < n; ++i) {
			const pool_engine_event &e = raw[static_cast<size_t>(i)];
			if (e.type == kUnwritten)
				return fail(error, "events() returned " + std::to_string(n) + " but wrote only " + std::to_string(i) +
				                       " events");
			if (!std::isfinite(e.t))
				return fail(error, "events(): event " + std::to_string(i) + " has a non-finite time");
			out->push_back({e.t, e.type, e.ball_a, e.ball_b});
		}
		std::stable_sort(out->begin(), out->end(), [](const Event &a, const Event &b) { return a.t < b.t; });
		return true;
	}

	pool_engine_stats stats() const {
		pool_engine_stats s = {0, 0.0, 0.0};
		api_->stats(engine_, &s);
		return s;
	}

	// The persistent-contact counters, when the plugin has the optional export and answers.
	bool link(pool_engine_link_info *out) const {
		*out = pool_engine_link_info{};
		return link_stats_ && link_stats_(engine_, out) == 0;
	}

	// Records the share of this run's step time spent in link steps (a run with no step time, or
	// a plugin that does not say, adds nothing).
	void add_link_share(std::vector<double> *shares) const {
		pool_engine_link_info l;
		if (link(&l) && l.step_seconds > 0.0 && std::isfinite(l.link_seconds))
			shares->push_back(std::min(1.0, std::max(0.0, l.link_seconds / l.step_seconds)));
	}

	double cpu = 0.0;
	double setup_cpu = 0.0;

private:
	// What the harness puts in the buffers before a call, to see which entries the plugin wrote.
	static constexpr int32_t kUnwritten = INT32_MIN;
	static constexpr int kMaxEvents = 1 << 22;
	static pool_engine_ball unwritten_ball() {
		pool_engine_ball b{};
		b.id = b.state = kUnwritten;
		return b;
	}
	static pool_engine_event unwritten_event() {
		pool_engine_event e{};
		e.t = kNone;
		e.type = kUnwritten;
		return e;
	}
	static bool fail(std::string *error, const std::string &message) {
		*error = message;
		return false;
	}
	static std::string triple(const double v[3]) {
		char buf[96];
		std::snprintf(buf, sizeof buf, "%g %g %g", v[0], v[1], v[2]);
		return buf;
	}

	bool check(int r, const char *what, std::string *error) {
		if (r >= 0)
			return true;
		const char *message = api_->last_error(engine_);
		*error = std::string(what) + " failed: " + (message && message[0] ? message : "no message");
		return false;
	}

	const pool_engine_api *api_;
	pool_engine_link_fn link_stats_; ///< optional export, may be null
	void *engine_ = nullptr;
};

bool is_collision(int type) {
	return type == POOL_ENGINE_EVENT_BALL_BALL || type == POOL_ENGINE_EVENT_BALL_CUSHION;
}

// The time the engine reached (its sim_time), or `asked` if the plugin reports nothing usable.
double engine_time(const pool_engine_stats &stats, double asked) {
	return std::isfinite(stats.sim_time) && stats.sim_time >= 0.0 ? stats.sim_time : asked;
}

double median(std::vector<double> v) {
	std::sort(v.begin(), v.end());
	const size_t n = v.size();
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A run whose plugin handed back something that is not a state: an error row, at the time reached.
Record invalid(Record *rec, double t) {
	char at[64];
	std::snprintf(at, sizeof at, " at t = %.6g s", t);
	rec->error += at;
	return *rec;
}

// The LINK counts of the measured run, when the plugin reports them.
void link_counts(const EngineRun &run, Record *rec) {
	pool_engine_link_info l;
	if (!run.link(&l))
		return;
	rec->link_steps = l.link_steps;
	rec->link_events = l.link_events;
	rec->link_clusters = l.clusters;
}

} // namespace

bool unsupported_models(const Scenario &scenario, const Plugin &plugin, std::vector<std::string> *out) {
	out->clear();
	if (!plugin.unsupported_models)
		return false;
	char text[512] = {0};
	const int n = plugin.unsupported_models(scenario.json.c_str(), text, sizeof text);
	text[sizeof text - 1] = '\0';
	if (n < 0) // the harness parsed the scenario already: a plugin that cannot is not saying
		return false;
	std::string list = text;
	for (size_t start = 0; start < list.size();) {
		size_t comma = list.find(',', start);
		if (comma == std::string::npos)
			comma = list.size();
		if (comma > start)
			out->push_back(list.substr(start, comma - start));
		start = comma + 1;
	}
	return true;
}

Record blank_record(const Scenario &scenario, const Reference &ref, const Plugin &plugin, const RunSettings &settings) {
	const pool_engine_api *api = plugin.api;
	Record rec;
	rec.scenario = scenario.name;
	rec.engine = api->name ? api->name : "";
	rec.description = api->description ? api->description : "";
	rec.reference = ref.kind();
	rec.reference_error = ref.why_none();
	rec.event_driven = api->event_driven != 0;
	rec.dt = rec.event_driven ? kNone : settings.dt;
	rec.models_known = unsupported_models(scenario, plugin, &rec.unsupported_models);
	rec.reference_exact = ref.has_truth() ? ref.exact() : -1;
	rec.balls = scenario.parsed.ball_count;
	rec.family = scenario.family;
	return rec;
}

double cpu_now() {
	timespec ts;
	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::vector<double> sample_times(const Reference &ref, int max_samples) {
	std::vector<double> times;
	for (const Event &e : ref.events) {
		if (e.t > 0.0 && e.t < ref.end_time)
			times.push_back(e.t);
		if (is_collision(e.type) && e.t + 0.03 < ref.end_time)
			times.push_back(e.t + 0.03);
	}
	for (const Apex &a : ref.apexes)
		if (a.t > 0.0 && a.t < ref.end_time)
			times.push_back(a.t);
	std::sort(times.begin(), times.end());
	times.erase(std::unique(times.begin(), times.end()), times.end());
	if (max_samples > 1 && static_cast<int>(times.size()) > max_samples - 1) {
		std::vector<double> kept;
		const double stride = static_cast<double>(times.size()) / (max_samples - 1);
		for (int i = 0; i < max_samples - 1; ++i)
			kept.push_back(times[static_cast<size_t>(i * stride)]);
		times.swap(kept);
	}
	times.insert(times.begin(), 0.0);
	return times;
}

Record run_engine(const Scenario &scenario, const Reference &ref, const Plugin &plugin, const RunSettings &settings) {
	const pool_params &params = scenario.parsed.def.params;
	const double max_time = scenario.parsed.def.max_time;
	Record rec = blank_record(scenario, ref, plugin, settings);

	// The measured run: states compared at the sample instants, then the end of the shot. An
	// engine stops at a step boundary (the first at or after the instant asked for), so each state
	// is compared with the reference at the time the engine actually reached.
	std::vector<double> cpu_times;
	std::vector<double> link_shares; // of each timed run whose plugin reports LINK timing
	std::vector<BallSample> final_balls;
	if (!ref.has_truth()) {
		// No ground truth: run the shot to max_time and keep what the engine says about itself
		// (cost, steps, its events and penetration); nothing is scored.
		EngineRun run(plugin);
		if (!run.create(scenario.json, settings.dt, &rec.error) || !run.finish(ref, max_time, &rec.error))
			return rec;
		if (!run.balls(scenario, &final_balls, &rec.error))
			return invalid(&rec, engine_time(run.stats(), ref.end_time));
		std::vector<Event> engine_events;
		const pool_engine_stats stats = run.stats();
		if (!run.events(&engine_events, &rec.error))
			return invalid(&rec, engine_time(stats, ref.end_time));
		rec.setup_cpu_seconds = run.setup_cpu;
		cpu_times.push_back(run.cpu);
		run.add_link_share(&link_shares);
		link_counts(run, &rec);
		rec.sim_seconds = stats.sim_time;
		rec.steps = stats.steps;
		rec.final_balls = final_balls;
		rec.max_penetration = std::max(0.0, stats.max_penetration);
		for (const Event &e : engine_events) {
			rec.collisions_engine += is_collision(e.type);
			rec.landings_engine += e.type == POOL_ENGINE_EVENT_BALL_TABLE;
		}
	} else {
		EngineRun run(plugin);
		if (!run.create(scenario.json, settings.dt, &rec.error))
			return rec;
		struct Sample {
			double t;
			std::vector<BallSample> engine, reference;
			double asked; ///< the sample instant asked for (t is the step the engine reached)
		};
		std::vector<Sample> samples;
		// The metrics' instants and the horizon's, in one pass: 1 for a metric sample, 2 for a
		// horizon instant, 3 for both.
		std::vector<std::pair<double, int>> instants;
		for (double t : sample_times(ref, settings.max_samples))
			instants.push_back({t, 1});
		for (double t : settings.horizon_times)
			instants.push_back({t, 2});
		std::sort(instants.begin(), instants.end());
		for (size_t k = 0; k + 1 < instants.size();)
			if (instants[k].first == instants[k + 1].first) {
				instants[k].second |= instants[k + 1].second;
				instants.erase(instants.begin() + static_cast<std::ptrdiff_t>(k) + 1);
			} else {
				++k;
			}
		const double far = off_play_distance(scenario);
		for (const auto &[t, use] : instants) {
			if (t > 0.0 && !run.advance(t, &rec.error))
				return rec;
			const double reached = t > 0.0 ? engine_time(run.stats(), t) : 0.0;
			std::vector<BallSample> balls;
			if (!run.balls(scenario, &balls, &rec.error))
				return invalid(&rec, reached);
			std::vector<BallSample> truth = ref.state_at(reached);
			if (use & 2) {
				rec.track.t.push_back(reached);
				rec.track.error.push_back(trajectory_distance(balls, truth, far));
			}
			if (use & 1)
				samples.push_back({reached, std::move(balls), std::move(truth), t});
		}
		if (!rec.track.t.empty()) {
			const Horizon h = departure(rec.track, kHorizonThreshold);
			rec.horizon_seconds = h.seconds;
			rec.horizon_censored = h.censored;
		}
		// Airborne: positions at the reference's landing instants (xy) and heights at its apex
		// instants, engine and reference compared at the step the engine reached.
		auto ball_in = [](const std::vector<BallSample> &list, int id) -> const BallSample * {
			for (const BallSample &b : list)
				if (b.id == id)
					return &b;
			return nullptr;
		};
		for (const Sample &sample : samples) {
			for (const Landing &l : ref.landings) {
				if (l.t != sample.asked)
					continue;
				const BallSample *e = ball_in(sample.engine, l.ball), *r = ball_in(sample.reference, l.ball);
				if (e && r)
					rec.landing_position_error = std::isnan(rec.landing_position_error)
					                                 ? (e->pos - r->pos).head<2>().norm()
					                                 : std::max(rec.landing_position_error,
					                                            (e->pos - r->pos).head<2>().norm());
			}
			for (const Apex &a : ref.apexes) {
				if (a.t != sample.asked)
					continue;
				const BallSample *e = ball_in(sample.engine, a.ball), *r = ball_in(sample.reference, a.ball);
				if (e && r)
					rec.bounce_height_error = std::isnan(rec.bounce_height_error)
					                              ? std::fabs(e->pos.z() - r->pos.z())
					                              : std::max(rec.bounce_height_error, std::fabs(e->pos.z() - r->pos.z()));
			}
		}
		if (!run.finish(ref, max_time, &rec.error))
			return rec;
		if (!run.balls(scenario, &final_balls, &rec.error))
			return invalid(&rec, engine_time(run.stats(), ref.end_time));
		const pool_engine_stats stats = run.stats();
		// A shot cut at max_time: the reference where the engine stopped (within a step past
		// it; the reference knows its states beyond max_time). A shot run to rest: both at rest,
		// whenever each got there.
		const double t_end = ref.at_rest ? ref.end_time : engine_time(stats, ref.end_time);
		const std::vector<BallSample> ref_final = ref.state_at(t_end);
		samples.push_back({ref.at_rest ? std::max(ref.end_time, engine_time(stats, ref.end_time)) : t_end,
		                   final_balls, ref_final, t_end});
		std::vector<Event> engine_events;
		if (!run.events(&engine_events, &rec.error))
			return invalid(&rec, engine_time(stats, ref.end_time));

		StateErrors errors(params, collision_windows(ref.events, engine_events, rec.dt));
		for (const Sample &sample : samples)
			errors.add(sample.t, sample.engine, sample.reference);

		rec.setup_cpu_seconds = run.setup_cpu;
		cpu_times.push_back(run.cpu);
		run.add_link_share(&link_shares);
		link_counts(run, &rec);
		rec.sim_seconds = stats.sim_time;
		rec.steps = stats.steps;
		rec.final_position_error = max_position_error(final_balls, ref_final);
		rec.final_balls = final_balls;
		rec.event_position_error = errors.position_error;
		rec.direction_error_deg = errors.direction_error;
		rec.energy_error = errors.energy_error;
		rec.max_penetration = std::max({0.0, stats.max_penetration, errors.penetration});
		rec.pocket_mismatches = pocket_mismatches(final_balls, ref_final);
		compare_events(engine_events, ref, &rec);
		compare_landings(engine_events, ref, &rec);
		if (errors.missing_balls)
			rec.error = "the engine did not report every ball";
	}

	// Short runs are repeated so the CPU time is not just clock resolution.
	const double timing_start = cpu_now();
	while ((cpu_times[0] + cpu_now() - timing_start < settings.min_timing_cpu ||
	        static_cast<int>(cpu_times.size()) < settings.min_repetitions) &&
	       static_cast<int>(cpu_times.size()) < std::max(settings.max_repetitions, settings.min_repetitions)) {
		EngineRun run(plugin);
		if (!run.create(scenario.json, settings.dt, &rec.error) || !run.finish(ref, max_time, &rec.error))
			return rec;
		cpu_times.push_back(run.cpu);
		run.add_link_share(&link_shares);
	}
	rec.repetitions = static_cast<int>(cpu_times.size());
	rec.cpu_seconds = median(cpu_times);
	rec.cpu_seconds_min = *std::min_element(cpu_times.begin(), cpu_times.end());
	if (!link_shares.empty())
		rec.link_cpu_share = median(link_shares);

	// Predictability: how far the outcome moves when the lead ball starts 1 um elsewhere. A
	// direction that puts it into a ball it touches (a ball resting on two others) is no
	// scenario at all: the engine refuses it, and that direction is left out.
	if (settings.spread_runs > 0) {
		const int id = scenario.lead_ball_id();
		const int n = settings.spread_runs;
		Eigen::MatrixXd change(n, static_cast<Eigen::Index>(final_balls.size()));
		int valid = 0;
		std::string refused;
		for (int k = 0; k < n; ++k) {
			const double angle = 2.0 * M_PI * k / n;
			const std::string json = perturbed_json(scenario.json, id, settings.perturbation * std::cos(angle),
			                                        settings.perturbation * std::sin(angle));
			EngineRun run(plugin);
			std::string error;
			if (json.empty()) {
				rec.error = "perturbed run " + std::to_string(k) + ": bad scenario";
				return rec;
			}
			if (!run.create(json, settings.dt, &error)) {
				refused = "perturbed run " + std::to_string(k) + ": " + error;
				continue;
			}
			if (!run.finish(ref, max_time, &error)) {
				rec.error = "perturbed run " + std::to_string(k) + ": " + error;
				return rec;
			}
			std::vector<BallSample> balls;
			if (!run.balls(scenario, &balls, &error)) {
				rec.error = "perturbed run " + std::to_string(k) + ": " + error;
				return rec;
			}
			for (size_t b = 0; b < final_balls.size(); ++b) {
				double d = std::numeric_limits<double>::infinity();
				for (const BallSample &s : balls)
					if (s.id == final_balls[b].id)
						d = (s.pos - final_balls[b].pos).head<2>().norm();
				change(valid, static_cast<Eigen::Index>(b)) = d;
			}
			++valid;
		}
		if (valid == 0) {
			rec.error = refused;
			return rec;
		}
		const Eigen::MatrixXd used = change.topRows(valid);
		rec.spread_runs = valid;
		rec.spread_perturbation = settings.perturbation;
		rec.spread_rms = std::sqrt(used.squaredNorm() / static_cast<double>(used.size()));
		rec.spread_max = used.maxCoeff();
	}
	return rec;
}

} // namespace pool_compare
