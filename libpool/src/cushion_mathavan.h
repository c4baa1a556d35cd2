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

/// Impulse steps over the estimated impact (cushion_mathavan.c).
#define POOL_MATHAVAN_STEPS 128
/// Substeps of a step where a contact changes between sticking and sliding.
#define POOL_MATHAVAN_SUBSTEPS 16

/// What pool_cushion_mathavan did.
typedef enum pool_mathavan_outcome {
	POOL_MATHAVAN_SEPARATING = 0, ///< the ball was not moving into the nose: unchanged
	POOL_MATHAVAN_RESOLVED = 1,   ///< compression and restitution integrated
	POOL_MATHAVAN_JAMMED = 2,     ///< friction kept the ball pressing (huge mu): unchanged
} pool_mathavan_outcome;

/// Resolves the impact of ball s (on the cloth) with a cushion nose; n is the unit normal from
/// the nose to the ball centre (pool_cushion_normal). steps: impulse steps over the estimated
/// impact (POOL_MATHAVAN_STEPS; more for a finer run). Only s->vel and s->omega change; the
/// caller derives the motion state. Deterministic: a fixed sequence of double operations.
pool_mathavan_outcome pool_cushion_mathavan(pool_ball_state *s, const pool_params *p, pool_vec3 n, int steps);

/// The cushion handler's entry (cushion.c): resolves s's impact by this model when the def
/// selects it (models.cushion) and the ball is on the cloth, and says so; false leaves s to
/// Petit's law: another model, a ball in flight (the model's cloth contact is absent), or a
/// jammed impact.
bool pool_cushion_mathavan_resolve(const pool_sim_def *def, pool_ball_state *s, pool_vec3 n);

#endif
