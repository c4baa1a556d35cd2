// Ball-ball events: Petit's law between two balls (docs/physics.md "Collisions", "Ball–ball").
#include <math.h>

#include "ball_friction.h"
#include "collision.h"
#include "handlers.h"
#include "motion.h"
#include "vec3.h"

int pool_handle_ball_ball(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count) {
	(void)type;
	(void)count;
	const pool_params *p = &ctx->def->params;
	pool_vec3 n = pool_v3_sub(s[0].pos, s[1].pos); // towards body 1, the ball with the smaller id
	n = pool_v3_scale(n, 1.0 / pool_v3_len(n));
	const double mu = pool_ball_ball_mu(ctx->def, &s[0], &s[1], n); // models.ball_ball_friction
	pool_collide(&s[0], p->ball_radius, p->ball_mass, &s[1], p->ball_radius, 1.0, n, p->e_ball, mu);
	for (int k = 0; k < 2; ++k)
		pool_motion_after_impulse(ctx->def, &s[k]);
	return 0;
}
