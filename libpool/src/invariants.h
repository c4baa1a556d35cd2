// The whole world checked against the invariants the code relies on (assert.h): the heap, the
// bodies and their partners, LINK's clusters, the history's chains. Run after every step in
// builds that check invariants (POOL_ASSERTS: the sanitizer build); compiled out otherwise.
#ifndef POOL_INVARIANTS_H
#define POOL_INVARIANTS_H

#include "assert.h"
#include "world.h"

#ifdef POOL_ASSERTS
/// Checks every invariant of sim (POOL_ASSERT_MSG, naming what broke).
void pool_world_check(pool_sim *sim);
#else
static inline void pool_world_check(pool_sim *sim) { (void)sim; }
#endif

#endif
