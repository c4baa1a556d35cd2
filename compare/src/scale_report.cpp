#include "scale_report.h"

#include <jansson.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "results_io.h"
#include "scale_scenarios.h"
#include "text_table.h"

namespace pool_compare {

namespace {

std::string fmt_dt(double dt) { return fmt(dt, "%.0e"); }

// "1 nm", "1 um", "1 mm".
std::string fmt_length(double m) {
	if (m < 1e-6)
		return fmt(m * 1e9, "%g") + " nm";
	if (m < 1e-3)
		return fmt(m * 1e6, "%g") + " um";
	return fmt(m * 1e3, "%g") + " mm";
}

std::string fmt_horizon(double seconds, bool censored) {
	if (!std::isfinite(seconds))
		return "-";
	return censored ? ">= " + fmt(seconds, "%.3g") + " (never 1 cm)" : fmt(seconds, "%.3g");
}

const SelfHorizon *self_at(const ScenarioHorizons &h, double perturbation) {
	for (const SelfHorizon &s : h.self)
		if (s.perturbation == perturbation)
			return &s;
	return nullptr;
}

const Record *libpool_row(const std::vector<Record> &records, const std::string &scenario) {
	for (const Record &r : records)
		if (r.scenario == scenario && r.engine == "libpool" && r.event_driven && r.error.empty())
			return &r;
	return nullptr;
}

// A run predicts at least as long as the self horizon.
bool as_long(const Record &r, const SelfHorizon &self) {
	if (!r.error.empty() || !std::isfinite(r.horizon_seconds))
		return false;
	if (self.horizon.censored)
		return r.horizon_censored;
	return r.horizon_censored || r.horizon_seconds >= self.horizon.seconds;
}

std::vector<std::string> stepped_engines(const std::vector<Record> &records, const std::string &scenario) {
	std::vector<std::string> engines;
	for (const Record &r : records)
		if (r.scenario == scenario && !r.event_driven &&
		    std::find(engines.begin(), engines.end(), r.engine) == engines.end())
			engines.push_back(r.engine);
	return engines;
}

json_t *number(double x) { return std::isfinite(x) ? json_real(x) : json_null(); }

} // namespace

double cpu_per_sim_second(const Record &r) {
	return r.sim_seconds > 0.0 ? r.cpu_seconds / r.sim_seconds : kNone;
}

std::vector<EqualPredictability> equal_predictability(const std::vector<Record> &records,
                                                      const ScenarioHorizons &horizons, double perturbation) {
	std::vector<EqualPredictability> out;
	const SelfHorizon *self = self_at(horizons, perturbation);
	for (const std::string &engine : stepped_engines(records, horizons.scenario)) {
		EqualPredictability e;
		e.engine = engine;
		std::vector<const Record *> sweep;
		for (const Record &r : records)
			if (r.scenario == horizons.scenario && r.engine == engine && !r.event_driven)
				sweep.push_back(&r);
		// Finest first: the coarsest step from which on every finer one gets there, so a lucky
		// coarse step does not count.
		std::sort(sweep.begin(), sweep.end(), [](const Record *a, const Record *b) { return a->dt < b->dt; });
		for (const Record *r : sweep) {
			if (!self || !as_long(*r, *self))
				break;
			e.run = r;
		}
		for (const Record *r : sweep)
			if (r->error.empty() && std::isfinite(r->horizon_seconds) &&
			    (!e.best || r->horizon_seconds > e.best->horizon_seconds))
				e.best = r;
		out.push_back(e);
	}
	return out;
}

std::string horizon_table(const std::vector<Record> &records, const std::vector<ScenarioHorizons> &horizons,
                          bool markdown) {
	const std::vector<std::string> head = {"scenario", "balls", "engine", "dt (s)", "horizon, 1 cm (s)",
	                                       "CPU s per simulated s"};
	std::vector<std::vector<std::string>> rows;
	for (const ScenarioHorizons &h : horizons) {
		const Record *lib = libpool_row(records, h.scenario);
		const std::string balls = std::to_string(h.balls);
		for (const SelfHorizon &s : h.self)
			rows.push_back({h.scenario, balls, "libpool, start " + fmt_length(s.perturbation) + " off", "event",
			                fmt_horizon(s.horizon.seconds, s.horizon.censored),
			                lib ? fmt(cpu_per_sim_second(*lib), "%.3g") : "-"});
		for (const Record &r : records) {
			if (r.scenario != h.scenario || r.event_driven)
				continue;
			if (!r.error.empty() && !std::isfinite(r.cpu_seconds)) {
				rows.push_back({h.scenario, balls, r.engine, fmt_dt(r.dt), "failed: " + r.error});
				continue;
			}
			rows.push_back({h.scenario, balls, r.engine, fmt_dt(r.dt), fmt_horizon(r.horizon_seconds, r.horizon_censored),
			                fmt(cpu_per_sim_second(r), "%.3g")});
		}
	}
	if (rows.empty())
		return "";
	return render_table(head, rows, markdown, "lrllrr", "lrllrr");
}

std::string scale_table(const std::vector<Record> &records, const std::vector<ScenarioHorizons> &horizons,
                        double perturbation, bool markdown) {
	std::vector<std::string> engines;
	for (const ScenarioHorizons &h : horizons)
		if (!h.family.empty())
			for (const std::string &e : stepped_engines(records, h.scenario))
				if (std::find(engines.begin(), engines.end(), e) == engines.end())
					engines.push_back(e);
	std::vector<std::string> head = {"family", "balls", "libpool CPU s / sim s",
	                                 "libpool's horizon, start " + fmt_length(perturbation) + " off (s)"};
	for (const std::string &e : engines)
		head.push_back(e + ": coarsest dt as predictive, CPU s / sim s");
	head.push_back("cheaper at equal predictability");
	std::vector<std::vector<std::string>> rows;
	for (const std::string &family : scale_families()) {
		std::vector<const ScenarioHorizons *> sizes;
		for (const ScenarioHorizons &h : horizons)
			if (h.family == family)
				sizes.push_back(&h);
		std::sort(sizes.begin(), sizes.end(),
		          [](const ScenarioHorizons *a, const ScenarioHorizons *b) { return a->balls < b->balls; });
		for (const ScenarioHorizons *h : sizes) {
			const Record *lib = libpool_row(records, h->scenario);
			const SelfHorizon *self = self_at(*h, perturbation);
			const double lib_cost = lib ? cpu_per_sim_second(*lib) : kNone;
			std::vector<std::string> row = {family, std::to_string(h->balls), fmt(lib_cost, "%.3g"),
			                                self ? fmt_horizon(self->horizon.seconds, self->horizon.censored) : "-"};
			std::string cheaper = "libpool";
			double best_cost = lib_cost;
			const std::vector<EqualPredictability> eq = equal_predictability(records, *h, perturbation);
			for (const std::string &engine : engines) {
				const EqualPredictability *e = nullptr;
				for (const EqualPredictability &x : eq)
					if (x.engine == engine)
						e = &x;
				if (!e) {
					row.push_back("-");
				} else if (e->run) {
					const double cost = cpu_per_sim_second(*e->run);
					row.push_back("dt " + fmt_dt(e->run->dt) + ": " + fmt(cost, "%.3g"));
					if (cost < best_cost || !std::isfinite(best_cost)) {
						best_cost = cost;
						cheaper = engine + " (" + fmt(lib_cost / cost, "%.2g") + "x)";
					}
				} else if (e->best) {
					row.push_back("never (best " + fmt_horizon(e->best->horizon_seconds, e->best->horizon_censored) +
					              " s at dt " + fmt_dt(e->best->dt) + ")");
				} else {
					row.push_back("no run");
				}
			}
			row.push_back(cheaper);
			rows.push_back(row);
		}
	}
	if (rows.empty())
		return "";
	std::string align(head.size(), 'l');
	align[1] = align[2] = 'r';
	return render_table(head, rows, markdown, align, align);
}

std::string scale_verdict(const std::vector<Record> &records, const std::vector<ScenarioHorizons> &horizons,
                          double perturbation) {
	std::ostringstream out;
	std::vector<std::string> wins;
	int compared = 0;
	for (const ScenarioHorizons &h : horizons) {
		if (h.family.empty())
			continue;
		const Record *lib = libpool_row(records, h.scenario);
		if (!lib)
			continue;
		++compared;
		for (const EqualPredictability &e : equal_predictability(records, h, perturbation))
			if (e.run && cpu_per_sim_second(*e.run) < cpu_per_sim_second(*lib))
				wins.push_back(h.family + " at " + std::to_string(h.balls) + " balls: " + e.engine + " at dt " +
				               fmt_dt(e.run->dt) + ", " + fmt(cpu_per_sim_second(*e.run), "%.3g") +
				               " CPU s per simulated s against libpool's " + fmt(cpu_per_sim_second(*lib), "%.3g"));
	}
	if (!compared)
		return "";
	out << "Equal predictability here: a time-stepped run whose trajectory stays within 1 cm of libpool's at least as "
	       "long as libpool's own does when its start is "
	    << fmt_length(perturbation) << " off (and at every finer step of the sweep). ";
	if (wins.empty()) {
		out << "At no ball count of the sweep does a time-stepped engine at equal predictability cost less CPU per "
		       "simulated second than libpool.\n";
	} else {
		out << "A time-stepped engine at equal predictability costs less CPU per simulated second than libpool in:\n\n";
		for (const std::string &w : wins)
			out << "- " << w << "\n";
	}
	return out.str();
}

bool write_horizon_json(const std::string &path, const std::vector<Record> &records,
                        const std::vector<ScenarioHorizons> &horizons, std::string *error) {
	json_t *root = json_object();
	json_object_set_new(root, "threshold", json_real(kHorizonThreshold));
	json_object_set_new(root, "spacing", json_real(kHorizonSpacing));
	json_t *scenarios = json_array();
	for (const ScenarioHorizons &h : horizons) {
		json_t *o = json_object();
		json_object_set_new(o, "scenario", json_string(h.scenario.c_str()));
		json_object_set_new(o, "balls", json_integer(h.balls));
		json_object_set_new(o, "family", h.family.empty() ? json_null() : json_string(h.family.c_str()));
		json_object_set_new(o, "end_time", number(h.end_time));
		const Record *lib = libpool_row(records, h.scenario);
		json_object_set_new(o, "libpool_cpu_per_sim_second", number(lib ? cpu_per_sim_second(*lib) : kNone));
		json_t *self = json_array();
		for (const SelfHorizon &s : h.self) {
			json_t *x = json_object();
			json_object_set_new(x, "perturbation", json_real(s.perturbation));
			json_object_set_new(x, "runs", json_integer(s.runs));
			json_object_set_new(x, "horizon_seconds", number(s.horizon.seconds));
			json_object_set_new(x, "censored", json_boolean(s.horizon.censored));
			json_object_set_new(x, "track", track_json(s.track));
			// The time-stepped engines' runs as predictive as this (null: none in the sweep).
			json_t *eq = json_object();
			for (const EqualPredictability &e : equal_predictability(records, h, s.perturbation))
				json_object_set_new(eq, e.engine.c_str(), e.run ? json_real(e.run->dt) : json_null());
			json_object_set_new(x, "equal_predictability_dt", eq);
			json_array_append_new(self, x);
		}
		json_object_set_new(o, "self", self);
		json_t *runs = json_array();
		for (const Record &r : records) {
			if (r.scenario != h.scenario || r.event_driven || r.track.t.empty())
				continue;
			json_t *x = json_object();
			json_object_set_new(x, "engine", json_string(r.engine.c_str()));
			json_object_set_new(x, "dt", number(r.dt));
			json_object_set_new(x, "horizon_seconds", number(r.horizon_seconds));
			json_object_set_new(x, "censored", json_boolean(r.horizon_censored));
			json_object_set_new(x, "cpu_per_sim_second", number(cpu_per_sim_second(r)));
			json_object_set_new(x, "track", track_json(r.track));
			json_array_append_new(runs, x);
		}
		json_object_set_new(o, "runs", runs);
		json_array_append_new(scenarios, o);
	}
	json_object_set_new(root, "scenarios", scenarios);
	char *text = json_dumps(root, JSON_COMPACT | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(10));
	json_decref(root);
	if (!text) {
		*error = "out of memory writing " + path;
		return false;
	}
	const std::string s = std::string(text) + "\n";
	free(text);
	return write_file(path, s, error);
}

} // namespace pool_compare
