// The Bullet model of a pool shot (see bullet_engine.h and docs/engines.md for the traps).
#include "bullet_engine.h"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "engine_state.h"

namespace pool_bullet {
namespace {

constexpr uint32_t kMaterialMagic = 0x706f6f6cu; // "pool"
constexpr int kBall = 0, kCloth = 1, kCushion = 2;

const Material *material_of(const btCollisionObject *object) {
	const auto *m = static_cast<const Material *>(object ? object->getUserPointer() : nullptr);
	return m && m->magic == kMaterialMagic ? m : nullptr;
}

// Bullet combines per-object coefficients (friction f0 f1, restitution e0 e1, rolling
// r0 f1 + r1 f0). Pool needs a value per pair of materials, so the hooks look the pair up in
// the owning engine; objects that are not ours keep Bullet's default rule.
btScalar combined_friction(const btCollisionObject *a, const btCollisionObject *b) {
	const Material *ma = material_of(a), *mb = material_of(b);
	if (ma && mb && ma->engine == mb->engine)
		return ma->engine->pair_friction(*ma, *mb);
	return std::clamp(a->getFriction() * b->getFriction(), btScalar(-10), btScalar(10));
}

btScalar combined_restitution(const btCollisionObject *a, const btCollisionObject *b) {
	const Material *ma = material_of(a), *mb = material_of(b);
	if (ma && mb && ma->engine == mb->engine)
		return ma->engine->pair_restitution(*ma, *mb);
	return a->getRestitution() * b->getRestitution();
}

// Bullet's rolling and spinning friction are replaced by torques (apply_torques): keep them off.
btScalar combined_rolling(const btCollisionObject *a, const btCollisionObject *b) {
	if (material_of(a) && material_of(b))
		return 0.0;
	return a->getRollingFriction() * b->getFriction() + b->getRollingFriction() * a->getFriction();
}

btScalar combined_spinning(const btCollisionObject *a, const btCollisionObject *b) {
	if (material_of(a) && material_of(b))
		return 0.0;
	return a->getSpinningFriction() * b->getFriction() + b->getSpinningFriction() * a->getFriction();
}

void install_hooks() {
	static std::once_flag once;
	std::call_once(once, [] {
		gCalculateCombinedFrictionCallback = combined_friction;
		gCalculateCombinedRestitutionCallback = combined_restitution;
		gCalculateCombinedRollingFrictionCallback = combined_rolling;
		gCalculateCombinedSpinningFrictionCallback = combined_spinning;
	});
}

// Every manifold gets a tiny contact breaking threshold. Bullet's default (2 % of the sphere's
// size, 0.57 mm here) keeps contact points that are still apart; the solver treats those as
// speculative contacts whose target velocity is e v - gap / dt, so a cushion hit found with a
// gap loses up to gap / dt of its rebound, and stale points of a rolling ball linger in the
// cloth manifold. With a threshold of 1e-9 m only touching points exist.
class Dispatcher : public btCollisionDispatcher {
public:
	Dispatcher(btCollisionConfiguration *config, btScalar threshold)
	    : btCollisionDispatcher(config), threshold_(threshold) {}
	btPersistentManifold *getNewManifold(const btCollisionObject *b0,
	                                     const btCollisionObject *b1) override {
		btPersistentManifold *m = btCollisionDispatcher::getNewManifold(b0, b1);
		if (m)
			m->setContactBreakingThreshold(threshold_);
		return m;
	}

private:
	btScalar threshold_;
};

// The dynamics world with one hook: Engine::before_solve runs once the step's contacts are known
// and before they are solved.
class World : public btDiscreteDynamicsWorld {
public:
	World(btDispatcher *dispatcher, btBroadphaseInterface *broadphase, btConstraintSolver *solver,
	      btCollisionConfiguration *config, Engine *engine)
	    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, config), engine_(engine) {}
	void solveConstraints(btContactSolverInfo &info) override {
		engine_->before_solve();
		btDiscreteDynamicsWorld::solveConstraints(info);
	}

private:
	Engine *engine_;
};

double horizontal_slip(const btVector3 &v, const btVector3 &w, double R) {
	// u = v + R k x w, k x w = (-w_y, w_x, 0)
	return std::hypot(v.x() - R * w.y(), v.y() + R * w.x());
}

} // namespace

Settings default_settings() {
	Settings s{};
	// Any rc works for a ball on the cloth (the axis is placed so the contact point and normal
	// are libpool's); half a ball radius keeps the rounded ends at the mouths small.
	s.capsule_radius = 0.5 * 0.028575;
	// Airborne mode: libpool's cushion is the nose line for a flying ball too. A capsule placed
	// to touch a ball on the cloth exactly gives a flying ball at another height another contact
	// point and normal (a dt-independent error: the cushion hop ended 3 cm from libpool at every
	// dt down to 1e-5 with rc = R/2); a 0.1 mm capsule is the line to 0.1 mm (4.8 mm at dt
	// 1e-5, shrinking with dt).
	s.airborne_capsule_radius = 1e-4;
	s.breaking_threshold = 1e-9;
	// docs/engines.md: on below 1e-4 m/s, off above 1e-2 m/s. Bullet's friction brings the slip to
	// zero within the step that ends sliding, so 1e-4 sees the transition at once.
	s.roll_on_slip = 1e-4;
	s.roll_off_slip = 1e-2;
	// The rolling torque is clamped so the last step lands on zero speed; these only absorb
	// rounding and the residue of collisions.
	s.rest_speed = 1e-5;
	s.rest_spin = 1e-4;
	s.release_gap = 1e-6;
	s.cloth_gap = 1e-5;
	// Airborne mode: a cloth contact whose ball moves down faster than 0.1 mm/s is a landing
	// (an impact: Petit's law with e_table and mu_table); landings too slow for the rebound to
	// fly pool_plugin::kSettleFlightTime (1 ms) settle (restitution 0): the harness's closed
	// form and libpool's rule. settle_speed is set per scenario in build() (9.81 mm/s at the
	// defaults).
	s.impact_speed = 1e-4;
	s.settle_speed = 0.0;
	s.solver_iterations = 10;
	return s;
}

Engine::~Engine() {
	// Bodies must leave the world before it goes; the world needs its broadphase and
	// dispatcher while it does so.
	if (world_) {
		for (auto &b : balls_)
			if (b->body && b->body->isInWorld())
				world_->removeRigidBody(b->body.get());
		for (auto &r : rails_)
			world_->removeRigidBody(r.get());
		if (cloth_)
			world_->removeRigidBody(cloth_.get());
	}
	world_.reset();
	solver_.reset();
	broadphase_.reset();
	dispatcher_.reset();
	config_.reset();
}

double Engine::pair_friction(const Material &a, const Material &b) const {
	const int k0 = std::min(a.kind, b.kind), k1 = std::max(a.kind, b.kind);
	if (k0 != kBall)
		return 0.0;
	if (k1 == kBall)
		return params_.mu_ball;
	if (k1 == kCloth)
		return params_.mu_slide;
	return params_.mu_cushion;
}

double Engine::pair_restitution(const Material &a, const Material &b) const {
	const int k0 = std::min(a.kind, b.kind), k1 = std::max(a.kind, b.kind);
	if (k0 != kBall)
		return 0.0;
	if (k1 == kBall)
		return params_.e_ball;
	if (k1 == kCloth)
		return airborne_ ? params_.e_table : 0.0;
	return params_.e_cushion;
}

bool Engine::build(const pool_scenario &scenario, double dt, std::string *error) {
	if (!(std::isfinite(dt) && dt >= 1e-7 && dt <= 0.1)) {
		*error = "config.dt: must be in [1e-7, 0.1] s";
		return false;
	}
	if (scenario.ball_count < 0 || (scenario.ball_count > 0 && !scenario.balls)) {
		*error = "balls: invalid ball array";
		return false;
	}
	settings_ = default_settings();
	params_ = scenario.def.params;
	airborne_ = scenario.def.airborne;
	settings_.settle_speed = pool_plugin::settle_landing_speed(params_);
	dt_ = dt;
	const double R = params_.ball_radius, m = params_.ball_mass;
	settings_.capsule_radius = airborne_ ? settings_.airborne_capsule_radius : 0.5 * R;
	if (!(std::isfinite(m) && m > 0.0)) {
		*error = "params.ball_mass: must be > 0";
		return false;
	}
	const pool_table_def &table = scenario.def.table;
	const double h = table.cushion_height;
	if (!(std::isfinite(R) && R > 0.0)) {
		*error = "params.ball_radius: must be > 0";
		return false;
	}
	if (!(std::isfinite(h) && h > 0.0 && h < 2.0 * R)) {
		*error = "table.cushion_height: the Bullet model needs 0 < h < 2R (a nose a ball on the "
		         "cloth can touch)";
		return false;
	}
	if (!(std::isfinite(table.length) && std::isfinite(table.width) && table.length > 2.0 * R &&
	      table.width > 2.0 * R)) {
		*error = "table.length: the table must be larger than a ball";
		return false;
	}
	// A capsule shorter than a micrometre is no cushion (the mouths meet there); a closed side
	// pocket leaves one capsule along the whole long rail.
	table_ = pool_plugin::make_table_geometry(table, R, {settings_.capsule_radius, 1e-6, false});
	install_hooks();

	config_ = std::make_unique<btDefaultCollisionConfiguration>();
	dispatcher_ = std::make_unique<Dispatcher>(config_.get(), settings_.breaking_threshold);
	broadphase_ = std::make_unique<btDbvtBroadphase>();
	solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
	world_ = std::make_unique<World>(dispatcher_.get(), broadphase_.get(), solver_.get(),
	                                 config_.get(), this);
	world_->setGravity(btVector3(0, 0, -params_.g));
	world_->setForceUpdateAllAabbs(false); // the cloth and cushions never move
	btContactSolverInfo &info = world_->getSolverInfo();
	info.m_numIterations = settings_.solver_iterations;
	// Penetration is removed by split impulse (pseudo-velocities that move positions but never
	// add kinetic energy) at every depth: with the default threshold (-0.04 m) shallow
	// penetrations are pushed out through the real velocity, and a 10 m/s head-on hit with
	// e = 1 gave the object ball up to 0.95 m/s extra (docs/engines.md).
	info.m_splitImpulse = 1;
	info.m_splitImpulsePenetrationThreshold = 0.0;
	// Restitution at every approach speed (the default 0.2 m/s kills slow kisses). A ball
	// resting on the cloth never bounces: Bullet's restitution uses the velocity before
	// gravity's impulse of the step, which is 0 there.
	info.m_restitutionVelocityThreshold = 0.0;
	// Two friction directions per contact. With Bullet's default single direction, a contact
	// without slip (a rolling ball, a ball at rest) gets a world-axis direction from
	// btPlaneSpace1 and no friction at all across it: the rolling torque then spun the ball
	// instead of slowing it (it never stopped), a 30-degree roll drifted to 27.6 degrees, and an
	// object ball at rest felt no cloth friction in the impact step (the cue ball's did, and the
	// e = 1 impact handed that impulse on: +0.05 % energy). The second direction is orthogonal to
	// the slip, so a sliding ball's friction stays a disc (mu N along the slip), not a box.
	info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;

	// The cloth: a static plane with its top at z = 0.
	cloth_shape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0.0);
	{
		btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, cloth_shape_.get());
		cloth_ = std::make_unique<btRigidBody>(ci);
		cloth_material_ = Material{kMaterialMagic, kCloth, 0, this};
		cloth_->setUserPointer(&cloth_material_);
		world_->addRigidBody(cloth_.get());
	}

	// The cushions: one static capsule per stretch of rail between pockets.
	rail_materials_.resize(table_.segments.size());
	for (size_t i = 0; i < table_.segments.size(); ++i) {
		const RailSegment &s = table_.segments[i];
		const bool along_x = s.a[1] == s.b[1] && s.a[2] == s.b[2];
		const bool along_y = s.a[0] == s.b[0] && s.a[2] == s.b[2];
		const btVector3 axis(s.b[0] - s.a[0], s.b[1] - s.a[1], s.b[2] - s.a[2]);
		const double len = axis.length();
		std::unique_ptr<btCollisionShape> shape;
		btTransform tr;
		tr.setIdentity();
		if (along_x) {
			shape = std::make_unique<btCapsuleShapeX>(s.radius, len);
		} else if (along_y) {
			shape = std::make_unique<btCapsuleShape>(s.radius, len); // along y
		} else {
			// A facing, a chord of a jaw or a jaw's vertical capsule (pockets "jaws"): the x
			// capsule turned onto the segment's axis.
			shape = std::make_unique<btCapsuleShapeX>(s.radius, len);
			const btVector3 x(1.0, 0.0, 0.0), u = axis / len, turn = x.cross(u);
			if (turn.length() > 1e-12)
				tr.setRotation(btQuaternion(turn.normalized(), std::acos(std::clamp(u.x(), -1.0, 1.0))));
			else if (u.x() < 0.0)
				tr.setRotation(btQuaternion(btVector3(0.0, 0.0, 1.0), SIMD_PI));
		}
		tr.setOrigin(btVector3(0.5 * (s.a[0] + s.b[0]), 0.5 * (s.a[1] + s.b[1]), 0.5 * (s.a[2] + s.b[2])));
		btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, shape.get());
		ci.m_startWorldTransform = tr;
		auto body = std::make_unique<btRigidBody>(ci);
		rail_materials_[i] = Material{kMaterialMagic, kCushion, int(i), this};
		body->setUserPointer(&rail_materials_[i]);
		world_->addRigidBody(body.get());
		rail_shapes_.push_back(std::move(shape));
		rails_.push_back(std::move(body));
	}

	// The balls.
	sphere_ = std::make_unique<btSphereShape>(R);
	btVector3 inertia(0, 0, 0);
	sphere_->calculateLocalInertia(m, inertia); // (2/5) m R^2
	pool_vec3 strike_v{0, 0, 0}, strike_w{0, 0, 0};
	if (scenario.has_strike) {
		pool_error e{};
		if (pool_strike_velocities(&params_, &scenario.strike, &strike_v, &strike_w, &e) != POOL_OK) {
			*error = e.message[0] ? e.message : "strike: invalid";
			return false;
		}
		if (!airborne_)
			strike_v.z = 0.0; // planar mode drops the vertical component, as libpool does
	}
	const int n = scenario.ball_count;
	balls_.reserve(size_t(n));
	for (int i = 0; i < n; ++i) {
		const pool_ball_state &s = scenario.balls[i];
		auto ball = std::make_unique<Ball>();
		ball->id = s.id;
		pool_vec3 v = s.vel, w = s.omega;
		if (scenario.has_strike && s.id == scenario.strike_ball) {
			v = strike_v;
			w = strike_w;
		}
		if (!airborne_)
			v.z = 0.0;
		btRigidBody::btRigidBodyConstructionInfo ci(m, nullptr, sphere_.get(), inertia);
		ci.m_startWorldTransform.setIdentity();
		ci.m_startWorldTransform.setOrigin(btVector3(s.pos.x, s.pos.y, s.pos.z));
		ci.m_linearDamping = 0.0;
		ci.m_angularDamping = 0.0;
		ci.m_friction = 1.0;     // replaced by the hooks
		ci.m_restitution = 1.0;  // replaced by the hooks
		ci.m_rollingFriction = 0.0;
		ci.m_spinningFriction = 0.0;
		ball->body = std::make_unique<btRigidBody>(ci);
		btRigidBody *body = ball->body.get();
		body->setLinearVelocity(btVector3(v.x, v.y, v.z));
		body->setAngularVelocity(btVector3(w.x, w.y, w.z));
		// Sleeping would freeze slow balls (thresholds 0.8 m/s and 1 rad/s by default).
		body->setActivationState(DISABLE_DEACTIVATION);
		body->setSleepingThresholds(0.0, 0.0);
		// A sphere's inertia is isotropic: the gyroscopic term is zero, skip its solve.
		body->setFlags(body->getFlags() & ~BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
		// CCD stays off (motion threshold 0): with it, restitution came out wrong (docs/engines.md).
		body->setCcdMotionThreshold(0.0);
		ball->material = Material{kMaterialMagic, kBall, i, this};
		body->setUserPointer(&ball->material);
		world_->addRigidBody(body);
		balls_.push_back(std::move(ball));
	}

	const size_t ns = table_.segments.size();
	impact_.assign(size_t(n), 0);
	// Pairs that already touch at t = 0 (frozen racks) are in contact, not new contacts.
	const double touch = 2.0 * R;
	for (int i = 0; i < n; ++i) {
		const btVector3 pi = balls_[size_t(i)]->body->getCenterOfMassPosition();
		for (int j = i + 1; j < n; ++j)
			if ((pi - balls_[size_t(j)]->body->getCenterOfMassPosition()).length() <= touch)
				ball_contacts_.set_touching(size_t(i), size_t(j));
		const double p[3] = {pi.x(), pi.y(), pi.z()};
		for (size_t k = 0; k < ns; ++k)
			if (pool_plugin::distance_to_axis(table_.segments[k], p) <=
			    R + table_.segments[k].radius + settings_.release_gap)
				rail_contacts_.set_touching(size_t(i), k);
	}
	for (auto &b : balls_)
		classify(*b, false, 0.0);
	measure_penetration();
	return true;
}

bool Engine::on_cloth(const Ball &ball) const {
	if (!airborne_)
		return true;
	return ball.body->getCenterOfMassPosition().z() - params_.ball_radius < settings_.cloth_gap;
}

void Engine::apply_torques() {
	const double R = params_.ball_radius, m = params_.ball_mass, g = params_.g;
	const double roll_decel = params_.mu_roll * g;
	const double spin_decel = 2.5 * params_.mu_spin * g / R; // rad/s^2, docs/physics.md
	const double inertia = 0.4 * m * R * R;
	for (auto &b : balls_) {
		if (!b->active || !on_cloth(*b))
			continue;
		// A landing is an impact: no rolling resistance or spin friction in it (libpool's has none).
		if (airborne_ && std::fabs(b->body->getLinearVelocity().z()) > settings_.impact_speed)
			continue;
		btRigidBody *body = b->body.get();
		const btVector3 v = body->getLinearVelocity(), w = body->getAngularVelocity();
		btVector3 torque(0, 0, 0);
		if (b->rolling && roll_decel > 0.0) {
			// Rolling resistance as a torque against the rolling rotation k x v / R: with the
			// cloth's friction holding the no-slip constraint, a torque tau decelerates the ball
			// by 5 tau / (7 m R), so tau = 1.4 mu_roll m g R gives mu_roll g. Scaled down in the
			// last step so the ball stops at zero instead of reversing.
			const double s = std::hypot(v.x(), v.y());
			if (s > 0.0) {
				const double scale = std::min(1.0, s / (roll_decel * dt_));
				const double tau = 1.4 * params_.mu_roll * m * g * R * scale;
				torque += btVector3(tau * v.y() / s, -tau * v.x() / s, 0.0);
			}
		}
		// Spin friction about z (Bullet's spinning friction needs rolling friction, issue 4188):
		// w_z decays at 5 mu_spin g / (2R), clamped at zero.
		const double wz = w.z();
		if (wz != 0.0 && spin_decel > 0.0) {
			const double scale = std::min(1.0, std::fabs(wz) / (spin_decel * dt_));
			torque.setZ(torque.z() - std::copysign(inertia * spin_decel * scale, wz));
		}
		// The torque's impulse goes straight into the angular velocity, before the step, instead
		// of through applyTorque: Bullet's friction rows measure the slip from the angular
		// velocity without the external torque impulse (setupFrictionConstraintInternal), so
		// with applyTorque the cloth corrected the torque's slip only one step later, the ball
		// kept a 3.4e-4 m/s slip and, near the stop, rocked back and forth forever. Applied here,
		// the cloth's friction sees it in the same step and v, w stay rolling exactly.
		if (!torque.isZero())
			body->setAngularVelocity(w + body->getInvInertiaTensorWorld() * torque * dt_);
	}
}

bool Engine::step() {
	apply_torques();
	// One fresh contact point per touching pair and step, as libpool's point contacts. A
	// persistent manifold keeps older points while they stay within the breaking threshold;
	// a slowly rolling ball's old contact point lifts and drifts only by (v dt)^2 / R, so the
	// cloth manifold filled up with near-duplicate points, and the sequential-impulse passes
	// over them lost up to 1 % of the rolling deceleration (the stop came 5 ms late at dt 1e-4).
	// The price is no warm starting, which only matters for resting stacks.
	const int manifolds = dispatcher_->getNumManifolds();
	for (int k = 0; k < manifolds; ++k)
		dispatcher_->getManifoldByIndexInternal(k)->clearManifold();
	// maxSubSteps = 0: exactly one internal step of dt, no interpolation.
	world_->stepSimulation(dt_, 0, dt_);
	++steps_;
	return after_step();
}

void Engine::before_solve() {
	// libpool's collisions are instantaneous impulses between two bodies (docs/physics.md): nothing
	// else acts during them, and in planar mode the vertical velocity they leave is dropped.
	// Bullet solves all contacts of a step together, so a collision that presses a ball into
	// the cloth (a cushion's impulse points down; ball-ball friction has a vertical part) also
	// gets the cloth's normal reaction and sliding friction in the same solve. Measured against
	// libpool: a cushion hit with side spin rebounded 8 % faster (the cloth held v_z = 0, so the
	// whole restitution along the tilted normal went into the horizontal velocity) and a
	// 30-degree cut threw the object ball with 12 % less z-spin. So a ball being hit in this step
	// (a ball or cushion contact closing faster than impact_closing) is solved without its cloth
	// contact (in planar mode after_step then drops v_z and puts it back at z = R, as libpool
	// does; in airborne mode the cloth answers in the next step, see below).
	std::fill(impact_.begin(), impact_.end(), 0);
	const int count = dispatcher_->getNumManifolds();
	// A hit closes faster than a step's gravity and contact forces do (g dt, twice for margin): a
	// ball bearing on another (resting on two, sliding off one) closes at about g dt every step,
	// and taken for an impact it took the lower ball off its cloth contact at every step, so
	// that ball had no cloth friction for as long as it carried the other (12 cm from libpool
	// and ODE at rest; 1.5-3.7 mm with this bound).
	const double impact_closing = std::max(settings_.rest_speed, 2.0 * params_.g * dt_);
	if (airborne_)
		landings();
	for (int k = 0; k < count; ++k) {
		const btPersistentManifold *mf = dispatcher_->getManifoldByIndexInternal(k);
		const Material *a = material_of(mf->getBody0()), *b = material_of(mf->getBody1());
		if (mf->getNumContacts() == 0 || !a || !b || a->engine != this || b->engine != this)
			continue;
		if (a->kind == kCloth || b->kind == kCloth || (a->kind != kBall && b->kind != kBall))
			continue;
		const btVector3 va = static_cast<const btRigidBody *>(mf->getBody0())->getLinearVelocity();
		const btVector3 vb = static_cast<const btRigidBody *>(mf->getBody1())->getLinearVelocity();
		for (int j = 0; j < mf->getNumContacts(); ++j) {
			// The normal points from body 1 to body 0; spheres' normals pass through their
			// centres, so the centres' velocities give the closing speed.
			if (mf->getContactPoint(j).m_normalWorldOnB.dot(va - vb) < -impact_closing) {
				if (a->kind == kBall)
					impact_[size_t(a->index)] = 1;
				if (b->kind == kBall)
					impact_[size_t(b->index)] = 1;
			}
		}
	}
	for (int k = 0; k < count; ++k) {
		btPersistentManifold *mf = dispatcher_->getManifoldByIndexInternal(k);
		const Material *a = material_of(mf->getBody0()), *b = material_of(mf->getBody1());
		if (!a || !b || a->engine != this || b->engine != this)
			continue;
		const Material *ball = a->kind == kBall && b->kind == kCloth   ? a
		                       : b->kind == kBall && a->kind == kCloth ? b
		                                                               : nullptr;
		if (!ball || !impact_[size_t(ball->index)])
			continue;
		// Airborne mode, as libpool too: the impact acts alone, and a downward velocity it
		// leaves (a cushion nose above the centre presses the ball down) is a ball-cloth
		// collision in the next step, which can make the ball hop; solved with the cloth, the
		// cloth's support absorbed that press and no ball ever hopped off a rail. The ball keeps
		// the cloth's support of its weight in that step (a force m g, read by the solver's
		// setup after this hook): without it every impact on the cloth would start a hop of
		// e_table g dt. The next step's cloth contact is a new one (a BALL_TABLE event when the
		// ball moves down).
		mf->clearManifold();
		if (airborne_) {
			Ball &bb = *balls_[size_t(ball->index)];
			bb.body->applyCentralForce(btVector3(0, 0, params_.ball_mass * params_.g));
			bb.cloth_contact = false;
		}
	}
}

void Engine::landings() {
	// Airborne mode: a ball touching the cloth while moving down is landing, an impact that
	// libpool resolves with Petit's law (n = k, e_table, mu_table). Bullet's contact with
	// restitution e and Coulomb friction mu (sticking when the friction impulse suffices) is that
	// law for one contact, given the pair's coefficients for this step: mu_table instead of the
	// rolling cloth's mu_slide, and e_table only above settle_speed (a slower landing settles,
	// restitution 0, as the closed form's 1 ms rule). A ball resting or rolling on the cloth
	// keeps mu_slide and restitution 0. A new touching cloth contact of a descending ball is a
	// BALL_TABLE event, stamped like the other contacts with the time of the state in which it
	// was found (the start of this step).
	const double t = double(steps_) * dt_;
	std::vector<uint8_t> touching(balls_.size(), 0);
	const int count = dispatcher_->getNumManifolds();
	for (int k = 0; k < count; ++k) {
		btPersistentManifold *mf = dispatcher_->getManifoldByIndexInternal(k);
		const Material *a = material_of(mf->getBody0()), *b = material_of(mf->getBody1());
		if (mf->getNumContacts() == 0 || !a || !b || a->engine != this || b->engine != this)
			continue;
		const Material *ball = a->kind == kBall && b->kind == kCloth   ? a
		                       : b->kind == kBall && a->kind == kCloth ? b
		                                                               : nullptr;
		if (!ball)
			continue;
		Ball &bb = *balls_[size_t(ball->index)];
		const double vz = bb.body->getLinearVelocity().z();
		const bool landing = -vz > settings_.impact_speed;
		for (int j = 0; j < mf->getNumContacts(); ++j) {
			btManifoldPoint &pt = mf->getContactPoint(j);
			if (pt.getDistance() > 0.0)
				continue;
			touching[size_t(ball->index)] = 1;
			pt.m_combinedRestitution = landing && -vz > settings_.settle_speed ? params_.e_table : 0.0;
			if (landing)
				pt.m_combinedFriction = params_.mu_table;
		}
		if (landing && touching[size_t(ball->index)] && !bb.cloth_contact)
			report(POOL_ENGINE_EVENT_BALL_TABLE, bb.id, -1, t);
	}
	for (size_t i = 0; i < balls_.size(); ++i)
		balls_[i]->cloth_contact = touching[i] != 0;
}

void Engine::report(int32_t type, int32_t a, int32_t b, double t) {
	pending_.push_back(pool_plugin::make_event(type, a, b, t));
}

void Engine::remove_ball(Ball &ball, int32_t state) {
	snapshot(ball, &ball.last);
	ball.last.state = state;
	for (double &x : ball.last.vel)
		x = 0.0;
	for (double &x : ball.last.omega)
		x = 0.0;
	ball.state = state;
	ball.active = false;
	ball.rolling = false;
	if (ball.body->isInWorld())
		world_->removeRigidBody(ball.body.get());
}

void Engine::update_contacts(double t_detect) {
	ball_contacts_.start_pass();
	rail_contacts_.start_pass();
	const int count = dispatcher_->getNumManifolds();
	for (int k = 0; k < count; ++k) {
		const btPersistentManifold *mf = dispatcher_->getManifoldByIndexInternal(k);
		bool touching = false;
		for (int j = 0; j < mf->getNumContacts(); ++j)
			if (mf->getContactPoint(j).getDistance() <= 0.0)
				touching = true;
		if (!touching)
			continue;
		const Material *a = material_of(mf->getBody0()), *b = material_of(mf->getBody1());
		if (!a || !b || a->engine != this || b->engine != this)
			continue;
		// A contact begins when a manifold first holds a touching point (the same step's events
		// are sorted in after_step, so the manifolds' order does not matter).
		if (a->kind == kBall && b->kind == kBall) {
			const size_t i = size_t(std::min(a->index, b->index)), j = size_t(std::max(a->index, b->index));
			if (ball_contacts_.see(i, j))
				report(POOL_ENGINE_EVENT_BALL_BALL, balls_[i]->id, balls_[j]->id, t_detect);
		} else if (a->kind == kBall && b->kind == kCushion) {
			if (rail_contacts_.see(size_t(a->index), size_t(b->index)))
				report(POOL_ENGINE_EVENT_BALL_CUSHION, balls_[size_t(a->index)]->id,
				       POOL_ENGINE_CUSHION(table_.segments[size_t(b->index)].rail), t_detect);
		} else if (b->kind == kBall && a->kind == kCushion) {
			if (rail_contacts_.see(size_t(b->index), size_t(a->index)))
				report(POOL_ENGINE_EVENT_BALL_CUSHION, balls_[size_t(b->index)]->id,
				       POOL_ENGINE_CUSHION(table_.segments[size_t(a->index)].rail), t_detect);
		}
	}
	// A contact ends only once the gap exceeds release_gap, so a resting contact that flickers
	// in the manifold is one contact.
	const double R = params_.ball_radius;
	ball_contacts_.release([&](size_t i, size_t j) {
		const Ball &bi = *balls_[i], &bj = *balls_[j];
		return !bi.active || !bj.active ||
		       (bi.body->getCenterOfMassPosition() - bj.body->getCenterOfMassPosition()).length() >
		           2.0 * R + settings_.release_gap;
	});
	rail_contacts_.release([&](size_t i, size_t k) {
		const Ball &bi = *balls_[i];
		const btVector3 pi = bi.body->getCenterOfMassPosition();
		const double p[3] = {pi.x(), pi.y(), pi.z()};
		return !bi.active || pool_plugin::distance_to_axis(table_.segments[k], p) >
		                         R + table_.segments[k].radius + settings_.release_gap;
	});
}

void Engine::measure_penetration() {
	const double R = params_.ball_radius;
	centres_.clear();
	for (const auto &b : balls_) {
		if (!b->active)
			continue;
		const btVector3 p = b->body->getCenterOfMassPosition();
		centres_.push_back({p.x(), p.y(), p.z()});
		for (const RailSegment &s : table_.segments)
			max_penetration_ = std::max(max_penetration_, R + s.radius - pool_plugin::distance_to_axis(s, centres_.back().data()));
	}
	max_penetration_ = std::max(max_penetration_, overlap_.deepest(centres_, R));
}

void Engine::classify(Ball &ball, bool report_events, double t) {
	if (!ball.active)
		return;
	const double R = params_.ball_radius;
	const btVector3 v = ball.body->getLinearVelocity(), w = ball.body->getAngularVelocity();
	const int32_t before = ball.state;
	// Airborne mode: above the cloth, or moving vertically (found below the cloth at the end of
	// the step before its landing is solved, or leaving it): in flight, not at rest.
	if (!on_cloth(ball) || (airborne_ && std::fabs(v.z()) > settings_.impact_speed)) {
		ball.state = POOL_MOTION_AIRBORNE;
		ball.rolling = false;
		return;
	}
	const double slip = horizontal_slip(v, w, R);
	const double speed = std::hypot(v.x(), v.y());
	const double roll = R * std::hypot(w.x(), w.y());
	const bool moving = speed >= settings_.rest_speed || roll >= settings_.rest_speed;
	const bool was_rolling = ball.rolling;
	ball.rolling = pool_plugin::roll_hysteresis(was_rolling, slip, settings_.roll_on_slip,
	                                            settings_.roll_off_slip);
	if (!moving)
		ball.state = std::fabs(w.z()) >= settings_.rest_spin ? POOL_MOTION_SPINNING : POOL_MOTION_STATIONARY;
	else
		ball.state = ball.rolling ? POOL_MOTION_ROLLING : POOL_MOTION_SLIDING;
	if (!report_events)
		return;
	if (moving && ball.rolling && !was_rolling)
		report(POOL_ENGINE_EVENT_SLIDE_ROLL, ball.id, -1, t);
	// libpool's roll_stop: a rolling ball stops translating (z-spin may go on).
	if (!moving && before == POOL_MOTION_ROLLING)
		report(POOL_ENGINE_EVENT_ROLL_STOP, ball.id, -1, t);
}

bool Engine::after_step() {
	const double t = double(steps_) * dt_;
	// The manifolds of this step were built from the positions at its start (t - dt), so a new
	// contact is stamped with the time of the state in which it was found.
	update_contacts(t - dt_);
	for (auto &b : balls_) {
		if (!b->active)
			continue;
		const btVector3 p = b->body->getCenterOfMassPosition();
		const btVector3 v = b->body->getLinearVelocity(), w = b->body->getAngularVelocity();
		if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()) &&
		      std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()) &&
		      std::isfinite(w.x()) && std::isfinite(w.y()) && std::isfinite(w.z()))) {
			error_ = "Bullet produced a non-finite state for ball " + std::to_string(b->id);
			return false;
		}
		// Planar mode: libpool drops the vertical velocity after every impulse; here every
		// ball ends the step on the cloth (the cloth contact keeps it there to ~1e-12 m
		// anyway, except in the steps of a collision, solved without the cloth).
		if (!airborne_ && (v.z() != 0.0 || p.z() != params_.ball_radius)) {
			b->body->setLinearVelocity(btVector3(v.x(), v.y(), 0.0));
			btTransform tr = b->body->getWorldTransform();
			tr.getOrigin().setZ(params_.ball_radius);
			b->body->setWorldTransform(tr);
		}
		// Thesis pocket model: a ball whose centre reaches the touch distance of a rail line
		// inside a mouth is pocketed.
		if (pool_plugin::pocket_entered(table_, p.x(), p.y()) != POOL_POCKET_NONE) {
			report(POOL_ENGINE_EVENT_POCKET, b->id, -1, t);
			remove_ball(*b, POOL_MOTION_POCKETED);
		} else if (pool_plugin::outside_table(table_, p.x(), p.y()) || p.z() < -params_.ball_radius) {
			remove_ball(*b, POOL_MOTION_OFF_TABLE); // tunnelled through a cushion or flew off
		}
	}
	measure_penetration();
	for (auto &b : balls_)
		classify(*b, true, t);
	// Same-step events in libpool's tie order: time, kind, ball ids.
	std::stable_sort(pending_.begin(), pending_.end(), [](const pool_engine_event &x, const pool_engine_event &y) {
		if (x.t != y.t)
			return x.t < y.t;
		if (x.type != y.type)
			return x.type < y.type;
		if (x.ball_a != y.ball_a)
			return x.ball_a < y.ball_a;
		return x.ball_b < y.ball_b;
	});
	events_.insert(events_.end(), pending_.begin(), pending_.end());
	pending_.clear();
	return true;
}

bool Engine::all_at_rest() const {
	for (const auto &b : balls_)
		if (b->active && b->state != POOL_MOTION_STATIONARY)
			return false;
	return true;
}

bool Engine::advance(double t) {
	if (!world_) {
		error_ = "advance: engine not built";
		return false;
	}
	if (!std::isfinite(t) || t / dt_ > 1e11) {
		error_ = "advance: t must be finite and below 1e11 steps";
		return false;
	}
	// Integer step counts: no drift of the clock, and t on a step boundary is reached exactly.
	const double target = std::ceil(t / dt_ - 1e-9);
	while (double(steps_) < target)
		if (!step())
			return false;
	return true;
}

bool Engine::run_to_rest(double max_time) {
	if (!world_) {
		error_ = "run_to_rest: engine not built";
		return false;
	}
	if (std::isnan(max_time) || max_time / dt_ > 1e11) {
		error_ = "run_to_rest: max_time must be finite and below 1e11 steps";
		return false;
	}
	const double target = std::ceil(max_time / dt_ - 1e-9);
	while (double(steps_) < target && !all_at_rest())
		if (!step())
			return false;
	return true;
}

void Engine::snapshot(const Ball &ball, pool_engine_ball *out) const {
	if (!ball.active) {
		*out = ball.last;
		return;
	}
	const btVector3 p = ball.body->getCenterOfMassPosition();
	const btVector3 v = ball.body->getLinearVelocity(), w = ball.body->getAngularVelocity();
	out->id = ball.id;
	out->state = ball.state;
	for (int k = 0; k < 3; ++k) {
		out->pos[k] = p[k];
		out->vel[k] = v[k];
		out->omega[k] = w[k];
	}
}

int Engine::balls(pool_engine_ball *out, int capacity) const {
	const int n = int(balls_.size());
	for (int i = 0; out && i < n && i < capacity; ++i)
		snapshot(*balls_[size_t(i)], &out[i]);
	return n;
}

} // namespace pool_bullet
