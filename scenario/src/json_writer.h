// A tiny deterministic JSON emitter for result and scenario files. Numbers are written with the
// fewest significant digits (15 to 17) that read back to the same double, so files round-trip
// exactly and identical inputs give byte-identical output.
#ifndef POOL_TOOLS_JSON_WRITER_H
#define POOL_TOOLS_JSON_WRITER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pool/base.h"
#include "text_buffer.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Deepest nesting the writer supports.
#define POOL_JW_MAX_DEPTH 32

/// Growing output buffer plus the nesting state needed for commas and indentation.
typedef struct pool_jw {
	pool_text_buffer out;               ///< the output (owned until pool_jw_finish); its
	                                    ///< `failed` also marks nesting that went too deep
	bool pretty;                        ///< indent containers that are not inline
	int depth;                          ///< current nesting depth
	bool first[POOL_JW_MAX_DEPTH];      ///< no element written yet at this depth
	bool inline_[POOL_JW_MAX_DEPTH];    ///< container kept on one line when pretty
	bool after_key;                     ///< a key was just written; the value follows it
} pool_jw;

/// Starts an empty document.
void pool_jw_init(pool_jw *w, bool pretty);
/// Returns the malloc'd text (ends with a newline; NULL on failure) and resets the writer.
char *pool_jw_finish(pool_jw *w);
/// Frees the buffer without returning it.
void pool_jw_discard(pool_jw *w);

/// Opens an object; inline keeps it on one line in pretty mode.
void pool_jw_object(pool_jw *w, bool inline_);
/// Opens an array; inline keeps it on one line in pretty mode.
void pool_jw_array(pool_jw *w, bool inline_);
/// Closes the innermost object or array.
void pool_jw_end(pool_jw *w, char close);
/// Writes an object key; the next call writes its value.
void pool_jw_key(pool_jw *w, const char *key);
/// Writes a double (null when not finite, which valid input never produces).
void pool_jw_number(pool_jw *w, double value);
/// Writes an integer.
void pool_jw_int(pool_jw *w, int64_t value);
/// Writes a string, escaped.
void pool_jw_string(pool_jw *w, const char *value);
/// Writes null.
void pool_jw_null(pool_jw *w);
/// Writes true or false.
void pool_jw_bool(pool_jw *w, bool value);
/// Writes [x, y, z] on one line.
void pool_jw_vec3(pool_jw *w, pool_vec3 v);

/// Formats a double with the fewest digits (15..17) that round-trip; buffer of 32 bytes.
void pool_jw_format_double(double value, char out[32]);

#ifdef __cplusplus
}
#endif

#endif
