// The plugin ABI (pool_engine_plugin.h) around the ODE model; argument checks, scenario parsing
// and error strings are the shared glue's (common/plugin_glue.h).
#include "ode_engine.h"
#include "plugin_glue.h"

namespace {

const pool_engine_api kApi = pool_plugin::make_api<pool_ode::Engine>(
	"ode",
	"ODE 0.16 (dWorldStep, fixed dt): spheres, capsule cushions, rolling resistance as a "
	"torque limit; cannot express: event times finer than dt (contacts found after overlap, "
	"semi-implicit Euler), simultaneous contacts in sequence (one LCP solves them together), "
	"Coulomb's cone for several contacts on a ball (friction box), libpool's closed-form rolling and "
	"spin decelerations (torque limits), line cushions for a flying ball (capsules, 0.1 mm thin in "
	"airborne mode; rounded jaws), "
	"hits above v*dt ~ R + rc = 5.7 cm (tunnelling), "
	"the optional models (mathavan2010 cushions, alciatore throw, endmass squirt)");

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
