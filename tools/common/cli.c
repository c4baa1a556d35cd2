// Command-line plumbing shared by the commands.
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomic_file.h"
#include "read_input.h"
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

static bool named(const char *const *names, const char *a) {
	for (const char *const *n = names; n && *n; ++n)
		if (strcmp(a, *n) == 0)
			return true;
	return false;
}

int pool_cli_walk(const char *program, int argc, char **argv, const char *what, const char *const *flags,
                  const char *const *with_value, pool_cli_option_fn option, void *context, const char **path,
                  bool *help) {
	bool only_files = false;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		if (only_files || a[0] != '-' || strcmp(a, "-") == 0) {
			if (*path)
				return pool_cli_usage_error(program, "unexpected argument '%s' (one %s per run)", pool_cli_arg(a),
				                            what);
			*path = a;
			continue;
		}
		if (strcmp(a, "--") == 0) {
			only_files = true;
			continue;
		}
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			*help = true;
			continue;
		}
		int status;
		if (named(flags, a)) {
			status = option(context, a, NULL);
		} else if (named(with_value, a)) {
			if (i + 1 >= argc)
				return pool_cli_usage_error(program, "option %s needs a value", a);
			status = option(context, a, argv[++i]);
		} else {
			return pool_cli_usage_error(program, "unknown option '%s'", pool_cli_arg(a));
		}
		if (status)
			return status;
	}
	return 0;
}

int pool_cli_max_input(const char *program, const char *value, size_t *out) {
	if (pool_parse_byte_count(value, out))
		return 0;
	return pool_cli_usage_error(program, "--max-input: '%s' is not a size in bytes > 0 (e.g. 1000000, 512k, 64M, 1G)",
	                            pool_cli_arg(value));
}
