// Writing a whole output file so that readers never see a partial one.
#ifndef POOL_TOOLS_ATOMIC_FILE_H
#define POOL_TOOLS_ATOMIC_FILE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Writes length bytes to path through a temporary file in the same directory renamed over it,
/// so on failure no (partial) file is left; creates the directories leading to path that are
/// missing. Returns 0, or -1 with a message in err.
int pool_write_file_atomic(const char *path, const char *data, size_t length, char *err,
                           size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
