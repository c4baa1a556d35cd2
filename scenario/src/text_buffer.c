// A growing text buffer (see text_buffer.h).
#include "text_buffer.h"

#include <stdlib.h>
#include <string.h>

void pool_text_append(pool_text_buffer *b, const char *text, size_t n) {
	if (b->failed)
		return;
	if (b->length + n + 1 > b->capacity) {
		size_t capacity = b->capacity ? b->capacity : 1024;
		while (b->length + n + 1 > capacity)
			capacity *= 2;
		char *data = realloc(b->data, capacity);
		if (!data) {
			b->failed = true;
			return;
		}
		b->data = data;
		b->capacity = capacity;
	}
	memcpy(b->data + b->length, text, n);
	b->length += n;
	b->data[b->length] = '\0';
}
