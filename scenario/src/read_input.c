// Whole-document input with a size limit (read_input.h).
#define _POSIX_C_SOURCE 200809L // fileno
#include "read_input.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "text_escape.h"

int pool_read_input(const char *path, size_t max_bytes, char **data, size_t *length, char *err,
                    size_t err_size) {
	*data = NULL;
	*length = 0;
	bool use_stdin = strcmp(path, "-") == 0;
	char name[POOL_ESCAPE_LONG];
	if (use_stdin)
		snprintf(name, sizeof name, "standard input");
	else
		pool_escape_str(name, sizeof name, path);
	if (max_bytes == 0 || max_bytes >= SIZE_MAX - 1)
		max_bytes = SIZE_MAX - 2; // room for the extra byte that detects an overflow, and the NUL
	FILE *f = use_stdin ? stdin : fopen(path, "rb");
	if (!f) {
		snprintf(err, err_size, "%s: %s", name, strerror(errno));
		return -1;
	}
	int status = 0;
	struct stat st;
	// A regular file says its size: refuse a big one without reading it.
	if (!use_stdin && fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0 &&
	    (uintmax_t)st.st_size > (uintmax_t)max_bytes) {
		snprintf(err, err_size, "%s: input is larger than the limit of %zu bytes (%jd bytes)", name,
		         max_bytes, (intmax_t)st.st_size);
		fclose(f);
		return -1;
	}
	size_t used = 0, capacity = 0;
	char *buffer = NULL;
	// Read at most max_bytes + 1 bytes: one byte more than allowed proves the input too long,
	// whatever it is (a pipe, a FIFO, /dev/zero, a file growing while it is read).
	while (status == 0) {
		if (capacity - used <= 1) { // full but for the NUL's byte
			size_t want = capacity ? capacity * 2 : 65536;
			if (capacity > (max_bytes + 2) / 2 || want > max_bytes + 2)
				want = max_bytes + 2;
			char *bigger = realloc(buffer, want);
			if (!bigger) {
				snprintf(err, err_size, "%s: out of memory reading %zu bytes", name, want);
				status = -1;
				break;
			}
			buffer = bigger;
			capacity = want;
		}
		// Leave the last byte of the buffer for the NUL.
		size_t room = capacity - 1 - used;
		size_t n = fread(buffer + used, 1, room, f);
		used += n;
		if (used > max_bytes) {
			snprintf(err, err_size, "%s: input is larger than the limit of %zu bytes", name, max_bytes);
			status = -1;
		} else if (n < room) {
			if (ferror(f)) { // e.g. a directory: say why (EISDIR)
				snprintf(err, err_size, "%s: read error: %s", name, strerror(errno));
				status = -1;
			}
			break;
		}
	}
	if (!use_stdin)
		fclose(f);
	if (status != 0) {
		free(buffer);
		return -1;
	}
	buffer[used] = '\0';
	*data = buffer;
	*length = used;
	return 0;
}

bool pool_parse_byte_count(const char *text, size_t *out) {
	if (!text || !isdigit((unsigned char)text[0]))
		return false;
	uintmax_t value = 0;
	const char *p = text;
	for (; isdigit((unsigned char)*p); ++p) {
		unsigned digit = (unsigned)(*p - '0');
		if (value > (UINTMAX_MAX - digit) / 10)
			return false;
		value = value * 10 + digit;
	}
	unsigned shift = 0;
	if (*p) {
		switch (tolower((unsigned char)*p)) {
		case 'k': shift = 10; break;
		case 'm': shift = 20; break;
		case 'g': shift = 30; break;
		default: return false;
		}
		++p;
		if ((p[0] == 'i' || p[0] == 'I') && (p[1] == 'b' || p[1] == 'B'))
			p += 2;
		if (*p)
			return false;
	}
	if (value == 0 || value > (uintmax_t)(SIZE_MAX - 2) >> shift)
		return false;
	*out = (size_t)(value << shift);
	return true;
}
