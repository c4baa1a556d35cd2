// Petit's impulse law with sticking, one function for ball-ball, ball-cushion and ball-cloth
// (docs/physics.md, "Collisions").
#ifndef POOL_COLLISION_H
#define POOL_COLLISION_H

#include "pool/ball.h"
#include "pool/event.h"
#include "pool/table.h"

/// One impulse between body 1 (a ball) and body 2 (a ball, or an immovable obstacle when
/// mass_ratio = M1/M2 = 0; then v2/w2 are taken as zero and body2 may be NULL).
/// n: unit normal pointing towards body 1. N: restitution, mu: friction of the pair.
/// Returns the normal impulse P (N s, > 0 when the bodies were approaching). Bodies not
/// approaching along n (P <= 0) are left unchanged and 0 is returned.
double pool_collide(pool_ball_state *b1, double R1, double M1, pool_ball_state *b2, double R2,
                    double mass_ratio, pool_vec3 n, double N, double mu);

#endif
