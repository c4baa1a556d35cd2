// A user's program that happens to define functions named like libpool's internal ones
// (pool_collide, pool_error_set, pool_predict_ball_ball) and links libpool.a statically. With
// the internals local to libpool.a this links and both sides call their own functions; with
// them global the link fails with "multiple definition".
#include <stdio.h>

#include <pool/pool.h>

int pool_collide(int x);
int pool_error_set(int x);
int pool_predict_ball_ball(int x);

int pool_collide(int x) { return x + 1; }
int pool_error_set(int x) { return x + 2; }
int pool_predict_ball_ball(int x) { return x + 3; }

int main(void) {
	if (pool_collide(1) != 2 || pool_error_set(1) != 3 || pool_predict_ball_ball(1) != 4)
		return 1;
	// A straight shot into a second ball: libpool's own collision code must run.
	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim = NULL;
	pool_error err = {{0}};
	if (pool_sim_create(&def, &sim, &err) != POOL_OK)
		return 1;
	pool_ball_state a = {0}, b = {0};
	a.id = 0, a.pos.x = 0.635, a.pos.y = 0.635, a.pos.z = def.params.ball_radius;
	b.id = 1, b.pos.x = 1.905, b.pos.y = 0.635, b.pos.z = def.params.ball_radius;
	pool_strike strike = {0};
	strike.speed = 2.0;
	if (pool_sim_add_ball(sim, &a, &err) != POOL_OK || pool_sim_add_ball(sim, &b, &err) != POOL_OK ||
	    pool_sim_strike(sim, 0, &strike, &err) != POOL_OK || pool_sim_run(sim) != POOL_OK) {
		fprintf(stderr, "static_clash: %s\n", err.message);
		return 1;
	}
	int count = 0, hits = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	for (int i = 0; i < count; ++i)
		hits += events[i].type == POOL_EVENT_BALL_BALL;
	pool_sim_destroy(sim);
	printf("static_clash: %d events, %d ball-ball collisions\n", count, hits);
	return hits >= 1 ? 0 : 1;
}
