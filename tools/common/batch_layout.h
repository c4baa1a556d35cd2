// A batch's layout file as pool-batch and pool-sensitivity read it: the scenario, and the exit
// status of a command when it cannot be used.
#ifndef POOL_TOOLS_BATCH_LAYOUT_H
#define POOL_TOOLS_BATCH_LAYOUT_H

#include <stddef.h>

#include "pool/scenario.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Reads a layout file (at most max_input bytes) and parses it, then checks that the balls alone
/// set up in the library. Returns 0; or POOL_EXIT_BAD_INPUT / POOL_EXIT_INTERNAL (cli.h) with
/// the message in err, the scenario empty.
int pool_batch_load_layout(const char *path, size_t max_input, pool_scenario *layout, char *err,
                           size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
