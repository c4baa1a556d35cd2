// A plugin built against a future ABI version; the tests check that pool-compare refuses it.
#include "pool_engine_plugin.h"

static const pool_engine_api api = {
	.abi_version = POOL_ENGINE_ABI_VERSION + 98,
	.name = "wrongabi",
	.description = "test module with a wrong ABI version",
};

const pool_engine_api *pool_engine_plugin(void) { return &api; }
