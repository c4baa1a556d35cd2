// A candidate refined by simulation: the aim phi that sends the potted ball through the pocket's
// aiming point (a root of the signed miss, by the secant method), more speed when it stops
// short, then the shot checked without noise. Throw, cut-induced spin, the cushion's rebound and
// the curve of a sliding ball are in the simulation, not in a formula.
#include <math.h>

#include "aim_internal.h"

// m: the miss at which the aim is taken as found. A mouth takes a ball within about 2 cm of its
// middle head on (Alciatore TP 3.5 and 3.6); a millimetre leaves the margin to the noise.
#define AIM_MISS_TOLERANCE 1e-3
// The secant's first step (rad, 0.05 degree), its largest step (2 degrees), its iterations.
#define AIM_FIRST_STEP (0.05 * AIM_DEG)
#define AIM_MAX_STEP (2.0 * AIM_DEG)
#define AIM_ITERATIONS 12
// A shot that falls short is tried again this much faster, up to this many times and this speed.
#define AIM_SPEED_BOOST 1.5
#define AIM_BOOSTS 2
#define AIM_FASTEST 8.0

// The window of aims that pot: searched from the refined aim outwards in steps doubling from
// this (rad, 0.02 degree) up to this far (2 degrees), then its edges bisected this many times.
#define AIM_WINDOW_STEP (0.02 * AIM_DEG)
#define AIM_WINDOW_REACH (2.0 * AIM_DEG)
#define AIM_WINDOW_BISECTIONS 6

typedef enum outcome { FOUND, SHORT, LOST } outcome;

/// The miss at phi; false when the shot did not go as meant (or the library refused it).
static bool miss_at(aim_search *s, aim_worker *w, const aim_candidate *c, pool_strike strike, double phi,
                    double *miss, bool *short_) {
	strike.phi = phi;
	pool_result r = aim_simulate(s, w, c, &strike);
	if (r != POOL_OK) {
		if (r == POOL_ERR_OUT_OF_MEMORY || r == POOL_ERR_INTERNAL) {
			int none = 0;
			atomic_compare_exchange_strong(&s->failure, &none, (int)r);
		}
		return false;
	}
	return aim_miss(s, w, c, miss, short_);
}

/// The secant method on the miss in phi, from the strike's phi. On FOUND, *phi is the root.
static outcome aim_phi(aim_search *s, aim_worker *w, const aim_candidate *c, const pool_strike *strike, double *phi) {
	double p0 = strike->phi, m0, p1, m1;
	bool short0, short1;
	if (!miss_at(s, w, c, *strike, p0, &m0, &short0))
		return LOST;
	if (fabs(m0) < AIM_MISS_TOLERANCE) {
		*phi = p0;
		return FOUND;
	}
	p1 = p0 + AIM_FIRST_STEP;
	if (!miss_at(s, w, c, *strike, p1, &m1, &short1)) {
		p1 = p0 - AIM_FIRST_STEP;
		if (!miss_at(s, w, c, *strike, p1, &m1, &short1))
			return short0 ? SHORT : LOST;
	}
	for (int k = 0; k < AIM_ITERATIONS; ++k) {
		if (fabs(m1) < AIM_MISS_TOLERANCE) {
			*phi = p1;
			return FOUND;
		}
		if (m1 == m0)
			break;
		double step = -m1 * (p1 - p0) / (m1 - m0);
		step = fmax(fmin(step, AIM_MAX_STEP), -AIM_MAX_STEP);
		double p2 = p1 + step, m2 = 0.0;
		bool short2 = false, ok = false;
		for (int half = 0; half < 4 && !(ok = miss_at(s, w, c, *strike, p2, &m2, &short2)); ++half)
			p2 = p1 + (step /= 2.0); // the shot changed its course: a smaller step
		if (!ok)
			break;
		p0 = p1, m0 = m1, short0 = short1;
		p1 = p2, m1 = m2, short1 = short2;
	}
	return short1 || short0 ? SHORT : LOST;
}

static bool pots_at(aim_search *s, aim_worker *w, const aim_candidate *c, pool_strike strike, double phi) {
	strike.phi = phi;
	return aim_simulate(s, w, c, &strike) == POOL_OK && aim_success(s, w, c);
}

/// One edge of the window of aims that pot, from phi (which pots) in direction side.
static double window_edge(aim_search *s, aim_worker *w, const aim_candidate *c, const pool_strike *strike,
                          double phi, double side) {
	double in = 0.0, out = AIM_WINDOW_STEP;
	while (out < AIM_WINDOW_REACH && pots_at(s, w, c, *strike, phi + side * out))
		in = out, out *= 2.0;
	for (int k = 0; k < AIM_WINDOW_BISECTIONS; ++k) {
		double mid = 0.5 * (in + out);
		if (pots_at(s, w, c, *strike, phi + side * mid))
			in = mid;
		else
			out = mid;
	}
	return phi + side * 0.5 * (in + out);
}

/// The aim in the middle of the window of aims that pot without noise. The mouth's middle is the
/// pocket's middle only head on: from an angle one jaw stands in the way sooner than the other,
/// and throw moves the window too; the middle of the window leaves the most room to an aiming
/// error either way, the noise that matters most.
static double center_window(aim_search *s, aim_worker *w, const aim_candidate *c, const pool_strike *strike,
                            double phi) {
	double lo = window_edge(s, w, c, strike, phi, -1.0), hi = window_edge(s, w, c, strike, phi, 1.0);
	double mid = 0.5 * (lo + hi);
	return pots_at(s, w, c, *strike, mid) ? mid : phi;
}

void aim_refine(aim_search *s, aim_worker *w, aim_candidate *c) {
	if (atomic_load(&s->out_of_time) || aim_now() > s->refine_deadline) {
		atomic_store(&s->out_of_time, true);
		c->state = AIM_SKIPPED;
		return;
	}
	pool_strike strike = c->strike;
	double phi = strike.phi;
	outcome o = LOST;
	for (int boost = 0; boost <= AIM_BOOSTS; ++boost) {
		o = aim_phi(s, w, c, &strike, &phi);
		if (o != SHORT || strike.speed >= AIM_FASTEST)
			break;
		strike.speed = fmin(strike.speed * AIM_SPEED_BOOST, AIM_FASTEST);
	}
	c->state = AIM_MISSES;
	if (o != FOUND)
		return;
	strike.phi = remainder(phi, 2.0 * AIM_PI);
	// The refined aim may cross a ball the first guess's did not: the cue is checked again.
	double theta = aim_cue_elevation(s, strike.phi, strike.a, strike.b, strike.theta);
	if (theta < 0.0) {
		c->state = AIM_BLOCKED;
		return;
	}
	if (theta != strike.theta) { // raised over a ball: a new shot, aimed afresh
		strike.theta = theta;
		if (aim_phi(s, w, c, &strike, &phi) != FOUND)
			return;
		strike.phi = remainder(phi, 2.0 * AIM_PI);
	}
	if (!pots_at(s, w, c, strike, strike.phi))
		return;
	strike.phi = center_window(s, w, c, &strike, strike.phi);
	if (!pots_at(s, w, c, strike, strike.phi)) // (center_window's last shot, run again for the final state)
		return;
	c->strike = strike;
	c->state = AIM_POTS;
	const pool_ball_state *final = pool_sim_balls(w->sim);
	c->cue_final = (aim_xy){final[s->cue].pos.x, final[s->cue].pos.y};
	if (s->def->position)
		c->position = aim_position_score(s, c, w);
}
