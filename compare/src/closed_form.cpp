// The closed-form motion of a single ball on the cloth (docs/physics.md "Motion between events";
// docs/validation.md 1-3): slide along a parabola until the slip vanishes, roll in a straight line
// until it stops, with the z-spin decaying independently.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "reference.h"

namespace pool_compare {

namespace {

using Eigen::Vector3d;

const Vector3d kUp(0.0, 0.0, 1.0);

class ClosedForm final : public Reference {
public:
	ClosedForm(const pool_params &p, int id, const Vector3d &r0, const Vector3d &v0, const Vector3d &w0)
	    : p_(p), id_(id), r0_(r0), v0_(v0), w0_(w0) {
		const double R = p.ball_radius;
		const Vector3d u0 = v0 + R * kUp.cross(w0);
		const double slip = u0.norm();
		// Below this the ball counts as rolling from the start (rounding of a natural-roll input).
		if (slip > 1e-12 * std::max(1.0, v0.norm())) {
			uhat_ = u0 / slip;
			t_roll_ = 2.0 * slip / (7.0 * p.mu_slide * p.g);
		}
		r1_ = position_sliding(t_roll_);
		v1_ = v0 - p.mu_slide * p.g * t_roll_ * uhat_;
		t_stop_ = t_roll_ + v1_.norm() / (p.mu_roll * p.g);
		const double wz = std::fabs(w0.z());
		t_spin_ = p.mu_spin > 0.0 ? 2.0 * R * wz / (5.0 * p.mu_spin * p.g)
		                          : (wz > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
		if (t_roll_ > 0.0)
			events.push_back({t_roll_, POOL_ENGINE_EVENT_SLIDE_ROLL, id, -1});
		if (v1_.norm() > 0.0)
			events.push_back({t_stop_, POOL_ENGINE_EVENT_ROLL_STOP, id, -1});
	}

	std::string kind() const override { return "closed-form"; }

	double rest_time() const { return std::max(t_stop_, t_spin_); }

	/// Whether the path up to `until` (s, default: to its end) stays clear of the cushion noses
	/// (so no event but slide/roll/stop).
	bool clear_of(double xmin, double xmax, double ymin, double ymax,
	              double until = std::numeric_limits<double>::infinity()) const {
		auto inside = [&](const Vector3d &r) {
			return r.x() >= xmin && r.x() <= xmax && r.y() >= ymin && r.y() <= ymax;
		};
		const int n = 512;
		const double slide_end = std::min(t_roll_, until);
		for (int i = 0; i <= n; ++i)
			if (!inside(position_sliding(slide_end * i / n)))
				return false;
		// the rolling path is a straight segment
		return inside(state_at_one(std::min(t_stop_, std::max(until, 0.0))).pos);
	}

	std::vector<BallSample> state_at(double t) const override { return {state_at_one(t)}; }

private:
	Vector3d position_sliding(double t) const {
		return r0_ + v0_ * t - 0.5 * p_.mu_slide * p_.g * t * t * uhat_;
	}

	BallSample state_at_one(double t) const {
		const double R = p_.ball_radius;
		BallSample s;
		s.id = id_;
		double wz = 0.0;
		if (t < t_spin_)
			wz = w0_.z() - std::copysign(1.0, w0_.z()) * (5.0 * p_.mu_spin * p_.g / (2.0 * R)) * t;
		if (t < t_roll_) {
			s.state = 2;
			s.pos = position_sliding(t);
			s.vel = v0_ - p_.mu_slide * p_.g * t * uhat_;
			Vector3d w_perp(w0_.x(), w0_.y(), 0.0);
			s.omega = w_perp + (5.0 * p_.mu_slide * p_.g / (2.0 * R)) * t * kUp.cross(uhat_);
		} else if (t < t_stop_) {
			const double tau = t - t_roll_;
			const Vector3d vhat = v1_.normalized();
			s.state = 3;
			s.pos = r1_ + v1_ * tau - 0.5 * p_.mu_roll * p_.g * tau * tau * vhat;
			s.vel = v1_ - p_.mu_roll * p_.g * tau * vhat;
			s.omega = kUp.cross(s.vel) / R;
		} else {
			const double run = t_stop_ - t_roll_;
			const Vector3d vhat = v1_.norm() > 0.0 ? Vector3d(v1_.normalized()) : Vector3d::Zero();
			s.state = wz != 0.0 ? 1 : 0;
			s.pos = r1_ + v1_ * run - 0.5 * p_.mu_roll * p_.g * run * run * vhat;
		}
		s.omega.z() = wz;
		return s;
	}

	pool_params p_;
	int id_;
	Vector3d r0_, v0_, w0_;
	Vector3d uhat_ = Vector3d::Zero();
	double t_roll_ = 0.0;
	Vector3d r1_, v1_;
	double t_stop_ = 0.0;
	double t_spin_ = 0.0;
};

// One ball in airborne mode: flights (parabolas, spin constant) separated by Petit impacts with
// the cloth, until a rebound too weak to fly kSettleFlightTime settles the ball; from then on the
// on-cloth closed form above, started at the settling instant.
class AirborneClosedForm final : public Reference {
public:
	struct Flight {
		double t0, t1;            ///< s, start (launch or rebound) and landing
		Vector3d r0, v0, w;       ///< state at t0 (w constant in flight)
	};

	AirborneClosedForm(const pool_params &p, int id, Vector3d r, Vector3d v, Vector3d w, double horizon)
	    : p_(p), id_(id) {
		const double R = p.ball_radius, g = p.g;
		double t = 0.0;
		// A bounded loop: with e_table < 1 the flights shrink geometrically and the rebound
		// settles after a few landings; e_table = 1 bounces for ever, so stop past the horizon.
		for (int n = 0; n < 100000; ++n) {
			const bool on_cloth = r.z() <= R + 1e-12;
			if (on_cloth && v.z() < 0.0) {
				// A landing (or a strike driving the ball into the cloth).
				r.z() = R;
				landings.push_back({t, id, r});
				events.push_back({t, POOL_ENGINE_EVENT_BALL_TABLE, id, -1});
				cloth_impact(p, &v, &w);
				if (2.0 * v.z() / g < kSettleFlightTime) {
					v.z() = 0.0; // settles: on the cloth from here
					break;
				}
			} else if (on_cloth && v.z() == 0.0) {
				r.z() = R;
				break;
			}
			if (t > horizon)
				break;
			// Flight until z = R with v_z < 0: R = z0 + vz tau - g tau^2 / 2.
			const double dz = r.z() - R;
			const double tau = (v.z() + std::sqrt(v.z() * v.z() + 2.0 * g * dz)) / g;
			flights_.push_back({t, t + tau, r, v, w});
			if (v.z() > 0.0)
				apexes.push_back({t + v.z() / g, id, r.z() + v.z() * v.z() / (2.0 * g)});
			r = r + v * tau - 0.5 * g * tau * tau * kUp;
			r.z() = R;
			v.z() -= g * tau;
			t += tau;
		}
		t_settle_ = t;
		settled_ = r.z() == R && v.z() == 0.0;
		if (settled_) {
			cloth_ = std::make_unique<ClosedForm>(p, id, r, Vector3d(v.x(), v.y(), 0.0), w);
			for (Event e : cloth_->events) {
				e.t += t_settle_;
				events.push_back(e);
			}
		}
	}

	std::string kind() const override { return "closed-form"; }

	bool settled() const { return settled_; }
	double rest_time() const { return settled_ ? t_settle_ + cloth_->rest_time() : HUGE_VAL; }

	/// Whether the path up to `until` (s) stays clear of the cushions.
	bool clear_of(double xmin, double xmax, double ymin, double ymax, double until) const {
		auto inside = [&](const Vector3d &r) {
			return r.x() >= xmin && r.x() <= xmax && r.y() >= ymin && r.y() <= ymax;
		};
		// Horizontally a flight is a straight segment: its ends tell.
		for (const Flight &f : flights_)
			if (f.t0 <= until && (!inside(f.r0) || !inside(f.r0 + f.v0 * (std::min(f.t1, until) - f.t0))))
				return false;
		return !settled_ || until < t_settle_ || cloth_->clear_of(xmin, xmax, ymin, ymax, until - t_settle_);
	}

	std::vector<BallSample> state_at(double t) const override {
		BallSample s;
		s.id = id_;
		if (settled_ && t >= t_settle_)
			return cloth_->state_at(t - t_settle_);
		// The flight holding t (the last one beyond the horizon of a ball that never settles).
		const Flight *f = flights_.empty() ? nullptr : &flights_.back();
		for (const Flight &c : flights_)
			if (t < c.t1) {
				f = &c;
				break;
			}
		if (!f)
			return {s};
		const double tau = std::max(0.0, t - f->t0);
		s.state = POOL_MOTION_AIRBORNE;
		s.pos = f->r0 + f->v0 * tau - 0.5 * p_.g * tau * tau * kUp;
		s.vel = f->v0 - p_.g * tau * kUp;
		s.omega = f->w;
		return {s};
	}

private:
	pool_params p_;
	int id_;
	std::vector<Flight> flights_;
	double t_settle_ = 0.0;
	bool settled_ = false;
	std::unique_ptr<ClosedForm> cloth_;
};

class NoReference final : public Reference {
public:
	explicit NoReference(std::string why) : why_(std::move(why)) {}
	std::string kind() const override { return "none"; }
	bool has_truth() const override { return false; }
	std::string why_none() const override { return why_; }
	std::vector<BallSample> state_at(double) const override { return {}; }

private:
	std::string why_;
};

} // namespace

bool cloth_impact(const pool_params &p, Vector3d *v, Vector3d *w) {
	// Petit's law with body 2 an immovable obstacle (M1/M2 = 0, v2 = w2 = 0), n = k.
	const double R = p.ball_radius, N = p.e_table, mu = p.mu_table;
	const Vector3d &n = kUp;
	const Vector3d Vc = *v - v->dot(n) * n + n.cross(R * *w); // slip of the contact point
	const double P_over_m = (1.0 + N) * (-v->dot(n));        // normal impulse / M1
	const double slip = Vc.norm();
	const bool slipping = slip > 0.0 && 1.0 - 3.5 * mu * P_over_m / slip >= 0.0;
	if (slipping) {
		const Vector3d c = Vc / slip;
		*v += P_over_m * (n - mu * c);
		*w += (2.5 * mu * P_over_m / R) * n.cross(c);
	} else {
		*v += P_over_m * n - (2.0 / 7.0) * Vc;
		*w += (5.0 / (7.0 * R)) * n.cross(Vc);
	}
	return slipping;
}

// The closed forms strike the ball by docs/physics.md "Cue strike" alone: with squirt selected an
// off-centre strike launches the ball elsewhere, so they do not apply (libpool's reference does,
// with the scenario's models). The other optional models act only at cushions and between balls,
// which a closed-form shot never meets.
static bool squirt_changes_strike(const pool_scenario &sc) {
	return sc.has_strike && sc.strike.a != 0.0 && sc.def.models.squirt != POOL_SQUIRT_NONE;
}

std::unique_ptr<Reference> make_airborne_closed_form_reference(const Scenario &scenario) {
	const pool_scenario &sc = scenario.parsed;
	const pool_params &p = sc.def.params;
	if (sc.ball_count != 1 || !sc.def.airborne || !(p.mu_slide > 0.0) || !(p.mu_roll > 0.0) || !(p.g > 0.0) ||
	    squirt_changes_strike(sc))
		return nullptr;
	const pool_ball_state &b = sc.balls[0];
	Vector3d r0(b.pos.x, b.pos.y, b.pos.z), v0(b.vel.x, b.vel.y, b.vel.z), w0(b.omega.x, b.omega.y, b.omega.z);
	if (sc.has_strike)
		strike_velocities(p, sc.strike, false, &v0, &w0);
	// The horizon: states are exact up to a second past max_time (Reference::state_at).
	auto cf = std::make_unique<AirborneClosedForm>(p, b.id, r0, v0, w0, sc.def.max_time + 1.0);
	const pool_table_def &t = sc.def.table;
	const double R = p.ball_radius, h = t.cushion_height;
	// Cushions out of reach: a ball on the cloth touches a nose at this distance from its line,
	// a flying one no further than R.
	const double reach = std::max(R, h > R ? std::sqrt(R * R - (h - R) * (h - R)) : R);
	// Up to a second past max_time: a time-stepped engine may stop a step past it.
	if (!cf->clear_of(reach, t.length - reach, reach, t.width - reach, sc.def.max_time + 1.0))
		return nullptr;
	const double rest = cf->rest_time();
	cf->at_rest = rest <= sc.def.max_time;
	cf->end_time = cf->at_rest ? rest : sc.def.max_time;
	// Only what happens up to the end counts.
	std::vector<Event> kept;
	for (const Event &e : cf->events)
		if (e.t <= cf->end_time)
			kept.push_back(e);
	cf->events = kept;
	std::vector<Landing> landed;
	for (const Landing &l : cf->landings)
		if (l.t <= cf->end_time)
			landed.push_back(l);
	cf->landings = landed;
	std::vector<Apex> tops;
	for (const Apex &a : cf->apexes)
		if (a.t <= cf->end_time)
			tops.push_back(a);
	cf->apexes = tops;
	return cf;
}

std::unique_ptr<Reference> make_no_reference(const Scenario &scenario, const std::string &why) {
	auto ref = std::make_unique<NoReference>(why);
	ref->end_time = scenario.parsed.def.max_time;
	ref->at_rest = false;
	return ref;
}

void strike_velocities(const pool_params &p, const pool_strike &s, bool planar, Vector3d *vel,
                       Vector3d *omega) {
	const double R = p.ball_radius, m = p.ball_mass;
	const Vector3d j(std::cos(s.phi), std::sin(s.phi), 0.0);
	const Vector3d right = j.cross(kUp);
	const Vector3d d = std::cos(s.theta) * j - std::sin(s.theta) * kUp;
	const double c = std::sqrt(R * R - s.a * s.a - s.b * s.b);
	const Vector3d Q = s.a * right + s.b * kUp - c * j;
	const double F = 2.0 * m * s.speed / (1.0 + m / p.cue_mass + 5.0 / (2.0 * R * R) * Q.cross(d).squaredNorm());
	const double I = 0.4 * m * R * R;
	*vel = (F / m) * d;
	*omega = Q.cross(F * d) / I;
	if (planar)
		vel->z() = 0.0;
}

std::unique_ptr<Reference> make_closed_form_reference(const Scenario &scenario) {
	const pool_scenario &sc = scenario.parsed;
	const pool_params &p = sc.def.params;
	if (sc.ball_count != 1 || sc.def.airborne || !(p.mu_slide > 0.0) || !(p.mu_roll > 0.0) ||
	    squirt_changes_strike(sc))
		return nullptr;
	const pool_ball_state &b = sc.balls[0];
	const double R = p.ball_radius;
	if (std::fabs(b.pos.z - R) > 1e-12)
		return nullptr;
	Vector3d r0(b.pos.x, b.pos.y, b.pos.z), v0(b.vel.x, b.vel.y, 0.0), w0(b.omega.x, b.omega.y, b.omega.z);
	if (sc.has_strike)
		strike_velocities(p, sc.strike, true, &v0, &w0);
	auto cf = std::make_unique<ClosedForm>(p, b.id, r0, v0, w0);
	// A ball on the cloth touches a nose when its centre is this far from the nose line.
	const pool_table_def &t = sc.def.table;
	const double h = t.cushion_height;
	const double reach = h > R ? std::sqrt(R * R - (h - R) * (h - R)) : R;
	if (!cf->clear_of(reach, t.length - reach, reach, t.width - reach))
		return nullptr;
	const double rest = cf->rest_time();
	cf->at_rest = rest <= sc.def.max_time;
	cf->end_time = cf->at_rest ? rest : sc.def.max_time;
	return cf;
}

double kinetic_energy(const std::vector<BallSample> &balls, const pool_params &p) {
	const double m = p.ball_mass, I = 0.4 * p.ball_mass * p.ball_radius * p.ball_radius;
	double e = 0.0;
	for (const BallSample &b : balls)
		if (b.state != 6 && b.state != 7)
			e += 0.5 * m * b.vel.squaredNorm() + 0.5 * I * b.omega.squaredNorm();
	return e;
}

} // namespace pool_compare
