// Command-line plumbing shared by pool-sim and pool-rack.
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomic_file.h"
#include "pool/base.h"
#include "text_escape.h"

const char *pool_cli_arg(const char *arg) {
	static char buffers[8][POOL_ESCAPE_SHORT + 16];
	static unsigned next;
	char *out = buffers[next++ % 8];
	return pool_escape_str(out, sizeof buffers[0], arg);
}

int pool_cli_result_status(int result) {
	return result == POOL_ERR_OUT_OF_MEMORY || result == POOL_ERR_INTERNAL ? POOL_EXIT_INTERNAL : POOL_EXIT_BAD_INPUT;
}

int pool_cli_usage_error(const char *program, const char *format, ...) {
	va_list args;
	va_start(args, format);
	fprintf(stderr, "%s: ", program);
	vfprintf(stderr, format, args);
	fprintf(stderr, "\nTry '%s --help'.\n", program);
	va_end(args);
	return POOL_EXIT_BAD_INPUT;
}

bool pool_cli_parse_double(const char *text, double *out) {
	char *end = NULL;
	errno = 0;
	double x = strtod(text, &end);
	if (errno || end == text || *end || !isfinite(x))
		return false;
	*out = x;
	return true;
}

bool pool_cli_parse_count(const char *text, long *out) {
	char *end = NULL;
	errno = 0;
	long value = strtol(text, &end, 10);
	if (errno || end == text || *end || value < 0)
		return false;
	*out = value;
	return true;
}

int pool_cli_write_output(const char *program, const char *path, const char *text) {
	size_t length = strlen(text);
	if (path) {
		char err[512];
		if (pool_write_file_atomic(path, text, length, err, sizeof err) != 0) {
			fprintf(stderr, "%s: %s\n", program, err);
			return POOL_EXIT_INTERNAL;
		}
		return 0;
	}
	fputs(text, stdout);
	if (fflush(stdout) != 0 || ferror(stdout)) {
		fprintf(stderr, "%s: standard output: %s\n", program, strerror(errno));
		return POOL_EXIT_INTERNAL;
	}
	return 0;
}
