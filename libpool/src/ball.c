// Ball states users build (pool/ball.h).
#include "pool/ball.h"

pool_ball_state pool_ball_on_cloth(int32_t id, double x, double y, const pool_params *params) {
	// Without params the default ball (pool_default_params) sits on the cloth.
	const double radius = params ? params->ball_radius : pool_default_params().ball_radius;
	pool_ball_state s = {.id = id, .motion = POOL_MOTION_STATIONARY, .pos = {x, y, radius}};
	return s;
}
