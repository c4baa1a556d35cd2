// The plugin ABI (pool_engine_plugin.h) around the ODE model; argument checks, scenario parsing
// and error strings are the shared glue's (common/plugin_glue.h).
#include "ode_engine.h"
#include "plugin_glue.h"

namespace {

const pool_engine_api kApi = pool_plugin::make_api<pool_ode::Engine>(
	"ode",
	"ODE 0.16 (dWorldStep, fixed dt): spheres, capsule cushions, rolling resistance as a "
	"torque limit; event times quantised to dt");

} // namespace

extern "C" __attribute__((visibility("default"))) const pool_engine_api *pool_engine_plugin(void) {
	return &kApi;
}
