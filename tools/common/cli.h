// Command-line plumbing shared by pool-sim and pool-rack: exit statuses, usage errors, number
// options and writing the output document (INTERFACES.md: exit 2 names the offending option).
#ifndef POOL_TOOLS_CLI_H
#define POOL_TOOLS_CLI_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Exit status for bad input or usage (the message names the option or field).
#define POOL_EXIT_BAD_INPUT 2
/// Exit status for an internal failure (out of memory, an output that cannot be written).
#define POOL_EXIT_INTERNAL 1

/// Exit status for a failing libpool result (a negative pool_result): POOL_EXIT_INTERNAL for
/// out of memory and internal errors, POOL_EXIT_BAD_INPUT for the rest (the input broke a rule).
int pool_cli_result_status(int result);

/// Prints "PROGRAM: <format, ...>" and "Try 'PROGRAM --help'." on standard error; returns
/// POOL_EXIT_BAD_INPUT.
int pool_cli_usage_error(const char *program, const char *format, ...)
	__attribute__((format(printf, 2, 3)));

/// The command-line argument arg made safe to print (pool_escape_str, cut to about 100 bytes),
/// for messages that quote it. Returns one of 8 static buffers used in turn: for single-threaded
/// command-line code, at most 8 arguments per message.
const char *pool_cli_arg(const char *arg);

/// Reads the whole of text as a finite double; false (out untouched) for empty text, trailing
/// characters, overflow, inf or nan.
bool pool_cli_parse_double(const char *text, double *out);

/// Reads the whole of text as a decimal integer >= 0; false (out untouched) for empty text,
/// trailing characters, a sign making it negative, or overflow.
bool pool_cli_parse_count(const char *text, long *out);

/// Writes text to path atomically (pool_write_file_atomic), or to standard output when path is
/// NULL. Returns 0, or POOL_EXIT_INTERNAL after printing "PROGRAM: <why>" on standard error.
int pool_cli_write_output(const char *program, const char *path, const char *text);

#ifdef __cplusplus
}
#endif

#endif
