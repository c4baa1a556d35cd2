// The plugin ABI (compare/include/pool_engine_plugin.h) around pool_bullet::Engine; argument
// checks, scenario parsing and catching everything at every entry point are the shared glue's
// (common/plugin_glue.h): a plugin must never take the harness down.
#include "bullet_engine.h"
#include "plugin_glue.h"

namespace {

const pool_engine_api kApi = pool_plugin::make_api<pool_bullet::Engine>(
    "bullet",
    "Bullet 3.24 double precision, btDiscreteDynamicsWorld, fixed dt, sequential impulse with "
    "split impulse; rolling and spin resistance as applied torques; cannot model: cushion hits "
    "without cloth friction, hops from cushion impulses, exact contact times (found after overlap, "
    "landings too), line cushions for a flying ball (0.1 mm capsules in airborne mode), the "
    "optional models (mathavan2010 cushions, alciatore throw, endmass squirt)");

} // namespace

extern "C" __attribute__((visibility("default"))) const pool_engine_api *pool_engine_plugin(void) {
	return &kApi;
}

// The optional models (docs/physics.md "Models") are not in this engine: a scenario that
// selects one runs with the engine's own laws, and the harness records which it lacked.
extern "C" __attribute__((visibility("default"))) int pool_engine_unsupported_models(
	const char *scenario_json, char *out, size_t out_size) {
	return pool_plugin::default_models_only(scenario_json, out, out_size);
}
