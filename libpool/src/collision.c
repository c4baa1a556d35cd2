// Petit's collision law (docs/physics.md "Collisions").
#include "collision.h"

#include <math.h>

#include "vec3.h"

double pool_collide(pool_ball_state *b1, double R1, double M1, pool_ball_state *b2, double R2,
                    double mass_ratio, pool_vec3 n, double N, double mu) {
	const pool_vec3 zero = pool_v3(0.0, 0.0, 0.0);
	const pool_vec3 v1 = b1->vel, w1 = b1->omega;
	const pool_vec3 v2 = b2 ? b2->vel : zero, w2 = b2 ? b2->omega : zero;
	const double r2 = b2 ? R2 : 0.0;
	const pool_vec3 dv = pool_v3_sub(v1, v2);
	// Slip of body 1's contact point relative to body 2's, tangential to n.
	const pool_vec3 vc = pool_v3_add(pool_v3_madd(dv, -pool_v3_dot(dv, n), n),
	                                 pool_v3_cross(n, pool_v3_madd(pool_v3_scale(w1, R1), r2, w2)));
	const double k = 1.0 + mass_ratio;
	const double P = (1.0 + N) * M1 * pool_v3_dot(pool_v3_sub(v2, v1), n) / k;
	// Bodies already separating (or exactly tangent) exchange no impulse: a negative P would
	// pull them together and could add energy. The caller's prediction said "touching"; the
	// velocities at the event, rounded differently, may say "leaving" by a hair.
	if (!(P > 0.0))
		return 0.0;
	const double vclen = pool_v3_len(vc);
	pool_vec3 v1n, w1n;
	// Sticking when friction can stop the slip during the impulse (s < 0) or there is none.
	const double s = vclen > 0.0 ? 1.0 - 3.5 * mu * k * (P / M1) / vclen : -1.0;
	if (s >= 0.0) {
		const pool_vec3 vchat = pool_v3_scale(vc, 1.0 / vclen);
		v1n = pool_v3_madd(v1, P / M1, pool_v3_madd(n, -mu, vchat));
		w1n = pool_v3_madd(w1, 5.0 * mu * P / (2.0 * M1 * R1), pool_v3_cross(n, vchat));
	} else {
		v1n = pool_v3_madd(pool_v3_madd(v1, P / M1, n), -2.0 / (7.0 * k), vc);
		w1n = pool_v3_madd(w1, 5.0 / (7.0 * R1 * k), pool_v3_cross(n, vc));
	}
	if (b2 && mass_ratio > 0.0) {
		b2->vel = pool_v3_madd(v2, mass_ratio, pool_v3_sub(v1, v1n));
		b2->omega = pool_v3_madd(w2, mass_ratio * R1 / R2, pool_v3_sub(w1n, w1));
	}
	b1->vel = v1n;
	b1->omega = w1n;
	return P;
}
