// The plugin ABI (compare/include/pool_engine_plugin.h) around pool_bullet::Engine. Every entry
// point catches everything: a plugin must never take the harness down.
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "bullet_engine.h"

namespace {

using pool_bullet::Engine;

void set_error(char *err, size_t size, const char *message) {
	if (err && size > 0)
		std::snprintf(err, size, "%s", message);
}

void *bullet_create(const char *json, const pool_engine_config *config, char *err, size_t err_size) {
	try {
		if (!json) {
			set_error(err, err_size, "scenario: missing document");
			return nullptr;
		}
		if (!config) {
			set_error(err, err_size, "config: missing");
			return nullptr;
		}
		pool_scenario scenario{};
		char message[512] = {0};
		if (pool_scenario_parse(json, std::strlen(json), &scenario, message, sizeof message) != 0) {
			set_error(err, err_size, message[0] ? message : "scenario: invalid");
			return nullptr;
		}
		auto *engine = new (std::nothrow) Engine();
		std::string error;
		const bool ok = engine && engine->build(scenario, config->dt, &error);
		pool_scenario_free(&scenario);
		if (!ok) {
			set_error(err, err_size, engine ? error.c_str() : "out of memory");
			delete engine;
			return nullptr;
		}
		return engine;
	} catch (const std::exception &e) {
		set_error(err, err_size, e.what());
	} catch (...) {
		set_error(err, err_size, "bullet: unknown failure while building the world");
	}
	return nullptr;
}

int bullet_advance(void *engine, double t) {
	if (!engine)
		return -1;
	try {
		return static_cast<Engine *>(engine)->advance(t) ? 0 : -1;
	} catch (...) {
		return -1;
	}
}

int bullet_run_to_rest(void *engine, double max_time) {
	if (!engine)
		return -1;
	try {
		return static_cast<Engine *>(engine)->run_to_rest(max_time) ? 0 : -1;
	} catch (...) {
		return -1;
	}
}

int bullet_balls(void *engine, pool_engine_ball *out, int capacity) {
	return engine ? static_cast<Engine *>(engine)->balls(out, capacity) : -1;
}

int bullet_events(void *engine, pool_engine_event *out, int capacity) {
	return engine ? static_cast<Engine *>(engine)->events(out, capacity) : -1;
}

void bullet_stats(void *engine, pool_engine_stats *out) {
	if (!out)
		return;
	if (!engine) {
		*out = pool_engine_stats{};
		return;
	}
	static_cast<Engine *>(engine)->stats(out);
}

const char *bullet_last_error(void *engine) {
	if (!engine)
		return "no engine";
	return static_cast<Engine *>(engine)->error().c_str();
}

void bullet_destroy(void *engine) {
	delete static_cast<Engine *>(engine);
}

const pool_engine_api bullet_api = {
    POOL_ENGINE_ABI_VERSION,
    "bullet",
    "Bullet 3.24 double precision, btDiscreteDynamicsWorld, fixed dt, sequential impulse with "
    "split impulse; rolling and spin resistance as applied torques; cannot model: cushion hits "
    "without cloth friction, hops from cushion impulses, exact contact times (found after overlap)",
    0,
    bullet_create,
    bullet_advance,
    bullet_run_to_rest,
    bullet_balls,
    bullet_events,
    bullet_stats,
    bullet_last_error,
    bullet_destroy,
};

} // namespace

extern "C" __attribute__((visibility("default"))) const pool_engine_api *pool_engine_plugin(void) {
	return &bullet_api;
}
