// The version of the library at run time (pool/base.h).
#include "pool/base.h"

int pool_version(void) { return POOL_VERSION; }
