// Ball-ball friction by the def's model (docs/physics.md "Models"): "constant" is
// params.mu_ball; "alciatore" falls with the slip speed at the contact, as measured.
#ifndef POOL_BALL_FRICTION_H
#define POOL_BALL_FRICTION_H

#include "pool/sim.h"

/// Relative slip speed (m/s) of ball 1's contact point on ball 2's, tangential to n (the unit
/// normal towards ball 1), both of radius R: |Δv − (Δv·n) n + R n × (w1 + w2)|.
double pool_ball_ball_slip_speed(const pool_ball_state *b1, const pool_ball_state *b2, pool_vec3 n, double R);

/// The friction of the impact about to happen between b1 and b2 (states before it): mu_ball, or
/// Alciatore's mu(v) = throw_a + throw_b exp(-throw_c v) at the slip speed v (TP A.14).
double pool_ball_ball_mu(const pool_sim_def *def, const pool_ball_state *b1, const pool_ball_state *b2, pool_vec3 n);

#endif
