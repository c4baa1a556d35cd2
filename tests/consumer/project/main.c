// A user's program built against an installed libpool (through find_package and through
// pkg-config): the README's break, a ball placed with pool_ball_on_cloth, the quartic solver,
// and the library found at run time reports the version of the headers it was built with.
#include <math.h>
#include <stdio.h>

#include <pool/pool.h>

int main(void) {
	if (pool_version() != POOL_VERSION) {
		fprintf(stderr, "consumer: headers %d, library %d\n", POOL_VERSION, pool_version());
		return 1;
	}
	const double c[5] = {1.0, -10.0, 35.0, -50.0, 24.0};
	double roots[4];
	int n = pool_quartic_real_roots(c, roots);
	if (n != 4)
		return 1;
	for (int i = 0; i < 4; ++i)
		if (fabs(roots[i] - (i + 1)) > 1e-12)
			return 1;

	pool_sim_def def = pool_default_sim_def();
	pool_sim *sim;
	pool_error err;
	if (pool_sim_create(&def, &sim, &err) != POOL_OK)
		return fprintf(stderr, "%s\n", err.message), 1;
	pool_ball_state balls[16];
	int count = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 0.0, balls, 16);
	for (int i = 0; i < count; ++i)
		pool_sim_add_ball(sim, &balls[i], NULL);
	// A 17th ball on the cloth near the foot rail, away from the rack.
	pool_ball_state extra = pool_ball_on_cloth(99, 2.4, 0.2, &def.params);
	if (pool_sim_add_ball(sim, &extra, &err) != POOL_OK)
		return fprintf(stderr, "%s\n", err.message), 1;
	pool_strike s = pool_break_strike(8.0);
	if (pool_sim_strike(sim, 0, &s, &err) != POOL_OK || pool_sim_run(sim) != POOL_OK)
		return 1;
	int events;
	pool_sim_events(sim, &events);
	printf("consumer: libpool %d, 4 roots, break of %d events, stop: %s\n", pool_version(), events,
	       pool_stop_reason_name(pool_sim_stop_reason(sim)));
	int ok = events > 50 && pool_sim_stop_reason(sim) == POOL_STOP_REST;
	pool_sim_destroy(sim);
	return ok ? 0 : 1;
}
