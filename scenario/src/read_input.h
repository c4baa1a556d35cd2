// Reading a whole input document (a file, a pipe, a FIFO, a device or standard input) with a
// size limit, so that `pool-sim /dev/zero` stops with a message instead of filling the memory.
#ifndef POOL_SCENARIO_READ_INPUT_H
#define POOL_SCENARIO_READ_INPUT_H

#include <stdbool.h>
#include <stddef.h>

#include "pool/scenario.h" // POOL_INPUT_DEFAULT_MAX

#ifdef __cplusplus
extern "C" {
#endif

/// Reads all of path ("-" = standard input) into a malloc'd buffer (NUL-terminated, *length
/// bytes before the NUL). More than max_bytes bytes is an error: "NAME: input is larger than
/// the limit of N bytes", NAME being the escaped path or "standard input"; a regular file is
/// refused from its size without being read, anything else after reading max_bytes + 1 bytes.
/// Returns 0, or -1 with the message in err and *data NULL.
int pool_read_input(const char *path, size_t max_bytes, char **data, size_t *length, char *err,
                    size_t err_size);

/// Parses a byte count for an input limit option: digits with an optional binary suffix k, M or
/// G (also KiB, MiB, GiB; case-insensitive), e.g. "1000", "512k", "64M", "1GiB". Zero, signs,
/// fractions, other suffixes and overflow are refused (false, *out untouched).
bool pool_parse_byte_count(const char *text, size_t *out);

#ifdef __cplusplus
}
#endif

#endif
