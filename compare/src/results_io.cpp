#include "results_io.h"

#include "scale_report.h"
#include "text_table.h"

#include <jansson.h>
#include <unistd.h>

#include <cstdio>
#include <limits>
#include <fstream>
#include <algorithm>
#include <map>
#include <sstream>

namespace pool_compare {

namespace {

json_t *number_or_null(double x) { return std::isfinite(x) ? json_real(x) : json_null(); }

json_t *count_or_null(long long n) { return n >= 0 ? json_integer(n) : json_null(); }

json_t *record_object(const Record &r) {
	json_t *o = json_object();
	json_object_set_new(o, "scenario", json_string(r.scenario.c_str()));
	json_object_set_new(o, "engine", json_string(r.engine.c_str()));
	json_object_set_new(o, "dt", r.event_driven ? json_null() : number_or_null(r.dt));
	json_object_set_new(o, "cpu_seconds", number_or_null(r.cpu_seconds));
	json_object_set_new(o, "sim_seconds", number_or_null(r.sim_seconds));
	json_object_set_new(o, "final_position_error", number_or_null(r.final_position_error));
	json_object_set_new(o, "event_time_error", number_or_null(r.event_time_error));
	json_object_set_new(o, "energy_error", number_or_null(r.energy_error));
	json_object_set_new(o, "missed_collisions", json_integer(r.missed_collisions));
	json_object_set_new(o, "phantom_collisions", json_integer(r.phantom_collisions));
	json_object_set_new(o, "max_penetration", number_or_null(r.max_penetration));
	json_object_set_new(o, "reference", json_string(r.reference.c_str()));
	// Beyond docs/interfaces.md:
	json_object_set_new(o, "speed", number_or_null(r.speed()));
	json_object_set_new(o, "cpu_seconds_min", number_or_null(r.cpu_seconds_min));
	json_object_set_new(o, "repetitions", json_integer(r.repetitions));
	json_object_set_new(o, "setup_cpu_seconds", number_or_null(r.setup_cpu_seconds));
	json_object_set_new(o, "steps", json_integer(r.steps));
	json_object_set_new(o, "event_position_error", number_or_null(r.event_position_error));
	json_object_set_new(o, "direction_error_deg", number_or_null(r.direction_error_deg));
	json_object_set_new(o, "consistency_error", number_or_null(r.consistency_error));
	json_object_set_new(o, "first_contact_time_error", number_or_null(r.first_contact_time_error));
	json_object_set_new(o, "slide_roll_time_error", number_or_null(r.slide_roll_time_error));
	json_object_set_new(o, "stop_time_error", number_or_null(r.stop_time_error));
	json_object_set_new(o, "collision_time_error", number_or_null(r.collision_time_error));
	json_object_set_new(o, "unmatched_events", json_integer(r.unmatched_events));
	json_object_set_new(o, "collisions_reference", json_integer(r.collisions_reference));
	json_object_set_new(o, "collisions_engine", json_integer(r.collisions_engine));
	json_object_set_new(o, "pocket_mismatches", json_integer(r.pocket_mismatches));
	json_object_set_new(o, "engine_messages", json_integer(r.engine_messages));
	json_object_set_new(o, "simultaneous_contacts", json_integer(r.simultaneous_contacts));
	json_object_set_new(o, "cushions_by_rail", json_boolean(r.cushions_by_rail));
	json_object_set_new(o, "spread_runs", json_integer(r.spread_runs));
	json_object_set_new(o, "spread_perturbation", number_or_null(r.spread_perturbation));
	json_object_set_new(o, "spread_rms", number_or_null(r.spread_rms));
	json_object_set_new(o, "spread_max", number_or_null(r.spread_max));
	json_object_set_new(o, "event_driven", json_boolean(r.event_driven));
	json_object_set_new(o, "notes", json_string(r.description.c_str()));
	json_object_set_new(o, "error", r.error.empty() ? json_null() : json_string(r.error.c_str()));
	json_object_set_new(o, "outcome", json_string(r.outcome.c_str()));
	json_object_set_new(o, "wall_seconds", number_or_null(r.wall_seconds));
	// Airborne motion (landings on the cloth):
	json_object_set_new(o, "landing_time_error", number_or_null(r.landing_time_error));
	json_object_set_new(o, "landing_position_error", number_or_null(r.landing_position_error));
	json_object_set_new(o, "bounce_height_error", number_or_null(r.bounce_height_error));
	json_object_set_new(o, "landings_reference", json_integer(r.landings_reference));
	json_object_set_new(o, "landings_engine", json_integer(r.landings_engine));
	json_object_set_new(o, "reference_error",
	                    r.reference_error.empty() ? json_null() : json_string(r.reference_error.c_str()));
	// The scenario's models the engine cannot express (null: the plugin does not say).
	json_t *models = r.models_known ? json_array() : json_null();
	for (const std::string &m : r.unsupported_models)
		json_array_append_new(models, json_string(m.c_str()));
	json_object_set_new(o, "unsupported_models", models);
	// Persistent contact (LINK; null from plugins without the POOL_ENGINE_LINK_ENTRY export), and
	// whether the reference is exact (false: libpool's result with LINK steps; null: no reference).
	json_object_set_new(o, "link_cpu_share", number_or_null(r.link_cpu_share));
	json_object_set_new(o, "link_steps", count_or_null(r.link_steps));
	json_object_set_new(o, "link_events", count_or_null(r.link_events));
	json_object_set_new(o, "link_clusters", count_or_null(r.link_clusters));
	json_object_set_new(o, "reference_exact", r.reference_exact < 0 ? json_null() : json_boolean(r.reference_exact));
	// Scale and chaos: the scenario's ball count, its scale family (null: not generated by
	// --scale), and the predictability horizon (null: not measured).
	json_object_set_new(o, "balls", json_integer(r.balls));
	json_object_set_new(o, "family", r.family.empty() ? json_null() : json_string(r.family.c_str()));
	json_object_set_new(o, "horizon_seconds", number_or_null(r.horizon_seconds));
	json_object_set_new(o, "horizon_censored",
	                    std::isfinite(r.horizon_seconds) ? json_boolean(r.horizon_censored) : json_null());
	return o;
}

double get_number(json_t *o, const char *key) {
	json_t *v = json_object_get(o, key);
	return json_is_number(v) ? json_number_value(v) : kNone;
}

// An optional count: -1 when null or absent.
long long get_count(json_t *o, const char *key) {
	json_t *v = json_object_get(o, key);
	return json_is_integer(v) ? static_cast<long long>(json_integer_value(v)) : -1;
}

long long get_integer(json_t *o, const char *key) {
	json_t *v = json_object_get(o, key);
	return json_is_integer(v) ? static_cast<long long>(json_integer_value(v)) : 0;
}

std::string get_string(json_t *o, const char *key) {
	json_t *v = json_object_get(o, key);
	return json_is_string(v) ? json_string_value(v) : "";
}

const size_t kJsonFlags = JSON_REAL_PRECISION(17);

std::string csv_cell(json_t *v) {
	if (json_is_null(v))
		return "";
	if (json_is_string(v)) {
		std::string s = json_string_value(v), out = "\"";
		for (char c : s)
			out += c == '"' ? std::string("\"\"") : std::string(1, c);
		return out + "\"";
	}
	if (json_is_true(v))
		return "true";
	if (json_is_false(v))
		return "false";
	char *text = json_dumps(v, JSON_ENCODE_ANY | kJsonFlags);
	std::string s = text ? text : "";
	free(text);
	return s;
}

// libpool's own row where libpool's result is the reference: its errors are 0 by construction.
bool is_own_reference(const Record &r) { return r.engine == "libpool" && r.event_driven && r.reference == "libpool"; }

bool any_sequential(const std::vector<Record> &records) {
	for (const Record &r : records)
		if (r.simultaneous_contacts > 0 && r.reference == "libpool")
			return true;
	return false;
}

bool cushions_named(const std::vector<Record> &records) {
	for (const Record &r : records)
		if (!r.cushions_by_rail)
			return false;
	return true;
}

// The notes under the report's table: engine messages and simultaneous contacts.
std::string footnotes(const std::vector<Record> &records) {
	std::ostringstream out;
	int flagged = 0, lines = 0;
	for (const Record &r : records)
		if (r.engine_messages > 0) {
			++flagged;
			lines += r.engine_messages;
		}
	if (flagged)
		out << "† N: the engine printed N lines during this run (" << flagged << " runs, " << lines
		    << " lines in all; text in `engines.log`, e.g. ODE's `LCP internal error`, a solve that failed and "
		       "was patched up): treat those rows with care.\n\n";
	std::vector<std::string> scenarios;
	for (const Record &r : records)
		if (r.simultaneous_contacts > 0 && r.reference == "libpool" &&
		    std::find(scenarios.begin(), scenarios.end(), r.scenario) == scenarios.end())
			scenarios.push_back(r.scenario);
	if (!scenarios.empty()) {
		out << "‡ Exactly simultaneous contacts (";
		for (size_t i = 0; i < scenarios.size(); ++i) {
			const std::string spread = [&] {
				for (const Record &r : records)
					if (r.scenario == scenarios[i] && r.event_driven && r.spread_runs)
						return ", libpool's own spread " + fmt(r.spread_rms, "%.2g") + " m";
				return std::string();
			}();
			out << (i ? "; " : "") << "`" << scenarios[i] << "`" << spread;
		}
		out << "): libpool resolves contacts that happen at the same instant pairwise, one after the other, in "
		       "a fixed order, while ODE and Bullet solve them together. libpool's answer there is one "
		       "admissible outcome, not ground truth (pairwise events are ill-posed for simultaneous "
		       "contacts), so the errors of those rows measure the distance between two admissible "
		       "outcomes as much as an engine's error.\n";
	}
	return out.str();
}

} // namespace

json_t *track_json(const ErrorTrack &track) {
	json_t *list = json_array();
	for (size_t k = 0; k < track.t.size(); ++k)
		json_array_append_new(list, json_pack("[oo]", number_or_null(track.t[k]), number_or_null(track.error[k])));
	return list;
}

ErrorTrack track_from_json(json_t *list) {
	ErrorTrack track;
	size_t k;
	json_t *point;
	json_array_foreach(list, k, point) {
		json_t *e = json_array_get(point, 1);
		track.t.push_back(json_number_value(json_array_get(point, 0)));
		// null: a distance that is not a number (a ball missing from one side), infinity
		track.error.push_back(json_is_number(e) ? json_number_value(e) : std::numeric_limits<double>::infinity());
	}
	return track;
}

std::string record_json(const Record &r) {
	json_t *o = record_object(r);
	char *text = json_dumps(o, JSON_COMPACT | kJsonFlags);
	std::string s = text ? text : "{}";
	free(text);
	json_decref(o);
	return s;
}

std::string record_wire(const Record &r) {
	json_t *o = record_object(r);
	json_t *balls = json_array();
	for (const BallSample &b : r.final_balls) {
		json_t *row = json_array();
		json_array_append_new(row, json_integer(b.id));
		json_array_append_new(row, json_integer(b.state));
		for (const Eigen::Vector3d *v : {&b.pos, &b.vel, &b.omega})
			for (int k = 0; k < 3; ++k)
				json_array_append_new(row, json_real((*v)[k]));
		json_array_append_new(balls, row);
	}
	json_object_set_new(o, "final_balls", balls);
	json_object_set_new(o, "track", track_json(r.track));
	char *text = json_dumps(o, JSON_COMPACT | kJsonFlags);
	json_decref(o);
	std::string s = text ? text : "";
	free(text);
	return s;
}

bool record_from_wire(const std::string &text, Record *out, std::string *error) {
	json_error_t parse_error;
	json_t *o = json_loadb(text.data(), text.size(), 0, &parse_error);
	if (!json_is_object(o)) {
		json_decref(o);
		*error = std::string("unreadable record: ") + parse_error.text;
		return false;
	}
	Record r;
	r.scenario = get_string(o, "scenario");
	r.engine = get_string(o, "engine");
	r.description = get_string(o, "notes");
	r.reference = get_string(o, "reference");
	r.error = get_string(o, "error");
	r.outcome = get_string(o, "outcome");
	r.reference_error = get_string(o, "reference_error");
	json_t *models = json_object_get(o, "unsupported_models");
	r.models_known = json_is_array(models);
	for (size_t i = 0; i < json_array_size(models); ++i)
		if (json_is_string(json_array_get(models, i)))
			r.unsupported_models.push_back(json_string_value(json_array_get(models, i)));
	r.event_driven = json_is_true(json_object_get(o, "event_driven"));
	r.cushions_by_rail = json_is_true(json_object_get(o, "cushions_by_rail"));
	struct {
		const char *key;
		double Record::*field;
	} numbers[] = {{"dt", &Record::dt},
	               {"cpu_seconds", &Record::cpu_seconds},
	               {"cpu_seconds_min", &Record::cpu_seconds_min},
	               {"setup_cpu_seconds", &Record::setup_cpu_seconds},
	               {"sim_seconds", &Record::sim_seconds},
	               {"final_position_error", &Record::final_position_error},
	               {"event_position_error", &Record::event_position_error},
	               {"direction_error_deg", &Record::direction_error_deg},
	               {"energy_error", &Record::energy_error},
	               {"event_time_error", &Record::event_time_error},
	               {"first_contact_time_error", &Record::first_contact_time_error},
	               {"slide_roll_time_error", &Record::slide_roll_time_error},
	               {"stop_time_error", &Record::stop_time_error},
	               {"collision_time_error", &Record::collision_time_error},
	               {"max_penetration", &Record::max_penetration},
	               {"spread_perturbation", &Record::spread_perturbation},
	               {"spread_rms", &Record::spread_rms},
	               {"spread_max", &Record::spread_max},
	               {"consistency_error", &Record::consistency_error},
	               {"wall_seconds", &Record::wall_seconds},
	               {"landing_time_error", &Record::landing_time_error},
	               {"landing_position_error", &Record::landing_position_error},
	               {"bounce_height_error", &Record::bounce_height_error},
	               {"link_cpu_share", &Record::link_cpu_share}};
	for (const auto &n : numbers)
		r.*n.field = get_number(o, n.key);
	struct {
		const char *key;
		int Record::*field;
	} integers[] = {{"repetitions", &Record::repetitions},
	                {"unmatched_events", &Record::unmatched_events},
	                {"missed_collisions", &Record::missed_collisions},
	                {"phantom_collisions", &Record::phantom_collisions},
	                {"simultaneous_contacts", &Record::simultaneous_contacts},
	                {"collisions_reference", &Record::collisions_reference},
	                {"collisions_engine", &Record::collisions_engine},
	                {"pocket_mismatches", &Record::pocket_mismatches},
	                {"engine_messages", &Record::engine_messages},
	                {"spread_runs", &Record::spread_runs},
	                {"landings_reference", &Record::landings_reference},
	                {"landings_engine", &Record::landings_engine}};
	for (const auto &n : integers)
		r.*n.field = static_cast<int>(get_integer(o, n.key));
	r.steps = get_integer(o, "steps");
	r.balls = static_cast<int>(get_integer(o, "balls"));
	r.family = get_string(o, "family");
	r.horizon_seconds = get_number(o, "horizon_seconds");
	r.horizon_censored = json_is_true(json_object_get(o, "horizon_censored"));
	r.track = track_from_json(json_object_get(o, "track"));
	r.link_steps = get_count(o, "link_steps");
	r.link_events = get_count(o, "link_events");
	r.link_clusters = get_count(o, "link_clusters");
	json_t *exact = json_object_get(o, "reference_exact");
	r.reference_exact = json_is_boolean(exact) ? json_is_true(exact) : -1;
	size_t i;
	json_t *row;
	json_array_foreach(json_object_get(o, "final_balls"), i, row) {
		BallSample b;
		b.id = static_cast<int>(json_integer_value(json_array_get(row, 0)));
		b.state = static_cast<int>(json_integer_value(json_array_get(row, 1)));
		for (int k = 0; k < 3; ++k) {
			b.pos[k] = json_number_value(json_array_get(row, 2 + k));
			b.vel[k] = json_number_value(json_array_get(row, 5 + k));
			b.omega[k] = json_number_value(json_array_get(row, 8 + k));
		}
		r.final_balls.push_back(b);
	}
	json_decref(o);
	*out = std::move(r);
	return true;
}

bool write_results_json(const std::string &path, const std::vector<Record> &records, std::string *error) {
	json_t *list = json_array();
	for (const Record &r : records)
		json_array_append_new(list, record_object(r));
	char *text = json_dumps(list, JSON_INDENT(2) | kJsonFlags);
	json_decref(list);
	if (!text) {
		*error = "out of memory writing " + path;
		return false;
	}
	std::string s = std::string(text) + "\n";
	free(text);
	return write_file(path, s, error);
}

bool write_results_csv(const std::string &path, const std::vector<Record> &records, std::string *error) {
	std::ostringstream out;
	Record blank;
	json_t *header = record_object(blank);
	const char *key;
	json_t *value;
	bool first = true;
	json_object_foreach(header, key, value) {
		out << (first ? "" : ",") << key;
		first = false;
	}
	out << "\n";
	for (const Record &r : records) {
		json_t *o = record_object(r);
		first = true;
		json_object_foreach(header, key, value) {
			out << (first ? "" : ",") << csv_cell(json_object_get(o, key));
			first = false;
		}
		out << "\n";
		json_decref(o);
	}
	json_decref(header);
	return write_file(path, out.str(), error);
}

std::string results_table(const std::vector<Record> &records, bool markdown) {
	const std::vector<std::string> head = {"scenario", "engine", "dt (s)", "sim s / CPU s", "final pos err (m)",
	                                       "event t err (s)", "dir err (deg)", "energy err (J)", "missed",
	                                       "phantom", "max pen (m)", "spread rms (m)", "reference"};
	std::vector<std::vector<std::string>> rows;
	for (const Record &r : records) {
		if (!r.error.empty() && !std::isfinite(r.cpu_seconds)) {
			rows.push_back({r.scenario, r.engine, r.event_driven ? "event" : fmt(r.dt, "%.0e"), "failed: " + r.error});
			continue;
		}
		// In the report, a row whose engine printed messages (ODE's "LCP internal error", ...) is
		// flagged with their count, and a libpool reference that resolved simultaneous contacts in
		// sequence is marked: it is one admissible outcome there, not ground truth.
		const std::string engine =
		    markdown && r.engine_messages > 0 ? r.engine + " †" + std::to_string(r.engine_messages) : r.engine;
		const std::string reference =
		    r.reference == "none" ? "no reference"
		    : markdown && r.simultaneous_contacts > 0 && r.reference == "libpool" ? r.reference + " ‡"
		                                                                          : r.reference;
		// libpool measured against its own result: no error to show, it is the reference.
		if (is_own_reference(r)) {
			rows.push_back({r.scenario, engine, "event", fmt(r.speed()), "reference", "reference", "reference",
			                "reference", "-", "-", fmt(r.max_penetration, "%.2e"),
			                r.spread_runs ? fmt(r.spread_rms, "%.2e") : "-", reference});
			continue;
		}
		rows.push_back({r.scenario, engine, r.event_driven ? "event" : fmt(r.dt, "%.0e"), fmt(r.speed()),
		                fmt(r.final_position_error, "%.2e"), fmt(r.event_time_error, "%.2e"),
		                fmt(r.direction_error_deg, "%.2g"), fmt(r.energy_error, "%.2e"),
		                std::to_string(r.missed_collisions), std::to_string(r.phantom_collisions),
		                fmt(r.max_penetration, "%.2e"), r.spread_runs ? fmt(r.spread_rms, "%.2e") : "-",
		                reference});
	}
	// Names, the dt and the reference read left; the numbers right.
	std::string align(head.size(), 'r');
	align[0] = align[1] = align.back() = 'l';
	return render_table(head, rows, markdown, align, align);
}

std::string landing_table(const std::vector<Record> &records, bool markdown) {
	const std::vector<std::string> head = {"scenario", "engine", "dt (s)", "landings (ref / engine)",
	                                       "landing t err (s)", "landing pos err (m)", "bounce height err (m)",
	                                       "reference"};
	std::vector<std::vector<std::string>> rows;
	for (const Record &r : records) {
		if (r.landings_reference == 0 && r.landings_engine == 0)
			continue;
		if (!r.error.empty() && !std::isfinite(r.cpu_seconds)) {
			rows.push_back({r.scenario, r.engine, r.event_driven ? "event" : fmt(r.dt, "%.0e"), "failed: " + r.error});
			continue;
		}
		const bool truth = r.reference != "none";
		rows.push_back({r.scenario, r.engine, r.event_driven ? "event" : fmt(r.dt, "%.0e"),
		                (truth ? std::to_string(r.landings_reference) : std::string("-")) + " / " +
		                    std::to_string(r.landings_engine),
		                fmt(r.landing_time_error, "%.2e"), fmt(r.landing_position_error, "%.2e"),
		                fmt(r.bounce_height_error, "%.2e"), truth ? r.reference : "no reference"});
	}
	if (rows.empty())
		return "";
	std::string align(head.size(), 'r');
	align[0] = align[1] = align.back() = 'l';
	return render_table(head, rows, markdown, align, align);
}

namespace {

bool is_link_scenario(const std::vector<Record> &records, const std::string &scenario) {
	for (const Record &r : records)
		if (r.scenario == scenario && (r.reference_exact == 0 || r.link_events > 0))
			return true;
	return false;
}

// The largest final-position distance to another time-stepped engine's run at the same step.
double cross_engine_error(const std::vector<Record> &records, const Record &r) {
	double worst = kNone;
	if (r.event_driven || r.final_balls.empty())
		return worst;
	for (const Record &o : records)
		if (o.scenario == r.scenario && o.engine != r.engine && !o.event_driven && o.dt == r.dt && o.error.empty() &&
		    !o.final_balls.empty()) {
			const double d = max_position_error(r.final_balls, o.final_balls);
			worst = std::isnan(worst) ? d : std::max(worst, d);
		}
	return worst;
}

} // namespace

std::string link_table(const std::vector<Record> &records, bool markdown) {
	const std::vector<std::string> head = {"scenario", "engine", "dt (s)", "CPU median / min (ms)", "link share",
	                                       "link steps (clusters)", "final pos vs libpool (m)",
	                                       "vs other engine, same dt (m)", "max pen (m)"};
	std::vector<std::vector<std::string>> rows;
	for (const Record &r : records) {
		if (!is_link_scenario(records, r.scenario))
			continue;
		const std::string dt = r.event_driven ? "event" : fmt(r.dt, "%.0e");
		if (!r.error.empty() && !std::isfinite(r.cpu_seconds)) {
			rows.push_back({r.scenario, r.engine, dt, "failed: " + r.error});
			continue;
		}
		rows.push_back({r.scenario, r.engine, dt,
		                fmt(1e3 * r.cpu_seconds, "%.3g") + " / " + fmt(1e3 * r.cpu_seconds_min, "%.3g"),
		                std::isfinite(r.link_cpu_share) ? fmt(100.0 * r.link_cpu_share, "%.1f") + " %" : "-",
		                r.link_steps >= 0 ? std::to_string(r.link_steps) + " (" + std::to_string(r.link_clusters) + ")"
		                                  : "-",
		                r.engine == "libpool" && r.event_driven ? "(reference)" : fmt(r.final_position_error, "%.2e"),
		                fmt(cross_engine_error(records, r), "%.2e"), fmt(r.max_penetration, "%.2e")});
	}
	if (rows.empty())
		return "";
	std::string align(head.size(), 'r');
	align[0] = align[1] = 'l';
	return render_table(head, rows, markdown, align, align);
}

void fill_consistency(std::vector<Record> *records) {
	for (Record &r : *records)
		r.consistency_error = kNone; // recomputed: a finer step may have been added since
	for (Record &r : *records) {
		if (r.event_driven || !r.error.empty() || r.final_balls.empty())
			continue;
		const Record *finest = nullptr;
		for (const Record &o : *records)
			if (o.scenario == r.scenario && o.engine == r.engine && !o.event_driven && o.error.empty() &&
			    !o.final_balls.empty() && (!finest || o.dt < finest->dt))
				finest = &o;
		if (finest && finest != &r)
			r.consistency_error = max_position_error(r.final_balls, finest->final_balls);
	}
}

std::string accuracy_summary(const std::vector<Record> &records, double tolerance, bool markdown) {
	std::vector<std::vector<std::string>> rows;
	std::vector<std::string> done;
	for (const Record &r : records) {
		if (r.event_driven)
			continue;
		const std::string key = r.scenario + "/" + r.engine;
		if (std::find(done.begin(), done.end(), key) != done.end())
			continue;
		done.push_back(key);
		const Record *libpool = nullptr, *reached = nullptr, *best = nullptr;
		std::vector<const Record *> sweep;
		for (const Record &o : records) {
			if (o.scenario != r.scenario)
				continue;
			if (o.engine == "libpool" && o.event_driven && o.error.empty())
				libpool = &o;
			if (o.engine == r.engine && !o.event_driven)
				sweep.push_back(&o);
		}
		// The largest step from which every finer step of the sweep stays within tolerance, so a
		// lucky cancellation at one coarse step does not count.
		std::sort(sweep.begin(), sweep.end(), [](const Record *a, const Record *b) { return a->dt < b->dt; });
		for (const Record *o : sweep) {
			if (!(o->final_position_error <= tolerance))
				break;
			reached = o;
		}
		for (const Record *o : sweep)
			if (std::isfinite(o->final_position_error) && (!best || o->final_position_error < best->final_position_error))
				best = o;
		std::string where, ratio = "-";
		if (r.reference == "none") {
			where = "no reference";
		} else if (reached) {
			where = "dt " + fmt(reached->dt, "%.0e") + " (" + fmt(reached->final_position_error, "%.2g") + " m, " +
			        fmt(reached->speed(), "%.3g") + " sim s / CPU s)";
			if (libpool)
				ratio = fmt(libpool->speed() / reached->speed(), "%.3g") + "x";
		} else if (best) {
			where = "never (best " + fmt(best->final_position_error, "%.2g") + " m at dt " + fmt(best->dt, "%.0e") + ")";
		} else {
			where = "no run";
		}
		const bool sequential = r.simultaneous_contacts > 0 && r.reference == "libpool";
		if (sequential && !reached)
			where += markdown ? " ‡" : " (simultaneous contacts: libpool's answer is one admissible outcome)";
		// Where libpool is the reference it has no error of its own: "reference", not "0 m".
		const std::string own = libpool ? (is_own_reference(*libpool) ? std::string("reference")
		                                                              : fmt(libpool->final_position_error, "%.2g") + " m") +
		                                      ", " + fmt(libpool->speed(), "%.3g")
		                                : "-";
		rows.push_back({r.scenario, r.engine, where, own, ratio, markdown && sequential ? r.reference + " ‡" : r.reference});
	}
	const std::vector<std::string> head = {"scenario", "engine", "largest dt within " + fmt(tolerance, "%g") + " m",
	                                       "libpool (error, sim s / CPU s)", "libpool faster by", "reference"};
	return render_table(head, rows, markdown, "llllrl", "llllll");
}

std::string machine_description() {
	std::ifstream in("/proc/cpuinfo");
	std::string line, model = "unknown CPU";
	while (std::getline(in, line))
		if (line.compare(0, 10, "model name") == 0) {
			model = line.substr(line.find(':') + 2);
			break;
		}
	return model + ", " + std::to_string(sysconf(_SC_NPROCESSORS_ONLN)) + " cores online";
}

bool write_report(const std::string &dir, const std::vector<Record> &records, const std::string &command_line,
                  const std::vector<std::string> &plots, std::string *error,
                  const std::vector<ScenarioHorizons> &horizons) {
	std::ostringstream out;
	out << "# Engine comparison: libpool against time-stepped engines\n\n";
	out << "Command: `" << command_line << "`  \nMachine: " << machine_description() << "\n\n";
	out << "Errors are against the closed form of docs/physics.md where one exists (`closed-form`), else against "
	       "libpool's exact event-driven result (`libpool`, whose own errors are then 0 by definition). "
	       "States are compared at the time the engine actually reached (a step boundary), with the reference "
	       "evaluated at that same time. `sim s / CPU s` is simulated seconds per CPU second (median of the "
	       "timed runs); `spread rms` is the RMS change of the final positions when the lead ball starts 1 um "
	       "elsewhere (predictability). `dir err` is the largest angle between engine and reference velocities "
	       "(balls faster than 5 cm/s) at sample instants where both have had the same collisions: instants "
	       "between a collision in one and its counterpart in the other (at most 0.5 s apart), or within max(3 dt, 1 ms) of any "
	       "collision, are left out, so it measures how a ball leaves a collision, not when (that is `event t "
	       "err`). `missed` / `phantom` count ball pairs and (ball, cushion) contacts of the reference the "
	       "engine lacks / has in excess" << (cushions_named(records) ? ", cushions told apart by rail" : "")
	    << ". Every field is in `results.json` / `results.csv`.\n\n";
	out << results_table(records, true) << "\n";
	out << footnotes(records) << "\n";
	const std::string flights = landing_table(records, true);
	if (!flights.empty())
		out << "## Flight and landing (airborne scenarios)\n\nLandings are ball-cloth contacts of a flying "
		       "ball (`BALL_TABLE` events), matched in order per ball: `landing t err` is the largest time "
		       "difference of the k-th landing in engine and reference, `landing pos err` the largest xy "
		       "distance at the reference's landing instants, `bounce height err` the largest height "
		       "difference at the reference's apex instants (states at the step the engine reached). The "
		       "closed form settles a rebound that would fly less than 1 ms.\n\n"
		    << flights << "\n";
	const std::string links = link_table(records, true);
	if (!links.empty())
		out << "## Persistent contact (LINK scenarios)\n\nIn these scenes contact persists (a ball pushing or "
		       "resting on another): libpool advances the touching balls as a cluster by LCP steps (`link_begin`, "
		       "`link_step`, `link_end` events; docs/physics.md \"LINK\") between its exact events. No exact "
		       "solution exists: the reference is libpool's result with those first-order steps "
		       "(`reference_exact: false` in results.json), so `final pos vs libpool` is the engines' "
		       "disagreement with libpool, and `vs other engine` the time-stepped engines' disagreement "
		       "with each other at the same step. `link share` is the part of libpool's step time spent "
		       "in steps that produced a link event (timed by the plugin around each `pool_sim_step`, "
		       "median of the timed runs); `link steps` the LCP solves of the run.\n\n"
		    << links << "\n";
	std::vector<std::string> missing;
	for (const Record &r : records)
		if (r.reference == "none" && std::find(missing.begin(), missing.end(), r.scenario) == missing.end())
			missing.push_back(r.scenario);
	// Models an engine ran without (its own laws instead): once per scenario and engine.
	std::vector<std::string> unexpressed;
	for (const Record &r : records) {
		if (r.unsupported_models.empty())
			continue;
		std::string line = "- `" + r.scenario + "` / " + r.engine + ":";
		for (const std::string &m : r.unsupported_models)
			line += " `" + m + "`";
		if (std::find(unexpressed.begin(), unexpressed.end(), line) == unexpressed.end())
			unexpressed.push_back(line);
	}
	if (!unexpressed.empty()) {
		out << "## Models an engine cannot express\n\nThese scenarios select models (docs/physics.md "
		       "\"Models\") that the engine does not have; it ran them with its own laws, so its "
		       "errors there include the difference of the laws, not only its integration "
		       "(`unsupported_models` in results.json):\n\n";
		for (const std::string &line : unexpressed)
			out << line << "\n";
		out << "\n";
	}
	if (!missing.empty()) {
		out << "## Scenarios without a reference\n\nThese ran on every engine but nothing is scored (no "
		       "closed form applies and the libpool reference failed); their rows say `no reference`:\n\n";
		for (const std::string &name : missing)
			for (const Record &r : records)
				if (r.scenario == name) {
					out << "- `" << name << "`: " << r.reference_error << "\n";
					break;
				}
		out << "\n";
	}
	out << "## Speed at equal accuracy\n\nThe largest swept time step from which on each time-stepped engine's final "
	       "positions stay within 1 mm of the reference, and libpool's speed over the engine's there. "
	       "`consistency_error` in results.json separates the discretisation error (against the engine's own "
	       "finest step) from modelling differences.\n\n";
	out << accuracy_summary(records, 1e-3, true) << "\n";
	if (any_sequential(records))
		out << "‡ as in the table above: libpool's sequential answer is one admissible outcome there, so "
		       "\"never\" means the engine lands on a different outcome, not that it cannot converge; its "
		       "`consistency_error` tells whether it converges to its own.\n\n";
	const std::string chaos = horizon_table(records, horizons, true);
	if (!chaos.empty())
		out << "## Predictability horizon (chaotic scenes)\n\nA break or a gas of balls is chaotic: each collision "
		       "multiplies a small offset by about the distance between the balls over their radius, so a final "
		       "position after seconds is ill-posed (in the frozen-rack break libpool itself ends millimetres away when "
		       "its cue ball starts 1 um elsewhere). The horizon is the time until a trajectory departs 1 cm (the largest distance over "
		       "the balls) from libpool's, sampled every "
		    << fmt(1e3 * kHorizonSpacing, "%g")
		    << " ms: for each time-stepped run, and for libpool against itself with its start 1 nm, 1 um or 1 mm "
		       "off: the struck ball moved that far (in a scene without a strike, every ball, each its own way), "
		       "in 8 directions (the median distance). `>= T (never "
		       "1 cm)`: still within 1 cm at the end of the scene. The errors against time are drawn in "
		       "`<scenario>_horizon.png`; the tracks are in `horizon.json`.\n\n"
		    << chaos << "\n";
	bool scaled = false;
	for (double perturbation : {1e-3, 1e-6}) {
		const std::string table = scale_table(records, horizons, perturbation, true);
		if (table.empty())
			continue;
		if (!scaled)
			out << "## Scale: CPU per simulated second against the number of balls\n\nThe scale families "
			       "(`--scale`) on tables of N / 16 standard areas. Equal accuracy, for these chaotic scenes, is "
			       "equal predictability: the coarsest swept step from which every finer step keeps the run within "
			       "1 cm of libpool at least as long as libpool stays within 1 cm of itself when its start is 1 mm "
			       "off (a table measured by a camera) or 1 um off. `scale.png` draws every run.\n\n";
		scaled = true;
		out << "As predictive as libpool with its start " << (perturbation >= 1e-3 ? "1 mm" : "1 um")
		    << " off:\n\n"
		    << table << "\n" << scale_verdict(records, horizons, perturbation) << "\n";
	}
	std::map<std::string, std::string> notes;
	for (const Record &r : records)
		notes[r.engine] = r.description;
	out << "## Engines\n\n";
	for (const auto &[engine, note] : notes)
		out << "- **" << engine << "**: " << note << "\n";
	bool failures = false;
	for (const Record &r : records)
		if (!r.error.empty()) {
			if (!failures)
				out << "\n## Runs that failed or are incomplete\n\n";
			failures = true;
			out << "- " << r.scenario << " / " << r.engine << " / "
			    << (r.event_driven ? std::string("event") : "dt " + fmt(r.dt, "%.0e")) << ": " << r.error
			    << (r.outcome != "ok" && r.outcome != "failed" ? " (" + r.outcome + ")" : "") << "\n";
		}
	if (!plots.empty()) {
		out << "\n## Plots\n\nLeft of each pair: speed (simulated s per CPU s) against final-position error, one "
		       "curve per engine over the time-step sweep (after Erez, Tassa & Todorov 2015, with true error "
		       "instead of consistency). Right: final-position error against the time step.\n\n";
		for (const std::string &p : plots)
			out << "![" << p << "](" << p << ")\n";
	}
	return write_file(dir + "/report.md", out.str(), error);
}

} // namespace pool_compare
