// The reference the mathavan2010 cushion (libpool/src/cushion_mathavan.c) is judged by: the same
// equations of Mathavan, Jackson & Parkin (2010) integrated in fixed impulse steps, a scheme
// independent of the library's adaptive one (libpool's own before it, at 128 steps). Run at many
// steps by pool-bench-models --accuracy and tests/unit/test_model_fidelity.c; not in the library.
#ifndef POOL_MATHAVAN_REFERENCE_H
#define POOL_MATHAVAN_REFERENCE_H

#include "cushion_mathavan.h"

/// Resolves the impact of ball s (on the cloth) with a cushion nose of unit normal n (from the
/// nose to the ball centre) in `steps` equal impulse steps over the estimated impact: first order
/// in 1/steps across stick-slip transitions, second order elsewhere. Only s->vel and s->omega
/// change; the outcomes are the library's.
pool_mathavan_outcome pool_mathavan_reference(pool_ball_state *s, const pool_params *p, pool_vec3 n, int steps);

#endif
