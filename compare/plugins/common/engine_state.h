// Engine-independent pieces of a time-stepped plugin's state: the rolling-resistance
// hysteresis, event records, the copy-out of a list the ABI asks for, and the members and
// accessors every time-stepped engine has (StepperState).
#ifndef POOL_PLUGIN_ENGINE_STATE_H
#define POOL_PLUGIN_ENGINE_STATE_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "contact_tracker.h"
#include "pool/pool.h"
#include "pool_engine_plugin.h"
#include "table_geometry.h"

namespace pool_plugin {

/// Rolling resistance acts only while rolling (docs/engines.md): a ball starts rolling when its slip
/// falls below on_slip and stops only when it rises above off_slip again, so rounding near the
/// threshold cannot toggle it. Returns the new rolling flag.
inline bool roll_hysteresis(bool rolling, double slip, double on_slip, double off_slip) {
	if (rolling)
		return !(slip > off_slip);
	return slip < on_slip;
}

/// Settling rule of airborne mode, the same as the harness's closed form (kSettleFlightTime in
/// compare/src/reference.h) and libpool's: a rebound that would fly less than this (2 v_z' / g)
/// settles on the cloth instead.
constexpr double kSettleFlightTime = 1e-3;

/// The slowest landing (approach speed, m/s) that still bounces under that rule: its rebound
/// e_table v flies 2 e_table v / g >= kSettleFlightTime. Infinite for e_table = 0 (never bounces).
inline double settle_landing_speed(const pool_params &p) {
	return p.e_table > 0.0 ? p.g * kSettleFlightTime / (2.0 * p.e_table) : HUGE_VAL;
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

/// What a time-stepped engine keeps besides its own world (the ODE and Bullet engines derive
/// from it): parameters, table, contact bookkeeping, the event record and the counters, with
/// the ABI's accessors for them.
class StepperState {
public:
	/// Events so far.
	int events(pool_engine_event *out, int capacity) const { return copy_out(events_, out, capacity); }
	/// Counters.
	void stats(pool_engine_stats *out) const { fill_stats(steps_, dt_, max_penetration_, out); }
	/// Message of the last failure.
	const std::string &error() const { return error_; }

protected:
	StepperState() = default;
	~StepperState() = default; // not deleted through this base

	pool_params params_{};
	bool airborne_ = false;
	double dt_ = 1e-3;
	TableGeometry table_;
	ContactTracker ball_contacts_;          ///< ball pairs (i < j) in contact
	ContactTracker rail_contacts_;          ///< (ball, segment) pairs in contact
	std::vector<uint8_t> impact_;           ///< per ball: hits a ball or cushion in this step
	std::vector<pool_engine_event> events_; ///< events so far, in time order
	int64_t steps_ = 0;
	double max_penetration_ = 0.0;
	std::string error_;
};

} // namespace pool_plugin

#endif
