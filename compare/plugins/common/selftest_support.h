// Helpers of the engine plugins' self-tests and benchmarks, which drive a built module through
// its C ABI: loading it, formatting scenario documents, and closed forms both tests check.
#ifndef POOL_PLUGIN_SELFTEST_SUPPORT_H
#define POOL_PLUGIN_SELFTEST_SUPPORT_H

#include <string>

#include "pool_engine_plugin.h"

namespace pool_plugin {

/// Loads a plugin module and returns its function table, or NULL with a message on stderr when
/// the module cannot be opened or is not a time-stepped plugin called `name` (any name if NULL)
/// of this ABI version. The module stays loaded (engines may keep static state).
const pool_engine_api *load_plugin(const char *path, const char *name);

/// printf into a std::string (scenario documents, check labels).
std::string fmt(const char *format, ...) __attribute__((format(printf, 1, 2)));

/// Petit's impulse law (docs/physics.md) for a ball of radius R hitting an immovable obstacle whose
/// unit normal n points from the contact towards the ball centre, restitution e and friction
/// mu: v and w become the velocities after the impact (no v_z is dropped here).
void petit_impact(const double n[3], double e, double mu, double R, double v[3], double w[3]);

} // namespace pool_plugin

#endif
