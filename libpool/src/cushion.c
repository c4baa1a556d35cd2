// Ball-cushion and pocket events (docs/physics.md "Ball–cushion", "Pocket", "Table geometry"):
// Petit's law (or mathavan2010) with the nose as an immovable obstacle; a pocket takes the ball.
#include <math.h>

#include "collision.h"
#include "cushion_mathavan.h"
#include "geometry.h"
#include "handlers.h"
#include "motion.h"
#include "vec3.h"

int pool_handle_ball_cushion(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count) {
	(void)type;
	(void)count;
	const pool_params *p = &ctx->def->params;
	// The normal from the contact point on the nose curve to the centre: a nose line's nearest
	// point (the thesis model's four lines), or that of the part hit (a nose segment, a facing, a
	// jaw), so a ball entering a pocket steeply is sent back out by the same law.
	const pool_vec3 n = ctx->part >= 0 ? pool_shape_normal(ctx->shape, ctx->part, s[0].pos)
	                                   : pool_cushion_normal(&ctx->def->table, s[0].pos, ctx->rail);
	if (!pool_cushion_mathavan_resolve(ctx->def, &s[0], n)) // models.cushion "mathavan2010"
		pool_collide(&s[0], p->ball_radius, p->ball_mass, NULL, p->ball_radius, 0.0, n, p->e_cushion, p->mu_cushion);
	pool_motion_after_impulse(ctx->def, &s[0]); // airborne mode: pressed into the cloth, a hop may follow
	return 0;
}

int pool_handle_pocket(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count) {
	(void)ctx;
	(void)type;
	(void)count;
	pool_take_out_of_play(&s[0], POOL_MOTION_POCKETED);
	return 0;
}
