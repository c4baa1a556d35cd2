// Ball-cloth events with airborne motion (docs/physics.md "Ball–cloth", "Airborne"): a landing, or a
// ball pressed into the cloth by a strike, a cushion or another ball, is Petit's law with the
// cloth as the obstacle; a ball that clears a rail leaves the table.
#include <math.h>

#include "collision.h"
#include "handlers.h"
#include "vec3.h"

int pool_handle_ball_table(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count) {
	(void)type;
	(void)count;
	const pool_params *p = &ctx->def->params;
	const double R = p->ball_radius;
	s[0].pos.z = R; // the contact rule met the cloth within POOL_TOUCH_TOLERANCE
	pool_collide(&s[0], R, p->ball_mass, NULL, R, 0.0, pool_v3(0.0, 0.0, 1.0), p->e_table, p->mu_table);
	// A rebound too weak to fly POOL_SETTLE_FLIGHT_TIME settles: the bounces end.
	if (2.0 * s[0].vel.z / p->g < POOL_SETTLE_FLIGHT_TIME)
		s[0].vel.z = 0.0;
	pool_motion_after_impulse(ctx->def, &s[0]);
	return 0;
}

int pool_handle_off_table(const pool_event_context *ctx, pool_event_type type, pool_ball_state *s, int count) {
	(void)ctx;
	(void)type;
	(void)count;
	pool_take_out_of_play(&s[0], POOL_MOTION_OFF_TABLE);
	return 0;
}
