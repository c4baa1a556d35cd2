// The ODE model of a pool shot (see ode_engine.h and README.md, "ODE engine plugin", for the choices).
#include "ode_engine.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "engine_state.h"

namespace pool_ode {

namespace {

// Up to this many geoms a simple space (every pair tested) is faster than a hash space (measured).
constexpr size_t kSimpleSpaceGeoms = 22;

// dInitODE2 / dCloseODE are process-wide: several engines may live at once, so count them.
std::mutex g_ode_mutex;
int g_ode_users = 0;

void acquire_ode() {
	std::lock_guard<std::mutex> lock(g_ode_mutex);
	if (g_ode_users++ == 0)
		dInitODE2(0);
	dAllocateODEDataForThread(dAllocateMaskAll);
}

void release_ode() {
	std::lock_guard<std::mutex> lock(g_ode_mutex);
	if (--g_ode_users == 0)
		dCloseODE();
}

void near_callback(void *data, dGeomID g1, dGeomID g2) {
	static_cast<Engine *>(data)->near(g1, g2);
}

// Geom tags: balls carry index + 1, cushions -(segment + 1), so 0 never occurs.
void *ball_tag(size_t i) { return reinterpret_cast<void *>(static_cast<intptr_t>(i) + 1); }
void *rail_tag(size_t s) { return reinterpret_cast<void *>(-static_cast<intptr_t>(s) - 1); }
intptr_t tag_of(dGeomID g) { return reinterpret_cast<intptr_t>(dGeomGetData(g)); }

bool finite3(const dReal *v) {
	return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

} // namespace

Settings default_settings() {
	Settings s;
	// ERP 0.2 (ODE's default): only resting contacts (a frozen rack, a ball against a cushion)
	// ever need position correction, and a larger ERP pushes overlapping balls apart faster
	// than their restitution, which adds energy to slow kisses.
	s.erp = 0.2;
	// CFM 1e-10: rigid for practical purposes (the compliance adds cfm/dt ~ 1e-7 to diagonals
	// of order 1/m ~ 6), but non-zero so Dantzig's LCP stays regular with redundant contacts.
	s.cfm = 1e-10;
	// Capsule radius R: large enough that a ball cannot pass a cushion's axis in one step below
	// v dt = 2R (~5.7 cm), and the ball-capsule contact is exact whatever rc is.
	s.capsule_radius = -1.0; // < 0: use the ball radius
	// Airborne mode: libpool's cushion is the nose line for a flying ball too. A capsule of
	// radius rc placed to touch a ball on the cloth exactly gives a flying ball at another height
	// another contact point and normal (a dt-independent error: the cushion hop ended 3.5 cm
	// from libpool at every dt down to 1e-5 with rc = R); a 0.1 mm capsule is the line to
	// 0.1 mm (2.6 mm at dt 1e-5, shrinking with dt). A ball then passes a capsule's axis at
	// v dt > R + rc instead of 2R; the off-table rule (the centre past the rail line) acts first.
	s.airborne_capsule_radius = 1e-4;
	// Rolling resistance only while rolling (docs/engines.md): on below 1e-4 m/s of slip, off again
	// above 1e-2 m/s. ODE's sticking friction makes the slip exactly 0 (to rounding) in the step
	// rolling starts, so 1e-4 catches that step; the gap to 1e-2 keeps rounding from toggling.
	s.roll_on_slip = 1e-4;
	s.roll_off_slip = 1e-2;
	// Rolling resistance and spin friction hold a stopped ball exactly (they are torque limits
	// of a sticking constraint), so the rest threshold can be tiny.
	s.rest_speed = 1e-5;
	// A touching pair must separate by 10 um before a new contact counts as a new collision:
	// balls resting against each other or a cushion jitter by far less than that.
	s.release_gap = 1e-5;
	// Airborne mode only: a ball within 1 um of the cloth is on it (its contact then holds it
	// there at zero depth), and a landing too slow for its rebound to fly
	// pool_plugin::kSettleFlightTime (1 ms) settles instead of bouncing: the harness's closed form
	// and libpool's rule. Set per scenario in build() (it depends on e_table and g; 9.81 mm/s at
	// the defaults).
	s.cloth_gap = 1e-6;
	s.settle_speed = 0.0;
	// Contacts approaching faster than 0.1 mm/s are impacts (planar mode solves them without
	// the cloth, see Engine::step); slower ones are resting contacts and keep the cloth.
	s.impact_speed = 1e-4;
	return s;
}

Engine::~Engine() {
	if (contacts_)
		dJointGroupDestroy(contacts_);
	if (space_)
		dSpaceDestroy(space_); // destroys its geoms (cleanup mode is on by default)
	if (world_)
		dWorldDestroy(world_); // destroys the bodies
	if (ode_ref_)
		release_ode();
}

bool Engine::build(const pool_scenario &scenario, double dt, std::string *error) {
	char message[512];
	if (!std::isfinite(dt) || dt <= 0.0 || dt > 0.1) {
		std::snprintf(message, sizeof message, "config.dt: must be in (0, 0.1] s, got %g", dt);
		*error = message;
		return false;
	}
	dt_ = dt;
	settings_ = default_settings();
	params_ = scenario.def.params;
	airborne_ = scenario.def.airborne;
	settings_.settle_speed = pool_plugin::settle_landing_speed(params_);
	const double R = params_.ball_radius;
	const double rc = airborne_ ? settings_.airborne_capsule_radius
	                            : settings_.capsule_radius > 0.0 ? settings_.capsule_radius : R;
	settings_.capsule_radius = rc;
	if (!(std::fabs(scenario.def.table.cushion_height - R) < R)) {
		*error = "table.cushion_height: the ODE model needs a nose a ball on the cloth can "
		         "touch (0 < h < 2R)";
		return false;
	}
	// Every stretch of positive length is a capsule; a closed side pocket still splits the long
	// rails into two capsules meeting at L/2.
	table_ = pool_plugin::make_table_geometry(scenario.def.table, R, {rc, 0.0, true});
	pool_vec3 strike_vel = {0, 0, 0}, strike_omega = {0, 0, 0};
	if (scenario.has_strike) {
		pool_error e;
		std::memset(&e, 0, sizeof e);
		pool_result r = pool_strike_velocities(&params_, &scenario.strike, &strike_vel,
		                                       &strike_omega, &e);
		if (r != POOL_OK) {
			std::snprintf(message, sizeof message, "strike: %s",
			              e.message[0] ? e.message : pool_result_str(r));
			*error = message;
			return false;
		}
		if (!airborne_)
			strike_vel.z = 0.0; // planar mode drops the vertical component, as libpool does
	}

	acquire_ode();
	ode_ref_ = true;
	world_ = dWorldCreate();
	dWorldSetGravity(world_, 0, 0, -params_.g);
	dWorldSetERP(world_, settings_.erp);
	dWorldSetCFM(world_, settings_.cfm);
	dWorldSetContactSurfaceLayer(world_, 0);
	dWorldSetAutoDisableFlag(world_, 0);
	// A simple space tests every pair of geoms: faster than the others up to 22 geoms (measured),
	// but quadratic (60 % of a 1,024-ball step). Beyond, sweep and prune: 1.2 ms a step for a
	// 1,024-ball gas against 1.8 ms with a hash space and 4.4 ms with the simple space.
	const size_t geoms = size_t(scenario.ball_count) + table_.segments.size();
	space_ = geoms <= kSimpleSpaceGeoms ? dSimpleSpaceCreate(nullptr)
	                                    : dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XYZ);
	contacts_ = dJointGroupCreate(0);

	for (size_t s = 0; s < table_.segments.size(); ++s) {
		const RailSegment &seg = table_.segments[s];
		double ax[3], len = 0.0;
		for (int k = 0; k < 3; ++k) {
			ax[k] = seg.b[k] - seg.a[k];
			len += ax[k] * ax[k];
		}
		len = std::sqrt(len);
		dGeomID g = dCreateCapsule(space_, seg.radius, len);
		dMatrix3 rot;
		dRFromZAxis(rot, ax[0], ax[1], ax[2]);
		dGeomSetRotation(g, rot);
		dGeomSetPosition(g, 0.5 * (seg.a[0] + seg.b[0]), 0.5 * (seg.a[1] + seg.b[1]),
		                 0.5 * (seg.a[2] + seg.b[2]));
		dGeomSetData(g, rail_tag(s));
		rails_.push_back(g);
	}

	dMass mass;
	dMassSetSphereTotal(&mass, params_.ball_mass, R);
	balls_.resize(size_t(scenario.ball_count));
	for (size_t i = 0; i < balls_.size(); ++i) {
		const pool_ball_state &src = scenario.balls[i];
		Ball &b = balls_[i];
		b.id = src.id;
		pool_vec3 v = src.vel, w = src.omega, p = src.pos;
		if (scenario.has_strike && src.id == scenario.strike_ball) {
			v = strike_vel;
			w = strike_omega;
		}
		if (!airborne_) {
			p.z = R;
			v.z = 0.0;
		}
		b.body = dBodyCreate(world_);
		dBodySetMass(b.body, &mass);
		dBodySetPosition(b.body, p.x, p.y, p.z);
		dBodySetLinearVel(b.body, v.x, v.y, v.z);
		dBodySetAngularVel(b.body, w.x, w.y, w.z);
		b.geom = dCreateSphere(space_, R);
		dGeomSetBody(b.geom, b.body);
		dGeomSetData(b.geom, ball_tag(i));
		double ux = v.x - R * w.y, uy = v.y + R * w.x;
		b.rolling = std::hypot(ux, uy) < settings_.roll_on_slip;
		b.moving = true;
		classify(i, false);
	}

	const size_t n = balls_.size(), ns = rails_.size();
	impact_.assign(n, 0);
	// Contacts that already exist at t = 0 (a frozen rack) are not collisions.
	for (size_t i = 0; i < n; ++i) {
		const dReal *pi = dBodyGetPosition(balls_[i].body);
		for (size_t j = i + 1; j < n; ++j) {
			const dReal *pj = dBodyGetPosition(balls_[j].body);
			double d = std::sqrt((pi[0] - pj[0]) * (pi[0] - pj[0]) +
			                     (pi[1] - pj[1]) * (pi[1] - pj[1]) +
			                     (pi[2] - pj[2]) * (pi[2] - pj[2]));
			if (d - 2.0 * R <= settings_.release_gap)
				ball_contacts_.set_touching(i, j);
		}
		for (size_t s = 0; s < ns; ++s) {
			double p[3] = {pi[0], pi[1], pi[2]};
			if (pool_plugin::distance_to_axis(table_.segments[s], p) - (R + table_.segments[s].radius) <=
			    settings_.release_gap)
				rail_contacts_.set_touching(i, s);
		}
	}
	return true;
}

void Engine::report(int32_t type, int32_t a, int32_t b, double t) {
	events_.push_back(pool_plugin::make_event(type, a, b, t));
}

void Engine::near(dGeomID g1, dGeomID g2) {
	const intptr_t t1 = tag_of(g1), t2 = tag_of(g2);
	if (t1 <= 0 && t2 <= 0)
		return; // two cushions
	dContact c;
	std::memset(&c, 0, sizeof c);
	if (dCollide(g1, g2, 1, &c.geom, sizeof(dContactGeom)) < 1)
		return;
	const double t = now();
	double mu, e;
	if (t1 > 0 && t2 > 0) {
		size_t i = size_t(t1 - 1), j = size_t(t2 - 1);
		if (i > j)
			std::swap(i, j);
		if (ball_contacts_.see(i, j))
			report(POOL_ENGINE_EVENT_BALL_BALL, balls_[i].id, balls_[j].id, t);
		mu = params_.mu_ball;
		e = params_.e_ball;
	} else {
		const size_t i = size_t((t1 > 0 ? t1 : t2) - 1);
		const size_t s = size_t(-(t1 > 0 ? t2 : t1) - 1);
		if (rail_contacts_.see(i, s))
			report(POOL_ENGINE_EVENT_BALL_CUSHION, balls_[i].id, POOL_ENGINE_CUSHION(table_.segments[s].rail), t);
		mu = params_.mu_cushion;
		e = params_.e_cushion;
	}
	max_penetration_ = std::max(max_penetration_, double(c.geom.depth));

	dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
	const dReal *p = c.geom.pos, *n = c.geom.normal;
	dVector3 v1 = {0, 0, 0, 0}, v2 = {0, 0, 0, 0};
	if (b1)
		dBodyGetPointVel(b1, p[0], p[1], p[2], v1);
	if (b2)
		dBodyGetPointVel(b2, p[0], p[1], p[2], v2);
	const double rel[3] = {v1[0] - v2[0], v1[1] - v2[1], v1[2] - v2[2]};
	const double rn = rel[0] * n[0] + rel[1] * n[1] + rel[2] * n[2];
	if (-rn > settings_.impact_speed) {
		// n points into body 1: rn < 0 means approaching.
		if (t1 > 0)
			impact_[size_t(t1 - 1)] = 1;
		if (t2 > 0)
			impact_[size_t(t2 - 1)] = 1;
	}
	// Restitution as a target separation speed, with no threshold: every approach bounces.
	c.surface.mode = dContactBounce;
	c.surface.bounce = e;
	c.surface.bounce_vel = 0.0;
	if (mu > 0.0) {
		// Friction proportional to the normal impulse (Approx1), its first direction along the
		// slip at the contact so ODE's friction box acts like Coulomb's cone for this contact.
		c.surface.mode |= dContactApprox1 | dContactFDir1;
		c.surface.mu = mu;
		const double tg[3] = {rel[0] - rn * n[0], rel[1] - rn * n[1], rel[2] - rn * n[2]};
		const double tl = std::sqrt(tg[0] * tg[0] + tg[1] * tg[1] + tg[2] * tg[2]);
		if (tl > 1e-12) {
			c.fdir1[0] = tg[0] / tl;
			c.fdir1[1] = tg[1] / tl;
			c.fdir1[2] = tg[2] / tl;
		} else {
			dVector3 a, b;
			dPlaneSpace(n, a, b);
			c.fdir1[0] = a[0];
			c.fdir1[1] = a[1];
			c.fdir1[2] = a[2];
		}
	}
	dJointID j = dJointCreateContact(world_, contacts_, &c);
	dJointAttach(j, b1, b2);
}

// The cloth is not a geom: every ball on it gets one contact made here, which also keeps the
// contact alive at zero depth (ODE's plane collider drops it whenever rounding lifts the ball).
void Engine::add_cloth_contact(size_t i) {
	Ball &b = balls_[i];
	const double R = params_.ball_radius;
	const dReal *p = dBodyGetPosition(b.body);
	const dReal *v = dBodyGetLinearVel(b.body);
	const dReal *w = dBodyGetAngularVel(b.body);
	const double gap = p[2] - R;
	if (airborne_ && gap > settings_.cloth_gap) {
		b.cloth_contact = false;
		return;
	}
	// A landing (or a strike pressing the ball into the cloth): a new cloth contact approaching
	// it, stamped with the time of the state in which it was found (the start of this step).
	if (airborne_ && !b.cloth_contact && -v[2] > settings_.impact_speed)
		report(POOL_ENGINE_EVENT_BALL_TABLE, b.id, -1, now());
	b.cloth_contact = true;
	dContact c;
	std::memset(&c, 0, sizeof c);
	c.geom.pos[0] = p[0];
	c.geom.pos[1] = p[1];
	c.geom.pos[2] = p[2] - R;
	c.geom.normal[2] = 1.0;
	c.geom.depth = -gap;
	c.geom.g1 = b.geom;
	// Friction direction: the slip u = v + R k x w while sliding, the velocity while rolling.
	// Without it ODE aligns its friction box with the world axes and a 30 degree shot curves.
	const double ux = v[0] - R * w[1], uy = v[1] + R * w[0];
	const double us = std::hypot(ux, uy), vs = std::hypot(v[0], v[1]);
	double fx = 1.0, fy = 0.0;
	if (!b.rolling && us > 1e-12)
		fx = ux / us, fy = uy / us;
	else if (vs > 1e-12)
		fx = v[0] / vs, fy = v[1] / vs;
	else if (us > 1e-12)
		fx = ux / us, fy = uy / us;
	c.fdir1[0] = fx;
	c.fdir1[1] = fy;
	// AxisDep (the same bit as Mu2) is what makes ODE read rho2 and rhoN, so mu2 must be set.
	c.surface.mode = dContactApprox1 | dContactFDir1 | dContactAxisDep | dContactRolling;
	c.surface.mu = params_.mu_slide;
	c.surface.mu2 = params_.mu_slide;
	// Rolling resistance as a torque limit rho N about both horizontal axes: rho = 1.4 mu_roll R
	// decelerates a rolling ball by mu_roll g. Only while rolling (hysteresis in classify).
	// A negative rho removes the row: with rho = 0 ODE 0.16 counts the row in getInfo1 but never
	// fills it, leaving an empty unbounded row.
	const double rho = 1.4 * params_.mu_roll * R;
	c.surface.rho = (b.rolling && rho > 0.0) ? rho : -1.0;
	c.surface.rho2 = c.surface.rho;
	// Spin friction: torque mu_spin R N about the normal gives dwz/dt = 5 mu_spin g / (2R).
	c.surface.rhoN = params_.mu_spin > 0.0 ? params_.mu_spin * R : -1.0;
	if (airborne_ && -v[2] > settings_.impact_speed) {
		// A landing: an impact (Petit's, with mu_table). Rolling resistance and spin friction are
		// torque limits proportional to the normal impulse, which in a landing step is the
		// impact's, (1 + e) m v, not m g dt: left on, they took 1.5 % of v_z from the speed of a
		// rolling ball at every landing (the hop's final position 17 mm off at any dt). libpool's
		// impact has neither. Landings faster than settle_speed bounce with e_table (ODE drops
		// the restitution below bounce_vel, so slower ones settle).
		c.surface.rho = c.surface.rho2 = c.surface.rhoN = -1.0;
		c.surface.mu = c.surface.mu2 = params_.mu_table;
		if (-v[2] > settings_.settle_speed) {
			c.surface.mode |= dContactBounce;
			c.surface.bounce = params_.e_table;
			c.surface.bounce_vel = settings_.settle_speed;
		}
	}
	dJointID j = dJointCreateContact(world_, contacts_, &c);
	dJointAttach(j, b.body, nullptr);
}

bool Engine::step() {
	ball_contacts_.start_pass();
	rail_contacts_.start_pass();
	std::fill(impact_.begin(), impact_.end(), 0);
	dSpaceCollide(space_, this, &near_callback);
	for (size_t i = 0; i < balls_.size(); ++i) {
		// Planar mode, as libpool: an impact's impulse acts alone along its 3D normal and the
		// vertical velocity it leaves is then dropped. Solved together with the cloth contact,
		// the cloth would take the impulse's vertical part (the cushion normal's downward tilt,
		// the ball-ball friction of spinning balls) and add cloth friction to the impact:
		// 0.2 m/s less rail-parallel speed off a cushion at 2 m/s, and a cut ball thrown 0.2
		// degrees off by the friction box of a ball at rest. Resting contacts keep the cloth.
		// Airborne mode, as libpool too: the impact acts alone, and a downward velocity it leaves
		// (a cushion nose above the centre presses the ball down) is a ball-cloth collision in
		// the next step, which can make the ball hop. Solved with the cloth, the cloth's support
		// absorbed that press and no ball ever hopped off a rail. The ball keeps the cloth's
		// support of its weight in that step (a force m g): without it, every impact of a ball on
		// the cloth would start a hop of e_table g dt.
		if (!balls_[i].active)
			continue;
		if (impact_[i]) {
			if (!airborne_)
				continue;
			Ball &b = balls_[i];
			if (dBodyGetPosition(b.body)[2] - params_.ball_radius <= settings_.cloth_gap) {
				dBodyAddForce(b.body, 0.0, 0.0, params_.ball_mass * params_.g);
				b.cloth_contact = false;
				continue;
			}
		}
		add_cloth_contact(i);
	}
	int ok = dWorldStep(world_, dt_);
	dJointGroupEmpty(contacts_);
	if (!ok) {
		error_ = "dWorldStep failed (out of memory)";
		return false;
	}
	++steps_;
	after_step();
	for (const Ball &b : balls_) {
		if (!b.active)
			continue;
		if (!finite3(dBodyGetPosition(b.body)) || !finite3(dBodyGetLinearVel(b.body)) ||
		    !finite3(dBodyGetAngularVel(b.body))) {
			char message[128];
			std::snprintf(message, sizeof message, "ODE produced a non-finite state at t = %.9g s",
			              now());
			error_ = message;
			return false;
		}
	}
	return true;
}

void Engine::after_step() {
	const double R = params_.ball_radius, t = now();
	const size_t n = balls_.size();
	for (size_t i = 0; i < n; ++i) {
		Ball &b = balls_[i];
		if (!b.active)
			continue;
		if (!airborne_) {
			// Planar mode, as libpool: the ball stays on the cloth (z = R, v_z = 0).
			const dReal *p = dBodyGetPosition(b.body), *v = dBodyGetLinearVel(b.body);
			dBodySetPosition(b.body, p[0], p[1], R);
			dBodySetLinearVel(b.body, v[0], v[1], 0.0);
		}
		const dReal *p = dBodyGetPosition(b.body);
		pool_pocket pocket = pool_plugin::pocket_entered(table_, p[0], p[1]);
		bool off = pocket == POOL_POCKET_NONE && (pool_plugin::outside_table(table_, p[0], p[1]) || p[2] < 0.0);
		if (pocket != POOL_POCKET_NONE || off) {
			b.active = false;
			b.state = pocket != POOL_POCKET_NONE ? POOL_MOTION_POCKETED : POOL_MOTION_OFF_TABLE;
			b.moving = false;
			dBodySetLinearVel(b.body, 0, 0, 0);
			dBodySetAngularVel(b.body, 0, 0, 0);
			dBodyDisable(b.body);
			dGeomDisable(b.geom);
			if (pocket != POOL_POCKET_NONE)
				report(POOL_ENGINE_EVENT_POCKET, b.id, -1, t);
			continue;
		}
		classify(i, true);
	}
	// Separations: a pair not found touching in this step's collision pass counts as apart
	// once its gap exceeds release_gap (or a ball left the table).
	ball_contacts_.release([&](size_t i, size_t j) {
		const dReal *pi = dBodyGetPosition(balls_[i].body), *pj = dBodyGetPosition(balls_[j].body);
		double d = std::sqrt((pi[0] - pj[0]) * (pi[0] - pj[0]) + (pi[1] - pj[1]) * (pi[1] - pj[1]) +
		                     (pi[2] - pj[2]) * (pi[2] - pj[2]));
		return !balls_[i].active || !balls_[j].active || d - 2.0 * R > settings_.release_gap;
	});
	rail_contacts_.release([&](size_t i, size_t s) {
		const dReal *pi = dBodyGetPosition(balls_[i].body);
		double p[3] = {pi[0], pi[1], pi[2]};
		double gap = pool_plugin::distance_to_axis(table_.segments[s], p) - (R + table_.segments[s].radius);
		return !balls_[i].active || gap > settings_.release_gap;
	});
}

// Motion state of a ball on the table and its slide/roll/stop transitions.
void Engine::classify(size_t i, bool events) {
	Ball &b = balls_[i];
	const double R = params_.ball_radius, t = now();
	const dReal *p = dBodyGetPosition(b.body);
	const dReal *v = dBodyGetLinearVel(b.body);
	const dReal *w = dBodyGetAngularVel(b.body);
	// Airborne mode: above the cloth, or moving vertically (a ball found below the cloth at the
	// end of the step before its landing is solved, or leaving it): in flight, not at rest.
	if (airborne_ && (p[2] - R > settings_.cloth_gap || std::fabs(v[2]) > settings_.impact_speed)) {
		b.state = POOL_MOTION_AIRBORNE;
		b.rolling = false;
		b.moving = true;
		return;
	}
	const double slip = std::hypot(v[0] - R * w[1], v[1] + R * w[0]);
	const double speed = std::hypot(v[0], v[1]);
	const bool was_rolling = b.rolling;
	b.rolling = pool_plugin::roll_hysteresis(was_rolling, slip, settings_.roll_on_slip,
	                                         settings_.roll_off_slip);
	if (events && b.rolling && !was_rolling && speed > settings_.rest_speed)
		report(POOL_ENGINE_EVENT_SLIDE_ROLL, b.id, -1, t);
	const bool moving = !b.rolling || speed > settings_.rest_speed;
	// (A ball settling from flight with no horizontal motion never rolled: no roll_stop.)
	if (events && b.moving && !moving && b.state != POOL_MOTION_AIRBORNE)
		report(POOL_ENGINE_EVENT_ROLL_STOP, b.id, -1, t);
	b.moving = moving;
	if (!b.rolling)
		b.state = POOL_MOTION_SLIDING;
	else if (speed > settings_.rest_speed)
		b.state = POOL_MOTION_ROLLING;
	else if (std::fabs(w[2]) * R > settings_.rest_speed)
		b.state = POOL_MOTION_SPINNING;
	else
		b.state = POOL_MOTION_STATIONARY;
}

bool Engine::all_at_rest() const {
	for (const Ball &b : balls_)
		if (b.active && b.state != POOL_MOTION_STATIONARY)
			return false;
	return true;
}

bool Engine::advance(double t) {
	if (!error_.empty())
		return false;
	if (!std::isfinite(t)) {
		error_ = "advance: t must be finite";
		return false;
	}
	if ((t - now()) / dt_ > 2e9) {
		error_ = "advance: t is more than 2e9 steps ahead";
		return false;
	}
	// Whole steps of dt: stop at the first step time at or after t (rounding-tolerant).
	while (now() < t - 1e-9 * dt_)
		if (!step())
			return false;
	return true;
}

bool Engine::run_to_rest(double max_time) {
	if (!error_.empty())
		return false;
	if (!std::isfinite(max_time)) {
		error_ = "run_to_rest: max_time must be finite";
		return false;
	}
	if ((max_time - now()) / dt_ > 2e9) {
		error_ = "run_to_rest: max_time is more than 2e9 steps ahead";
		return false;
	}
	while (!all_at_rest() && now() < max_time - 1e-9 * dt_)
		if (!step())
			return false;
	return true;
}

int Engine::balls(pool_engine_ball *out, int capacity) const {
	const int n = int(balls_.size());
	for (int i = 0; i < n && i < capacity && out; ++i) {
		const Ball &b = balls_[size_t(i)];
		const dReal *p = dBodyGetPosition(b.body);
		const dReal *v = dBodyGetLinearVel(b.body);
		const dReal *w = dBodyGetAngularVel(b.body);
		out[i].id = b.id;
		out[i].state = b.state;
		for (int k = 0; k < 3; ++k) {
			out[i].pos[k] = p[k];
			out[i].vel[k] = b.active ? v[k] : 0.0;
			out[i].omega[k] = b.active ? w[k] : 0.0;
		}
	}
	return n;
}

} // namespace pool_ode
