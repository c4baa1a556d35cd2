// Filling pool_error messages (field path first) without a dependency on stdio's vsnprintf
// quirks in callers.
#ifndef POOL_ERROR_H
#define POOL_ERROR_H

#include "pool/base.h"

/// Writes a printf-style message into error (if not NULL) and returns code.
pool_result pool_error_set(pool_error *error, pool_result code, const char *fmt, ...)
#if defined(__GNUC__)
	__attribute__((format(printf, 3, 4)))
#endif
	;

/// Clears error (if not NULL) and returns POOL_OK.
pool_result pool_error_ok(pool_error *error);

#endif
