// A growing, NUL-terminated text buffer that remembers an allocation failure instead of
// reporting each one: writers append freely and check `failed` once at the end.
#ifndef POOL_TOOLS_TEXT_BUFFER_H
#define POOL_TOOLS_TEXT_BUFFER_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pool_text_buffer {
	char *data;      ///< NUL-terminated text (malloc'd; NULL while empty)
	size_t length;   ///< bytes written, without the NUL
	size_t capacity; ///< bytes allocated
	bool failed;     ///< an allocation failed: the text is incomplete and stays so
} pool_text_buffer;

/// Appends n bytes of text (doubling the allocation as needed, from 1 KiB).
void pool_text_append(pool_text_buffer *b, const char *text, size_t n);

/// Appends formatted text, at most 1023 bytes of it per call (a line of a report).
void pool_text_appendf(pool_text_buffer *b, const char *format, ...) __attribute__((format(printf, 2, 3)));

/// The same with a va_list.
void pool_text_vappendf(pool_text_buffer *b, const char *format, va_list args) __attribute__((format(printf, 2, 0)));

#ifdef __cplusplus
}
#endif

#endif
