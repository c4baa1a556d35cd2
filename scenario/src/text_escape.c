// Printable renderings of user input for messages (text_escape.h).
#include "text_escape.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

// Length of the valid UTF-8 sequence at s (1 to 4) with its code point, or 0 when the bytes
// there are not valid UTF-8 (overlong forms, surrogates and code points above U+10FFFF are not).
static size_t utf8_decode(const unsigned char *s, size_t n, uint32_t *cp) {
	unsigned char c = s[0];
	size_t len;
	uint32_t min;
	if (c < 0x80) {
		*cp = c;
		return 1;
	} else if (c >= 0xC2 && c <= 0xDF) {
		len = 2, min = 0x80, *cp = c & 0x1F;
	} else if (c >= 0xE0 && c <= 0xEF) {
		len = 3, min = 0x800, *cp = c & 0x0F;
	} else if (c >= 0xF0 && c <= 0xF4) {
		len = 4, min = 0x10000, *cp = c & 0x07;
	} else {
		return 0;
	}
	if (n < len)
		return 0;
	for (size_t i = 1; i < len; ++i) {
		if ((s[i] & 0xC0) != 0x80)
			return 0;
		*cp = (*cp << 6) | (s[i] & 0x3F);
	}
	if (*cp < min || *cp > 0x10FFFF || (*cp >= 0xD800 && *cp <= 0xDFFF))
		return 0;
	return len;
}

// Code points shown escaped although they are valid: they are invisible or reorder the text
// around them (bidirectional overrides), so the message would not show what the input holds.
static bool is_hidden(uint32_t cp) {
	return cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) || cp == 0x061C || cp == 0x180E ||
	       (cp >= 0x200B && cp <= 0x200F) || (cp >= 0x2028 && cp <= 0x202E) ||
	       (cp >= 0x2060 && cp <= 0x206F) || cp == 0xFEFF || (cp >= 0xFFF9 && cp <= 0xFFFB) ||
	       cp == 0xFFFE || cp == 0xFFFF || (cp >= 0xE0000 && cp <= 0xE007F);
}

// The rendering of the character at s into r (at most 11 bytes); returns the input bytes used.
static size_t render(const unsigned char *s, size_t n, char r[12], size_t *r_len) {
	uint32_t cp = 0;
	size_t used = utf8_decode(s, n, &cp);
	if (used == 0) {
		*r_len = (size_t)snprintf(r, 12, "\\x%02x", s[0]);
		return 1;
	}
	if (is_hidden(cp)) {
		*r_len = (size_t)(cp > 0xFFFF ? snprintf(r, 12, "\\U%08x", (unsigned)cp)
		                              : snprintf(r, 12, "\\u%04x", (unsigned)cp));
	} else {
		memcpy(r, s, used);
		r[used] = '\0';
		*r_len = used;
	}
	return used;
}

char *pool_escape_text(char *out, size_t out_size, const char *text, size_t length) {
	if (!out || out_size == 0)
		return out;
	out[0] = '\0';
	const size_t cap = out_size - 1; // bytes available before the NUL
	char suffix[40];
	size_t suffix_len = (size_t)snprintf(suffix, sizeof suffix, "...(%zu bytes)", length);
	const unsigned char *s = (const unsigned char *)text;
	size_t pos = 0, safe = 0, i = 0;
	bool cut = false;
	while (i < length) {
		char r[12];
		size_t r_len = 0;
		size_t used = render(s + i, length - i, r, &r_len);
		if (pos + r_len > cap) {
			cut = true;
			break;
		}
		memcpy(out + pos, r, r_len);
		pos += r_len;
		i += used;
		if (pos + suffix_len <= cap)
			safe = pos;
	}
	if (cut) {
		// Back to the last character boundary that leaves room for the suffix.
		pos = suffix_len <= cap ? safe : pos;
		if (suffix_len <= cap) {
			memcpy(out + pos, suffix, suffix_len);
			pos += suffix_len;
		}
	}
	out[pos] = '\0';
	return out;
}

char *pool_escape_str(char *out, size_t out_size, const char *text) {
	return pool_escape_text(out, out_size, text, text ? strlen(text) : 0);
}
