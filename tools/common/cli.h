// Command-line plumbing shared by the commands (pool-sim, pool-rack, pool-batch, pool-sensitivity): exit statuses, usage errors, number
// options and writing the output document (docs/interfaces.md: exit 2 names the offending option).
#ifndef POOL_TOOLS_CLI_H
#define POOL_TOOLS_CLI_H

#include <stdbool.h>
#include <stddef.h>

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

/// One option of pool_cli_walk: called with its name and its value (NULL for an option without
/// one); returns 0, or an exit status (pool_cli_usage_error's) that stops the walk.
typedef int (*pool_cli_option_fn)(void *context, const char *name, const char *value);

/// Walks argv[1..argc) the way pool-batch and pool-sensitivity read their arguments: "-h" and
/// "--help" set *help; an argument not starting with '-', "-" itself, and everything after "--"
/// is the one input file, *path (a second one is "unexpected argument ... (one WHAT per run)");
/// the options named in flags (NULL-terminated) go to `option` with no value, those in
/// with_value take the next argument (missing: "option X needs a value"); any other is
/// "unknown option". Returns 0 or the first nonzero status (usage errors print and give
/// POOL_EXIT_BAD_INPUT).
int pool_cli_walk(const char *program, int argc, char **argv, const char *what, const char *const *flags,
                  const char *const *with_value, pool_cli_option_fn option, void *context, const char **path,
                  bool *help);

/// Reads a --max-input value (pool_parse_byte_count: 1000000, 512k, 64M, 1G) into *out; 0, or
/// the usage error naming the option.
int pool_cli_max_input(const char *program, const char *value, size_t *out);

/// Writes text to path atomically (pool_write_file_atomic), or to standard output when path is
/// NULL. Returns 0, or POOL_EXIT_INTERNAL after printing "PROGRAM: <why>" on standard error.
int pool_cli_write_output(const char *program, const char *path, const char *text);

#ifdef __cplusplus
}
#endif

#endif
