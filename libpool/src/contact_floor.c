// The separation floor (contact_floor.h).
#include "contact_floor.h"

#include <math.h>

#include "contact.h"
#include "motion.h"
#include "sim_internal.h"
#include "vec3.h"

int pool_contact_floor(const pool_params *p, pool_ball_state *s1, pool_ball_state *s2, pool_vec3 n) {
	pool_vec3 a = pool_motion_accel(p, s1);
	pool_vec3 v = s1->vel;
	if (s2) {
		a = pool_v3_sub(a, pool_motion_accel(p, s2));
		v = pool_v3_sub(v, s2->vel);
	}
	const double an = pool_v3_dot(a, n), vn = pool_v3_dot(v, n);
	if (!(an < 0.0))
		return 0;
	// At least POOL_SEPARATION_MIN, or the next prediction would find the same contact "now"
	// again (contact.h) when the pull is weaker than 2 POOL_SEPARATION_MIN / the interval.
	const double floor = fmax(-an * POOL_CONTACT_MIN_INTERVAL * 0.5, POOL_SEPARATION_MIN);
	if (vn >= floor)
		return 0;
	const double dv = floor - vn;
	if (s2) {
		s1->vel = pool_v3_madd(s1->vel, 0.5 * dv, n);
		s2->vel = pool_v3_madd(s2->vel, -0.5 * dv, n);
		pool_motion_derive(p, s2);
	} else {
		s1->vel = pool_v3_madd(s1->vel, dv, n);
	}
	pool_motion_derive(p, s1);
	return 1;
}

double pool_floor_energy_bound(const pool_params *p) {
	const double an = 2.0 * fmax(p->mu_slide, p->mu_roll) * p->g;
	const double f = fmax(an * POOL_CONTACT_MIN_INTERVAL * 0.5, POOL_SEPARATION_MIN);
	return 0.25 * p->ball_mass * f * f;
}
