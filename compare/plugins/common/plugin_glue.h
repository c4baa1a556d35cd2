// The plugin ABI (compare/include/pool_engine_plugin.h) around an engine class: argument checks,
// scenario parsing, error strings, and every entry point catching everything, so no input can
// take the harness down. The engine class provides
//     bool build(const pool_scenario &, double dt, std::string *error);
//     bool advance(double t);  bool run_to_rest(double max_time);
//     int balls(pool_engine_ball *, int) const;  int events(pool_engine_event *, int) const;
//     void stats(pool_engine_stats *) const;  const std::string &error() const;
// and a plugin's entry point returns make_api<Engine>(name, description).
#ifndef POOL_PLUGIN_PLUGIN_GLUE_H
#define POOL_PLUGIN_PLUGIN_GLUE_H

#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "pool_engine_plugin.h"
#include "pool/scenario.h"

namespace pool_plugin {

/// Writes a message into the caller's buffer (if any), truncated to fit.
inline void set_error(char *err, size_t size, const char *message) {
	if (err && size > 0)
		std::snprintf(err, size, "%s", message);
}

/// The C entry points for one engine class.
template <class Engine> struct Glue {
	static void *create(const char *json, const pool_engine_config *config, char *err,
	                    size_t err_size) {
		if (!json) {
			set_error(err, err_size, "scenario_json: NULL");
			return nullptr;
		}
		if (!config) {
			set_error(err, err_size, "config: NULL");
			return nullptr;
		}
		pool_scenario scenario{};
		char message[512] = {0};
		if (pool_scenario_parse(json, std::strlen(json), &scenario, message, sizeof message) != 0) {
			set_error(err, err_size, message[0] ? message : "scenario: invalid");
			pool_scenario_free(&scenario);
			return nullptr;
		}
		Engine *engine = nullptr;
		std::string error;
		bool ok = false;
		try {
			engine = new Engine();
			ok = engine->build(scenario, config->dt, &error);
		} catch (const std::bad_alloc &) {
			error = "out of memory";
		} catch (const std::exception &e) {
			error = e.what();
		} catch (...) {
			error = "unknown failure while building the engine";
		}
		pool_scenario_free(&scenario);
		if (!ok) {
			set_error(err, err_size, error.c_str());
			delete engine;
			return nullptr;
		}
		return engine;
	}

	static int advance(void *engine, double t) {
		if (!engine)
			return -1;
		try {
			return static_cast<Engine *>(engine)->advance(t) ? 0 : -1;
		} catch (...) {
			return -1;
		}
	}

	static int run_to_rest(void *engine, double max_time) {
		if (!engine)
			return -1;
		try {
			return static_cast<Engine *>(engine)->run_to_rest(max_time) ? 0 : -1;
		} catch (...) {
			return -1;
		}
	}

	static int balls(void *engine, pool_engine_ball *out, int capacity) {
		return engine ? static_cast<const Engine *>(engine)->balls(out, capacity) : -1;
	}

	static int events(void *engine, pool_engine_event *out, int capacity) {
		return engine ? static_cast<const Engine *>(engine)->events(out, capacity) : -1;
	}

	static void stats(void *engine, pool_engine_stats *out) {
		if (!out)
			return;
		if (!engine) {
			*out = pool_engine_stats{};
			return;
		}
		static_cast<const Engine *>(engine)->stats(out);
	}

	static const char *last_error(void *engine) {
		if (!engine)
			return "engine: NULL";
		return static_cast<const Engine *>(engine)->error().c_str();
	}

	static void destroy(void *engine) { delete static_cast<Engine *>(engine); }
};

/// The optional models query (POOL_ENGINE_MODELS_ENTRY) of an engine that has none of the optional
/// models (docs/physics.md "Models"), only its own approximation of the default laws: every
/// kind the scenario selects away from its default is one it cannot express ("kind=name").
inline int default_models_only(const char *json, char *out, size_t out_size) {
	if (!json) {
		set_error(out, out_size, "scenario_json: NULL");
		return -1;
	}
	pool_scenario scenario{};
	char message[512] = {0};
	if (pool_scenario_parse(json, std::strlen(json), &scenario, message, sizeof message) != 0) {
		set_error(out, out_size, message[0] ? message : "scenario: invalid");
		pool_scenario_free(&scenario);
		return -1;
	}
	const pool_models m = scenario.def.models;
	pool_scenario_free(&scenario);
	std::string list;
	int count = 0;
	auto add = [&](const char *kind, const char *name) {
		list += std::string(count++ ? "," : "") + kind + "=" + (name ? name : "unknown");
	};
	if (m.cushion != POOL_CUSHION_PETIT)
		add("cushion", pool_cushion_model_name(m.cushion));
	if (m.ball_ball_friction != POOL_BALL_FRICTION_CONSTANT)
		add("ball_ball_friction", pool_ball_friction_model_name(m.ball_ball_friction));
	if (m.squirt != POOL_SQUIRT_NONE)
		add("squirt", pool_squirt_model_name(m.squirt));
	set_error(out, out_size, list.c_str());
	return count;
}

/// The function table of a time-stepped engine plugin.
template <class Engine> constexpr pool_engine_api make_api(const char *name, const char *description) {
	return pool_engine_api{POOL_ENGINE_ABI_VERSION, name,          description,
	                       0,                       &Glue<Engine>::create,
	                       &Glue<Engine>::advance,  &Glue<Engine>::run_to_rest,
	                       &Glue<Engine>::balls,    &Glue<Engine>::events,
	                       &Glue<Engine>::stats,    &Glue<Engine>::last_error,
	                       &Glue<Engine>::destroy};
}

} // namespace pool_plugin

#endif
