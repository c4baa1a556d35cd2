// The reference the mathavan2010 cushion (libpool/src/cushion_mathavan.c) is judged by: the same
// equations of Mathavan, Jackson & Parkin (2010) integrated in fixed impulse steps, a scheme
// independent of the library's adaptive one (libpool's own before it, at 128 steps). Run at many
// steps by pool-bench-models --accuracy and tests/unit/test_model_fidelity.c; not in the library.
#ifndef POOL_MATHAVAN_REFERENCE_H
#define POOL_MATHAVAN_REFERENCE_H

#include <stdint.h>

#include "cushion_mathavan.h"

/// Resolves the impact of ball s (on the cloth) with a cushion nose of unit normal n (from the
/// nose to the ball centre) in `steps` equal impulse steps over the estimated impact: first order
/// in 1/steps across stick-slip transitions, second order elsewhere. Only s->vel and s->omega
/// change; the outcomes are the library's.
pool_mathavan_outcome pool_mathavan_reference(pool_ball_state *s, const pool_params *p, pool_vec3 n, int steps);

/// A random impact into the north rail (normal +y) of a ball of radius R on the cloth, from the
/// xorshift state *seed: 0.1-8 m/s, -89 to 89 degrees from the normal, spin any top or back spin
/// (60 %), rolling (20 %) or stun (20 %), side up to 3 times the speed.
pool_ball_state pool_mathavan_random_impact(uint64_t *seed, double R);

/// The largest difference of two outcomes a and b of the impact `in`, over their velocity and
/// surface speed (R omega) components, relative to the impact's largest such component.
double pool_mathavan_difference(const pool_ball_state *in, const pool_ball_state *a, const pool_ball_state *b, double R);

#endif
