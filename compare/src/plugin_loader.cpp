#include "plugin_loader.h"

#include <dirent.h>
#include <dlfcn.h>
#include <sys/stat.h>

#include <algorithm>

namespace pool_compare {

namespace {

bool ends_with(const std::string &s, const std::string &suffix) {
	return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

const char kPrefix[] = "libpool_engine_";
const char kSuffix[] = ".so";

} // namespace

std::string plugin_module_path(const std::string &request, const std::string &plugin_dir) {
	if (request.find('/') != std::string::npos || ends_with(request, kSuffix))
		return request;
	return plugin_dir + "/" + kPrefix + request + kSuffix;
}

bool load_plugin(const std::string &request, const std::string &plugin_dir, Plugin *plugin,
                 std::string *error) {
	const std::string path = plugin_module_path(request, plugin_dir);
	const std::string who = "plugin '" + request + "'";
	struct stat st;
	if (stat(path.c_str(), &st) != 0) {
		*error = who + ": no module " + path +
		         " (not built? pass --plugin-dir DIR, or a path to the .so)";
		return false;
	}
	// A path without '/' would make dlopen search the library path instead of this file.
	const std::string open_path = path.find('/') == std::string::npos ? "./" + path : path;
	void *handle = dlopen(open_path.c_str(), RTLD_NOW | RTLD_LOCAL);
	if (!handle) {
		const char *message = dlerror();
		*error = who + ": cannot load " + path + ": " + (message ? message : "unknown dlopen error");
		return false;
	}
	dlerror();
	void *symbol = dlsym(handle, POOL_ENGINE_ENTRY);
	if (!symbol) {
		*error = who + ": " + path + " does not export the entry symbol " POOL_ENGINE_ENTRY
		         " (not a pool engine plugin?)";
		dlclose(handle);
		return false;
	}
	pool_engine_entry_fn entry;
	static_assert(sizeof entry == sizeof symbol, "function and object pointers differ in size");
	std::copy(reinterpret_cast<const char *>(&symbol), reinterpret_cast<const char *>(&symbol) + sizeof symbol,
	          reinterpret_cast<char *>(&entry));
	const pool_engine_api *api = entry();
	if (!api) {
		*error = who + ": " + path + ": " POOL_ENGINE_ENTRY "() returned NULL";
		dlclose(handle);
		return false;
	}
	if (api->abi_version != POOL_ENGINE_ABI_VERSION) {
		*error = who + ": " + path + " has plugin ABI version " + std::to_string(api->abi_version) +
		         ", this harness needs version " + std::to_string(POOL_ENGINE_ABI_VERSION) +
		         " (rebuild the plugin against compare/include/pool_engine_plugin.h)";
		dlclose(handle);
		return false;
	}
	const char *missing = nullptr;
	if (!api->name || !api->name[0])
		missing = "name";
	else if (!api->create)
		missing = "create";
	else if (!api->advance)
		missing = "advance";
	else if (!api->run_to_rest)
		missing = "run_to_rest";
	else if (!api->balls)
		missing = "balls";
	else if (!api->events)
		missing = "events";
	else if (!api->stats)
		missing = "stats";
	else if (!api->last_error)
		missing = "last_error";
	else if (!api->destroy)
		missing = "destroy";
	if (missing) {
		*error = who + ": " + path + ": the function table has no " + missing;
		dlclose(handle);
		return false;
	}
	plugin->requested = request;
	plugin->path = path;
	plugin->api = api;
	plugin->unsupported_models =
		reinterpret_cast<pool_engine_models_fn>(dlsym(handle, POOL_ENGINE_MODELS_ENTRY));
	plugin->link_stats = reinterpret_cast<pool_engine_link_fn>(dlsym(handle, POOL_ENGINE_LINK_ENTRY));
	return true;
}

std::vector<std::string> available_plugins(const std::string &plugin_dir) {
	std::vector<std::string> names;
	DIR *dir = opendir(plugin_dir.c_str());
	if (!dir)
		return names;
	const std::string prefix = kPrefix;
	while (const dirent *entry = readdir(dir)) {
		const std::string file = entry->d_name;
		if (file.compare(0, prefix.size(), prefix) == 0 && ends_with(file, kSuffix))
			names.push_back(file.substr(prefix.size(), file.size() - prefix.size() - (sizeof kSuffix - 1)));
	}
	closedir(dir);
	std::sort(names.begin(), names.end());
	return names;
}

} // namespace pool_compare
