// The "mathavan2010" cushion model (docs/physics.md "Models"): Mathavan, Jackson & Parkin,
// "A theoretical analysis of billiard ball dynamics under cushion impacts", Proc. IMechE Part C
// 224 (2010). The cushion contact I (at the nose, e_cushion_mathavan, mu_cushion_mathavan: the
// paper's fit, not Petit's e_cushion and mu_cushion) and the cloth contact C
// (under the ball, mu_table) act together through the impact; the ball's velocities are
// integrated over the normal impulse P at I through compression and restitution, restitution by
// Stronge's energetic coefficient (the normal force at I gives back e^2 of the work it absorbed
// in compression), and the ball is kept on the cloth (the cloth's normal impulse is whatever
// holds v_z at zero).
#ifndef POOL_CUSHION_MATHAVAN_H
#define POOL_CUSHION_MATHAVAN_H

#include <stdbool.h>

#include "pool/sim.h"

/// Impulse steps over the estimated impact. The scheme (cushion_mathavan.c) is of second order
/// while the contacts slide and of first order across stick-slip transitions; at this count,
/// against a 64 times finer run, the rebound velocity is within 1e-3 of the impact speed and the
/// rebound angle within 0.05 degrees at 1 m/s over incidences 0-80 degrees, stun to rolling,
/// running and check side (test_model_fidelity.c, MATHAVAN_CONVERGENCE); over random impacts
/// (0.1-8 m/s, any incidence, spin and side) the outgoing velocities are within 2.3e-6 of the
/// impact's speed scale at the median and 7.4e-3 at worst, where a contact changes between stick
/// and slip (MATHAVAN_RANDOM_*). Cost: tools/bench_models (about 6 us an impact).
#define POOL_MATHAVAN_STEPS 128

/// What pool_cushion_mathavan did.
typedef enum pool_mathavan_outcome {
	POOL_MATHAVAN_SEPARATING = 0, ///< the ball was not moving into the nose: unchanged
	POOL_MATHAVAN_RESOLVED = 1,   ///< compression and restitution integrated
	POOL_MATHAVAN_JAMMED = 2,     ///< friction kept the ball pressing (huge mu): unchanged
} pool_mathavan_outcome;

/// Resolves the impact of ball s (on the cloth) with a cushion nose; n is the unit normal from
/// the nose to the ball centre (pool_cushion_normal). steps: impulse steps over the estimated
/// impact (POOL_MATHAVAN_STEPS; more for a reference). Only s->vel and s->omega change; the
/// caller derives the motion state. Deterministic: a fixed sequence of double operations.
pool_mathavan_outcome pool_cushion_mathavan(pool_ball_state *s, const pool_params *p, pool_vec3 n, int steps);

/// The cushion handler's entry (cushion.c): resolves s's impact by this model when the def
/// selects it (models.cushion) and the ball is on the cloth, and says so; false leaves s to
/// Petit's law: another model, a ball in flight (the model's cloth contact is absent), or a
/// jammed impact.
bool pool_cushion_mathavan_resolve(const pool_sim_def *def, pool_ball_state *s, pool_vec3 n);

#endif
