// Ball-ball friction models. Alciatore, "Throw, TP A.14" (billiards.colostate.edu): the friction
// between balls measured by Marlow falls with the relative slip speed at the contact; his fit
// mu(v) = a + b exp(-c v) (a 9.951e-3, b 0.108, c 1.088 s/m) reproduces the measured throw
// falling with speed (a 30 degree stun cut throws more when slow).
#include "ball_friction.h"

#include <math.h>

#include "vec3.h"

double pool_ball_ball_slip_speed(const pool_ball_state *b1, const pool_ball_state *b2, pool_vec3 n, double R) {
	const pool_vec3 dv = pool_v3_sub(b1->vel, b2->vel);
	const pool_vec3 slip = pool_v3_add(pool_v3_madd(dv, -pool_v3_dot(dv, n), n),
	                                   pool_v3_cross(n, pool_v3_scale(pool_v3_add(b1->omega, b2->omega), R)));
	return pool_v3_len(slip);
}

double pool_ball_ball_mu(const pool_sim_def *def, const pool_ball_state *b1, const pool_ball_state *b2, pool_vec3 n) {
	const pool_params *p = &def->params;
	if (def->models.ball_ball_friction != POOL_BALL_FRICTION_ALCIATORE)
		return p->mu_ball;
	const double v = pool_ball_ball_slip_speed(b1, b2, n, p->ball_radius);
	return p->throw_a + p->throw_b * exp(-p->throw_c * v);
}
