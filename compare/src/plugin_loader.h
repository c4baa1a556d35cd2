// Loading engine plugins (compare/include/pool_engine_plugin.h) from shared modules, by name
// (<plugin dir>/libpool_engine_<name>.so) or by path, with the ABI checked before use.
#ifndef POOL_COMPARE_PLUGIN_LOADER_H
#define POOL_COMPARE_PLUGIN_LOADER_H

#include <string>
#include <vector>

#include "pool_engine_plugin.h"

namespace pool_compare {

/// A loaded plugin module. Modules stay loaded until the process ends (engines such as Bullet
/// keep static state that must not be unmapped while its destructors may still run).
struct Plugin {
	std::string requested; ///< what the user asked for (name or path)
	std::string path;      ///< the module file
	const pool_engine_api *api = nullptr; ///< the checked function table
	/// The optional POOL_ENGINE_MODELS_ENTRY export; nullptr when the plugin has none.
	pool_engine_models_fn unsupported_models = nullptr;
	/// The optional POOL_ENGINE_LINK_ENTRY export; nullptr when the plugin has none.
	pool_engine_link_fn link_stats = nullptr;
};

/// File a plugin name resolves to; a request containing '/' or ending in ".so" is a path.
std::string plugin_module_path(const std::string &request, const std::string &plugin_dir);

/// Loads and checks one plugin. Returns false with a one-line message in *error naming the
/// plugin, the file and what is wrong (missing file, dlopen failure, missing entry symbol,
/// entry returning NULL, wrong ABI version, incomplete function table).
bool load_plugin(const std::string &request, const std::string &plugin_dir, Plugin *plugin,
                 std::string *error);

/// Names of the plugin modules present in a directory (libpool_engine_<name>.so), sorted.
std::vector<std::string> available_plugins(const std::string &plugin_dir);

} // namespace pool_compare

#endif
