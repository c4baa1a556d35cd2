// The closed-form motion of a single ball on the cloth (PHYSICS.md "Motion between events";
// VALIDATION.md 1-3): slide along a parabola until the slip vanishes, roll in a straight line
// until it stops, with the z-spin decaying independently.
#include <cmath>
#include <limits>

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

	/// Whether the whole path stays clear of the cushion noses (so no event but slide/roll/stop).
	bool clear_of(double xmin, double xmax, double ymin, double ymax) const {
		auto inside = [&](const Vector3d &r) {
			return r.x() >= xmin && r.x() <= xmax && r.y() >= ymin && r.y() <= ymax;
		};
		const int n = 512;
		for (int i = 0; i <= n; ++i)
			if (!inside(position_sliding(t_roll_ * i / n)))
				return false;
		return inside(state_at_one(t_stop_).pos); // the rolling path is a straight segment
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

} // namespace

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
	if (sc.ball_count != 1 || sc.def.airborne || !(p.mu_slide > 0.0) || !(p.mu_roll > 0.0))
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
