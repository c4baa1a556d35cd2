// Error messages of validating calls.
#include "error.h"

#include <stdarg.h>
#include <stdio.h>

pool_result pool_error_set(pool_error *error, pool_result code, const char *fmt, ...) {
	if (error) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(error->message, sizeof error->message, fmt, ap);
		va_end(ap);
	}
	return code;
}

pool_result pool_error_ok(pool_error *error) {
	if (error)
		error->message[0] = '\0';
	return POOL_OK;
}
