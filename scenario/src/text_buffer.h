// A growing, NUL-terminated text buffer that remembers an allocation failure instead of
// reporting each one: writers append freely and check `failed` once at the end.
#ifndef POOL_TOOLS_TEXT_BUFFER_H
#define POOL_TOOLS_TEXT_BUFFER_H

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

#ifdef __cplusplus
}
#endif

#endif
