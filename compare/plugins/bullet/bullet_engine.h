// The Bullet 3.24 (double precision) model of a pool shot: one btDiscreteDynamicsWorld stepped
// at a fixed dt, balls as spheres, the cloth as a static plane, cushion noses as static capsules,
// rolling resistance and spin friction as torques applied by hand (Bullet's own are box-shaped).
#ifndef POOL_BULLET_ENGINE_H
#define POOL_BULLET_ENGINE_H

#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine_state.h"
#include "sphere_overlap.h"
#include "pool/pool.h"
#include "pool_engine_plugin.h"
#include "pool/scenario.h"
#include "table_geometry.h"

static_assert(sizeof(btScalar) == sizeof(double),
              "the Bullet plugin needs BT_USE_DOUBLE_PRECISION (pkg-config bullet-float64)");

namespace pool_bullet {

using pool_plugin::RailSegment;
using pool_plugin::TableGeometry;

/// Tuning of the model; every value is explained where it is set (bullet_engine.cpp).
struct Settings {
	double capsule_radius;     ///< m, radius of the cushion capsules
	double airborne_capsule_radius; ///< m, the same in airborne mode (thin: the nose line)
	double breaking_threshold; ///< m, contact breaking threshold of every manifold
	double roll_on_slip;       ///< m/s, slip below which rolling resistance switches on
	double roll_off_slip;      ///< m/s, slip above which it switches off again
	double rest_speed;         ///< m/s, speed (and R |w_perp|) below which a ball stops translating
	double rest_spin;          ///< rad/s, |w_z| below which a stopped ball is stationary
	double release_gap;        ///< m, gap beyond which a touching pair counts as separated
	double cloth_gap;          ///< m, height above z = R still counted as on the cloth (airborne mode)
	double impact_speed;       ///< m/s, vertical speed above which a cloth contact is a landing (airborne mode)
	double settle_speed;       ///< m/s, slowest landing that still bounces (airborne mode; per scenario)
	int solver_iterations;     ///< sequential-impulse iterations per step
};

/// The model's default settings.
Settings default_settings();

class Engine;

/// What a collision object is; its user pointer points to one of these, so the combined
/// coefficient hooks can give every pair libpool's value.
struct Material {
	uint32_t magic;       ///< kMaterialMagic: marks our user pointers
	int kind;             ///< 0 ball, 1 cloth, 2 cushion
	int index;            ///< ball or segment index
	const Engine *engine; ///< owner (several engines may coexist)
};

/// One ball of the world.
struct Ball {
	int32_t id = 0;                    ///< scenario id
	std::unique_ptr<btRigidBody> body; ///< its rigid body
	Material material{};               ///< its user pointer target
	int32_t state = 0;                 ///< pool_motion code
	bool active = true;                ///< false once pocketed or off the table
	bool rolling = false;              ///< rolling resistance on (no slip), with hysteresis
	bool cloth_contact = false;        ///< touched the cloth in the last step (airborne mode: landings)
	pool_engine_ball last{};           ///< state when it left the table (pocketed / off table)
};

/// A pool shot simulated by Bullet.
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

	/// Friction of a pair of our objects (libpool's mu of that pair).
	double pair_friction(const Material &a, const Material &b) const;
	/// Restitution of a pair of our objects (libpool's e of that pair; 0 on the cloth in planar mode).
	double pair_restitution(const Material &a, const Material &b) const;
	/// Called by the world between collision detection and the solver of every step.
	void before_solve();

private:
	bool step();
	void apply_torques();
	bool after_step();
	void update_contacts(double t_detect);
	void landings();
	void measure_penetration();
	void classify(Ball &ball, bool report, double t);
	bool on_cloth(const Ball &ball) const;
	bool all_at_rest() const;
	void remove_ball(Ball &ball, int32_t state);
	void snapshot(const Ball &ball, pool_engine_ball *out) const;
	void report(int32_t type, int32_t a, int32_t b, double t);

	Settings settings_{};

	// Bullet objects, created in build() and torn down in the destructor in reverse order.
	std::unique_ptr<btDefaultCollisionConfiguration> config_;
	std::unique_ptr<btCollisionDispatcher> dispatcher_;
	std::unique_ptr<btBroadphaseInterface> broadphase_;
	std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
	std::unique_ptr<btDiscreteDynamicsWorld> world_;
	std::unique_ptr<btSphereShape> sphere_;
	std::unique_ptr<btStaticPlaneShape> cloth_shape_;
	std::unique_ptr<btRigidBody> cloth_;
	Material cloth_material_{};
	std::vector<std::unique_ptr<btCollisionShape>> rail_shapes_;
	std::vector<std::unique_ptr<btRigidBody>> rails_;
	std::vector<Material> rail_materials_;
	std::vector<std::unique_ptr<Ball>> balls_;
	std::vector<pool_engine_event> pending_; ///< this step's events, sorted before publishing
	pool_plugin::SphereOverlap overlap_;     ///< the deepest ball-ball overlap of a step
	std::vector<std::array<double, 3>> centres_; ///< active balls' centres, reused every step
};

} // namespace pool_bullet

#endif
