// The ODE 0.16 model of a pool shot: one dWorld stepped with dWorldStep, balls as spheres,
// cushions as capsules, the cloth as a contact made by hand for every ball on it.
#ifndef POOL_ODE_ENGINE_H
#define POOL_ODE_ENGINE_H

#include <ode/ode.h>

#include <cstdint>
#include <string>
#include <vector>

#include "engine_state.h"
#include "pool/pool.h"
#include "pool_engine_plugin.h"
#include "pool/scenario.h"
#include "table_geometry.h"

namespace pool_ode {

using pool_plugin::RailSegment;
using pool_plugin::TableGeometry;

/// Tuning of the model; every value is explained where it is set (ode_engine.cpp).
struct Settings {
	double erp;              ///< world ERP: fraction of a penetration corrected per step
	double cfm;              ///< world CFM: constraint compliance (near zero: stiff contacts)
	double capsule_radius;   ///< m, radius of the cushion capsules
	double airborne_capsule_radius; ///< m, the same in airborne mode (thin: the nose line)
	double roll_on_slip;     ///< m/s, slip below which rolling resistance switches on
	double roll_off_slip;    ///< m/s, slip above which it switches off again
	double rest_speed;       ///< m/s, speed (and R |w|) below which a ball is at rest
	double release_gap;      ///< m, gap beyond which a touching pair counts as separated
	double cloth_gap;        ///< m, height above the cloth still counted as on it (airborne mode)
	double settle_speed;     ///< m/s, slowest landing that still bounces (airborne mode)
	double impact_speed;     ///< m/s, approach speed above which a contact is an impact
};

/// The model's default settings.
Settings default_settings();

/// One ball of the world.
struct Ball {
	int32_t id = 0;             ///< scenario id
	dBodyID body = nullptr;     ///< its rigid body
	dGeomID geom = nullptr;     ///< its sphere
	int32_t state = 0;          ///< pool_motion code
	bool active = true;         ///< false once pocketed or off the table
	bool rolling = true;        ///< rolling resistance on (no slip), with hysteresis
	bool moving = false;        ///< translating or sliding (false = at rest or only z-spin)
	bool cloth_contact = false; ///< had a cloth contact in the last step (airborne: landings)
};

/// A pool shot simulated by ODE.
class Engine : public pool_plugin::StepperState {
public:
	// events(), stats(), error() and the members every stepped engine has: StepperState.
	Engine() = default;
	~Engine();
	Engine(const Engine &) = delete;
	Engine &operator=(const Engine &) = delete;

	/// Builds the world from a parsed scenario; false with a message on failure.
	bool build(const pool_scenario &scenario, double dt, std::string *error);
	/// Steps until the simulated time reaches t.
	bool advance(double t);
	/// Steps until every ball is at rest or max_time.
	bool run_to_rest(double max_time);
	/// Ball states as the plugin ABI wants them.
	int balls(pool_engine_ball *out, int capacity) const;

	/// Contact generation for one candidate pair (dSpaceCollide's callback).
	void near(dGeomID g1, dGeomID g2);

private:
	bool step();
	void add_cloth_contact(size_t i);
	void after_step();
	void classify(size_t i, bool report);
	bool all_at_rest() const;
	double now() const { return double(steps_) * dt_; }
	void report(int32_t type, int32_t a, int32_t b, double t);

	Settings settings_{};
	dWorldID world_ = nullptr;
	dSpaceID space_ = nullptr;
	dJointGroupID contacts_ = nullptr;
	std::vector<Ball> balls_;
	std::vector<dGeomID> rails_;
	bool ode_ref_ = false;
};

} // namespace pool_ode

#endif
