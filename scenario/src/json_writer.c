// Deterministic JSON emitter (see json_writer.h).
#include "json_writer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void pool_jw_init(pool_jw *w, bool pretty) {
	memset(w, 0, sizeof *w);
	w->pretty = pretty;
	w->first[0] = true;
}

void pool_jw_discard(pool_jw *w) {
	free(w->out.data);
	memset(w, 0, sizeof *w);
}

char *pool_jw_finish(pool_jw *w) {
	if (w->out.failed || w->depth != 0 || !w->out.data) {
		pool_jw_discard(w);
		return NULL;
	}
	char *text = w->out.data;
	w->out.data = NULL;
	pool_jw_discard(w);
	return text;
}

static void put(pool_jw *w, const char *text, size_t n) { pool_text_append(&w->out, text, n); }

static void puts_(pool_jw *w, const char *text) { put(w, text, strlen(text)); }

static void newline(pool_jw *w, int depth) {
	put(w, "\n", 1);
	for (int i = 0; i < depth; ++i)
		put(w, "  ", 2);
}

// Separator and indentation before a value or key at the current depth.
static void before_item(pool_jw *w) {
	if (w->after_key) {
		w->after_key = false;
		return;
	}
	bool first = w->first[w->depth];
	w->first[w->depth] = false;
	if (!first)
		put(w, ",", 1);
	if (w->depth == 0)
		return;
	if (w->pretty) {
		if (w->inline_[w->depth]) {
			if (!first)
				put(w, " ", 1);
		} else {
			newline(w, w->depth);
		}
	}
}

static void open(pool_jw *w, char c, bool inline_) {
	before_item(w);
	if (w->depth + 1 >= POOL_JW_MAX_DEPTH) {
		w->out.failed = true;
		return;
	}
	put(w, &c, 1);
	w->depth++;
	w->first[w->depth] = true;
	// A container inside an inline one stays inline too.
	w->inline_[w->depth] = inline_ || (w->depth > 1 && w->inline_[w->depth - 1]);
}

void pool_jw_object(pool_jw *w, bool inline_) { open(w, '{', inline_); }
void pool_jw_array(pool_jw *w, bool inline_) { open(w, '[', inline_); }

void pool_jw_end(pool_jw *w, char close) {
	if (w->depth <= 0) {
		w->out.failed = true;
		return;
	}
	bool empty = w->first[w->depth];
	bool inline_ = w->inline_[w->depth];
	w->depth--;
	if (w->pretty && !inline_ && !empty)
		newline(w, w->depth);
	put(w, &close, 1);
	if (w->depth == 0)
		put(w, "\n", 1); // documents end with a newline, like any text file
}

static void string_body(pool_jw *w, const char *s) {
	put(w, "\"", 1);
	for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
		char buffer[8];
		switch (*p) {
		case '"': puts_(w, "\\\""); break;
		case '\\': puts_(w, "\\\\"); break;
		case '\n': puts_(w, "\\n"); break;
		case '\t': puts_(w, "\\t"); break;
		case '\r': puts_(w, "\\r"); break;
		default:
			if (*p < 0x20) {
				snprintf(buffer, sizeof buffer, "\\u%04x", *p);
				puts_(w, buffer);
			} else {
				put(w, (const char *)p, 1);
			}
		}
	}
	put(w, "\"", 1);
}

void pool_jw_key(pool_jw *w, const char *key) {
	before_item(w);
	string_body(w, key);
	put(w, ":", 1);
	if (w->pretty)
		put(w, " ", 1);
	w->after_key = true;
}

void pool_jw_format_double(double value, char out[32]) {
	if (!isfinite(value)) {
		strcpy(out, "null");
		return;
	}
	if (value == 0.0) {
		// -0 and 0 print alike; the sign of zero carries no physics here.
		strcpy(out, "0");
		return;
	}
	for (int digits = 15; digits <= 17; ++digits) {
		snprintf(out, 32, "%.*g", digits, value);
		if (digits == 17 || strtod(out, NULL) == value)
			return;
	}
}

void pool_jw_number(pool_jw *w, double value) {
	char buffer[32];
	pool_jw_format_double(value, buffer);
	before_item(w);
	puts_(w, buffer);
}

void pool_jw_int(pool_jw *w, int64_t value) {
	char buffer[32];
	snprintf(buffer, sizeof buffer, "%lld", (long long)value);
	before_item(w);
	puts_(w, buffer);
}

void pool_jw_string(pool_jw *w, const char *value) {
	before_item(w);
	string_body(w, value ? value : "");
}

void pool_jw_null(pool_jw *w) {
	before_item(w);
	puts_(w, "null");
}

void pool_jw_bool(pool_jw *w, bool value) {
	before_item(w);
	puts_(w, value ? "true" : "false");
}

void pool_jw_vec3(pool_jw *w, pool_vec3 v) {
	pool_jw_array(w, true);
	pool_jw_number(w, v.x);
	pool_jw_number(w, v.y);
	pool_jw_number(w, v.z);
	pool_jw_end(w, ']');
}
