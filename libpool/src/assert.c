// A broken invariant (assert.h): reported and fatal, in builds that check them.
#include "assert.h"

#ifdef POOL_ASSERTS
#include <stdio.h>
#include <stdlib.h>

void pool_assert_failed(const char *expression, const char *detail, const char *file, int line) {
	fprintf(stderr, "libpool: invariant broken at %s:%d: %s%s%s\n", file, line, expression, detail[0] ? ": " : "", detail);
	abort();
}
#else
typedef int pool_assert_unused; // (ISO C wants a translation unit to declare something)
#endif
