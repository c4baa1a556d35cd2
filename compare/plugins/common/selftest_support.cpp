// Self-test helpers of the engine plugins (see selftest_support.h).
#include "selftest_support.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace pool_plugin {

const pool_engine_api *load_plugin(const char *path, const char *name) {
	void *module = dlopen(path, RTLD_NOW | RTLD_LOCAL);
	if (!module) {
		std::fprintf(stderr, "dlopen: %s\n", dlerror());
		return nullptr;
	}
	auto entry = reinterpret_cast<pool_engine_entry_fn>(dlsym(module, POOL_ENGINE_ENTRY));
	const pool_engine_api *api = entry ? entry() : nullptr;
	if (!api || api->abi_version != POOL_ENGINE_ABI_VERSION ||
	    (name && std::strcmp(api->name, name) != 0) || api->event_driven != 0) {
		std::fprintf(stderr, "bad plugin entry in %s\n", path);
		return nullptr;
	}
	return api;
}

std::string fmt(const char *format, ...) {
	char buffer[4096];
	va_list args;
	va_start(args, format);
	std::vsnprintf(buffer, sizeof buffer, format, args);
	va_end(args);
	return buffer;
}

void petit_impact(const double n[3], double e, double mu, double R, double v[3], double w[3]) {
	const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
	const double nxw[3] = {n[1] * w[2] - n[2] * w[1], n[2] * w[0] - n[0] * w[2],
	                       n[0] * w[1] - n[1] * w[0]};
	double vc[3], vcl = 0.0; // slip of the contact point
	for (int k = 0; k < 3; ++k) {
		vc[k] = v[k] - vn * n[k] + R * nxw[k];
		vcl += vc[k] * vc[k];
	}
	vcl = std::sqrt(vcl);
	const double p = (1.0 + e) * (-vn); // P / m
	// Sliding throughout the impact unless friction stops the slip first.
	const bool slipping = vcl > 0.0 && 1.0 - 3.5 * mu * p / vcl >= 0.0;
	const double nxvc[3] = {n[1] * vc[2] - n[2] * vc[1], n[2] * vc[0] - n[0] * vc[2],
	                        n[0] * vc[1] - n[1] * vc[0]};
	for (int k = 0; k < 3; ++k) {
		if (slipping) {
			v[k] += p * (n[k] - mu * vc[k] / vcl);
			w[k] += 5.0 * mu * p / (2.0 * R) * nxvc[k] / vcl;
		} else {
			v[k] += p * n[k] - 2.0 / 7.0 * vc[k];
			w[k] += 5.0 / (7.0 * R) * nxvc[k];
		}
	}
}

} // namespace pool_plugin
