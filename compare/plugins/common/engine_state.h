// Engine-independent pieces of a time-stepped plugin's state: the rolling-resistance
// hysteresis, event records and the copy-out of a list the ABI asks for.
#ifndef POOL_PLUGIN_ENGINE_STATE_H
#define POOL_PLUGIN_ENGINE_STATE_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pool_engine_plugin.h"

namespace pool_plugin {

/// Rolling resistance acts only while rolling (ENGINES.md): a ball starts rolling when its slip
/// falls below on_slip and stops only when it rises above off_slip again, so rounding near the
/// threshold cannot toggle it. Returns the new rolling flag.
inline bool roll_hysteresis(bool rolling, double slip, double on_slip, double off_slip) {
	if (rolling)
		return !(slip > off_slip);
	return slip < on_slip;
}

/// One event record.
inline pool_engine_event make_event(int32_t type, int32_t a, int32_t b, double t) {
	pool_engine_event e{};
	e.t = t;
	e.type = type;
	e.ball_a = a;
	e.ball_b = b;
	return e;
}

/// The ABI's list convention: writes up to capacity items (none if out is NULL) and returns how
/// many there are.
template <class T> int copy_out(const std::vector<T> &items, T *out, int capacity) {
	const int n = int(std::min<size_t>(items.size(), size_t(INT32_MAX)));
	for (int i = 0; out && i < n && i < capacity; ++i)
		out[i] = items[size_t(i)];
	return n;
}

/// Counters of a time-stepped engine.
inline void fill_stats(int64_t steps, double dt, double max_penetration, pool_engine_stats *out) {
	out->steps = steps;
	out->max_penetration = max_penetration;
	out->sim_time = double(steps) * dt;
}

} // namespace pool_plugin

#endif
