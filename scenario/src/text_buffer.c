// A growing text buffer (see text_buffer.h).
#include "text_buffer.h"

#include <stdarg.h>
#include <stdio.h>
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

void pool_text_vappendf(pool_text_buffer *b, const char *format, va_list args) {
	char line[1024];
	int n = vsnprintf(line, sizeof line, format, args);
	if (n > 0)
		pool_text_append(b, line, (size_t)n < sizeof line ? (size_t)n : sizeof line - 1);
}

void pool_text_appendf(pool_text_buffer *b, const char *format, ...) {
	va_list args;
	va_start(args, format);
	pool_text_vappendf(b, format, args);
	va_end(args);
}
