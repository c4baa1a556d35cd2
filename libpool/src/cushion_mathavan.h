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

/// Error tolerance of each integration step, relative to the impact's speed scale (its largest
/// velocity or surface speed R |w| component). At this value the outgoing velocities differ from
/// the same equations integrated far finer (tools/mathavan_reference.c) by at most
/// MATHAVAN_RANDOM_WORST of the speed scale over random impacts (0.1-8 m/s, any incidence, spin
/// and side; test_model_fidelity.c). Cost: bench/bench_models.c.
#define POOL_MATHAVAN_TOLERANCE 1e-5

/// What pool_cushion_mathavan did.
typedef enum pool_mathavan_outcome {
	POOL_MATHAVAN_SEPARATING = 0, ///< the ball was not moving into the nose: unchanged
	POOL_MATHAVAN_RESOLVED = 1,   ///< compression and restitution integrated
	POOL_MATHAVAN_JAMMED = 2,     ///< friction kept the ball pressing (huge mu): unchanged
} pool_mathavan_outcome;

/// Resolves the impact of ball s (on the cloth) with a cushion nose; n is the unit normal from
/// the nose to the ball centre (pool_cushion_normal). tolerance: of each integration step
/// (POOL_MATHAVAN_TOLERANCE; smaller is finer and dearer). Only s->vel and s->omega change; the
/// caller derives the motion state. Deterministic: a fixed sequence of double operations.
pool_mathavan_outcome pool_cushion_mathavan(pool_ball_state *s, const pool_params *p, pool_vec3 n, double tolerance);

/// The cushion handler's entry (cushion.c): resolves s's impact by this model when the def
/// selects it (models.cushion) and the ball is on the cloth, and says so; false leaves s to
/// Petit's law: another model, a ball in flight (the model's cloth contact is absent), or a
/// jammed impact.
bool pool_cushion_mathavan_resolve(const pool_sim_def *def, pool_ball_state *s, pool_vec3 n);

#endif
