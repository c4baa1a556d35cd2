// What the harness's C++ tests share: CHECK (counts a failure and says where), the scenario
// folder and loading from it, and the closing line.
#ifndef POOL_COMPARE_TEST_H
#define POOL_COMPARE_TEST_H

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "plugin_loader.h"
#include "scenario_file.h"

namespace compare_test {

inline int failures = 0;
inline std::string scenario_dir; ///< set by main from the command line

#define CHECK(cond, ...)                                                                                   \
	do {                                                                                                   \
		if (!(cond)) {                                                                                     \
			++compare_test::failures;                                                                      \
			std::printf("FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                    \
			std::printf(__VA_ARGS__);                                                                      \
			std::printf("\n");                                                                             \
		}                                                                                                  \
	} while (0)

/// scenario_dir/NAME.json, or a counted failure and NULL.
inline std::unique_ptr<pool_compare::Scenario> load(const std::string &name) {
	std::unique_ptr<pool_compare::Scenario> s;
	std::string error;
	if (!pool_compare::load_scenario(scenario_dir + "/" + name + ".json", &s, &error)) {
		std::printf("FAIL cannot load %s: %s\n", name.c_str(), error.c_str());
		++failures;
	}
	return s;
}

/// A scenario from JSON text, or a counted failure and NULL.
inline std::unique_ptr<pool_compare::Scenario> from_text(const std::string &name, const std::string &json) {
	std::unique_ptr<pool_compare::Scenario> s;
	std::string error;
	if (!pool_compare::parse_scenario(name, json, &s, &error)) {
		std::printf("FAIL cannot parse %s: %s\n", name.c_str(), error.c_str());
		++failures;
	}
	return s;
}

/// The engines named on the command line (argv[first..argc)), looked up in plugin_dir; each that
/// does not load is a counted failure (an engine of the build must be there).
inline std::vector<pool_compare::Plugin> load_plugins(int argc, char **argv, int first, const char *plugin_dir) {
	std::vector<pool_compare::Plugin> plugins;
	for (int i = first; i < argc; ++i) {
		pool_compare::Plugin plugin;
		std::string error;
		CHECK(pool_compare::load_plugin(argv[i], plugin_dir, &plugin, &error), "expected engine missing: %s",
		      error.c_str());
		if (plugin.api)
			plugins.push_back(plugin);
	}
	return plugins;
}

/// Prints the closing line; the exit status.
inline int finish() {
	std::printf("%s (%d failures)\n", failures ? "FAILED" : "passed", failures);
	return failures ? 1 : 0;
}

} // namespace compare_test

#endif
