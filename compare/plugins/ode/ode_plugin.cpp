// The plugin ABI (pool_engine_plugin.h) around the ODE model: argument checks, scenario
// parsing and error strings, so no input can crash the harness.
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "ode_engine.h"

namespace {

void copy_message(const std::string &message, char *err, size_t err_size) {
	if (!err || err_size == 0)
		return;
	std::snprintf(err, err_size, "%s", message.c_str());
}

void *ode_create(const char *scenario_json, const pool_engine_config *config, char *err,
                 size_t err_size) {
	if (!scenario_json) {
		copy_message("scenario_json: NULL", err, err_size);
		return nullptr;
	}
	if (!config) {
		copy_message("config: NULL", err, err_size);
		return nullptr;
	}
	pool_scenario scenario;
	std::memset(&scenario, 0, sizeof scenario);
	char message[512] = {0};
	if (pool_scenario_parse(scenario_json, std::strlen(scenario_json), &scenario, message,
	                        sizeof message) != 0) {
		copy_message(message[0] ? message : "scenario: invalid", err, err_size);
		pool_scenario_free(&scenario);
		return nullptr;
	}
	pool_ode::Engine *engine = new (std::nothrow) pool_ode::Engine();
	if (!engine) {
		copy_message("out of memory", err, err_size);
		pool_scenario_free(&scenario);
		return nullptr;
	}
	std::string error;
	bool ok = false;
	try {
		ok = engine->build(scenario, config->dt, &error);
	} catch (const std::exception &e) {
		error = e.what();
	}
	pool_scenario_free(&scenario);
	if (!ok) {
		copy_message(error, err, err_size);
		delete engine;
		return nullptr;
	}
	return engine;
}

pool_ode::Engine *as_engine(void *engine) { return static_cast<pool_ode::Engine *>(engine); }

int ode_advance(void *engine, double t) {
	if (!engine)
		return -1;
	try {
		return as_engine(engine)->advance(t) ? 0 : -1;
	} catch (...) {
		return -1;
	}
}

int ode_run_to_rest(void *engine, double max_time) {
	if (!engine)
		return -1;
	try {
		return as_engine(engine)->run_to_rest(max_time) ? 0 : -1;
	} catch (...) {
		return -1;
	}
}

int ode_balls(void *engine, pool_engine_ball *out, int capacity) {
	if (!engine)
		return -1;
	return as_engine(engine)->balls(out, capacity);
}

int ode_events(void *engine, pool_engine_event *out, int capacity) {
	if (!engine)
		return -1;
	return as_engine(engine)->events(out, capacity);
}

void ode_stats(void *engine, pool_engine_stats *out) {
	if (!out)
		return;
	if (!engine) {
		std::memset(out, 0, sizeof *out);
		return;
	}
	as_engine(engine)->stats(out);
}

const char *ode_last_error(void *engine) {
	if (!engine)
		return "engine: NULL";
	return as_engine(engine)->error().c_str();
}

void ode_destroy(void *engine) { delete as_engine(engine); }

const pool_engine_api kApi = {
	POOL_ENGINE_ABI_VERSION,
	"ode",
	"ODE 0.16 (dWorldStep, fixed dt): spheres, capsule cushions, rolling resistance as a "
	"torque limit; event times quantised to dt",
	0,
	ode_create,
	ode_advance,
	ode_run_to_rest,
	ode_balls,
	ode_events,
	ode_stats,
	ode_last_error,
	ode_destroy,
};

} // namespace

extern "C" __attribute__((visibility("default"))) const pool_engine_api *pool_engine_plugin(void) {
	return &kApi;
}
