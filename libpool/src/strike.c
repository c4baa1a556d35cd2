// The five-parameter cue strike (docs/physics.md "Cue strike", Leckie & Greenspan impulse).
#include "pool/strike.h"

#include <math.h>

#include "error.h"
#include "models.h"
#include "pool/ball.h"
#include "vec3.h"

pool_result pool_strike_velocities(const pool_params *params, const pool_strike *strike,
                                   pool_vec3 *vel, pool_vec3 *omega, pool_error *error) {
	if (!params || !strike || !vel || !omega)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "strike: missing argument");
	const double R = params->ball_radius, m = params->ball_mass, M = params->cue_mass;
	const double fields[5] = {strike->speed, strike->phi, strike->theta, strike->a, strike->b};
	static const char *const names[5] = {"strike.speed", "strike.phi", "strike.theta", "strike.a", "strike.b"};
	for (int i = 0; i < 5; ++i)
		if (!isfinite(fields[i]))
			return pool_error_set(error, POOL_ERR_NON_FINITE, "%s: must be finite", names[i]);
	if (!(strike->speed > 0.0))
		return pool_error_set(error, POOL_ERR_BAD_STRIKE, "strike.speed: must be > 0");
	if (strike->speed > POOL_MAX_SPEED)
		return pool_error_set(error, POOL_ERR_BAD_STRIKE, "strike.speed: %g m/s is above the %g m/s limit (POOL_MAX_SPEED)",
		                      strike->speed, POOL_MAX_SPEED);
	if (!(strike->theta >= 0.0 && strike->theta < 1.57079632679489661923))
		return pool_error_set(error, POOL_ERR_BAD_STRIKE, "strike.theta: must be in [0, pi/2) rad");
	const double c2 = R * R - strike->a * strike->a - strike->b * strike->b;
	if (!(c2 > 0.0))
		return pool_error_set(error, POOL_ERR_BAD_STRIKE, "strike.a: a^2 + b^2 must be < R^2");
	const pool_vec3 k = pool_v3(0.0, 0.0, 1.0);
	const pool_vec3 j = pool_v3(cos(strike->phi), sin(strike->phi), 0.0);
	const pool_vec3 r = pool_v3_cross(j, k);
	const pool_vec3 d = pool_v3_madd(pool_v3_scale(j, cos(strike->theta)), -sin(strike->theta), k);
	const double c = sqrt(c2);
	const pool_vec3 Q = pool_v3_madd(pool_v3_madd(pool_v3_scale(r, strike->a), strike->b, k), -c, j);
	const pool_vec3 qd = pool_v3_cross(Q, d);
	const double F = 2.0 * m * strike->speed /
	                 (1.0 + m / M + (5.0 / (2.0 * R * R)) * pool_v3_dot(qd, qd));
	const double I = 0.4 * m * R * R;
	const pool_vec3 v = pool_v3_scale(d, F / m), w = pool_v3_scale(qd, F / I);
	// Safety net for parameters whose products overflow or underflow: never hand out NaN.
	if (!(isfinite(v.x) && isfinite(v.y) && isfinite(v.z) && isfinite(w.x) && isfinite(w.y) &&
	      isfinite(w.z)))
		return pool_error_set(error, POOL_ERR_NON_FINITE,
		                      "strike.speed: the ball's velocity or spin is not finite with these params");
	// A light ball under a heavy cue leaves at up to twice the cue speed: the ball's own limit.
	if (pool_v3_len(v) > POOL_MAX_SPEED || pool_v3_len(w) * R > POOL_MAX_SPEED)
		return pool_error_set(error, POOL_ERR_BAD_STRIKE,
		                      "strike.speed: the ball would leave faster than %g m/s (POOL_MAX_SPEED) with these params",
		                      POOL_MAX_SPEED);
	*vel = v;
	*omega = w;
	return pool_error_ok(error);
}

// Squirt (Alciatore TP A.31): the tip's contact with the ball lasts long enough for the ball's
// side spin to push the cue's end sideways; only the shaft's end mass m_e takes part, so the
// ball's launch turns away from the offset side by the angle of that sideways impulse.
double pool_squirt_angle(const pool_params *params, double a) {
	const double x = a / params->ball_radius, rest = 1.0 - x * x;
	if (!(rest > 0.0))
		return 0.0; // outside the ball: no strike
	return atan(2.5 * x * sqrt(rest) / (1.0 + params->ball_mass / params->cue_end_mass + 2.5 * rest));
}

pool_result pool_strike_velocities_modelled(const pool_params *params, pool_squirt_model squirt,
                                            const pool_strike *strike, pool_vec3 *vel, pool_vec3 *omega,
                                            pool_error *error) {
	pool_result r = pool_strike_velocities(params, strike, vel, omega, error);
	if (r || squirt != POOL_SQUIRT_ENDMASS)
		return r;
	const double alpha = pool_squirt_angle(params, strike->a), c = cos(alpha), s = sin(alpha);
	const pool_vec3 v = *vel;
	vel->x = c * v.x - s * v.y;
	vel->y = s * v.x + c * v.y;
	return POOL_OK;
}
