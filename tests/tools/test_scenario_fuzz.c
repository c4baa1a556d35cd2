// Deterministic mutation fuzz test of the scenario parser, the simulation it sets up and the
// result writer: bad input must give -1 and a message that starts with a field path, never a
// crash, hang, leak or undefined behaviour (the sanitizer build runs this with ASan + UBSan).
// Seeds are every compare/scenarios/*.json plus hand-written documents; mutants come from a
// splitmix64 generator with a fixed seed, so every run tests the same inputs.
// POOL_FUZZ_CASES=N overrides the number of mutants; POOL_FUZZ_SEED=S explores other mutants.
#define _POSIX_C_SOURCE 200809L // strdup, opendir
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <ctype.h>
#include <dirent.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pool/scenario.h"

#ifndef POOL_FUZZ_SCENARIO_DIR
#error "POOL_FUZZ_SCENARIO_DIR must name compare/scenarios"
#endif

#if defined(__SANITIZE_ADDRESS__)
#define POOL_FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define POOL_FUZZ_SANITIZED 1
#endif
#endif
#ifdef POOL_FUZZ_SANITIZED
#define POOL_FUZZ_DEFAULT_CASES 4000
#else
#define POOL_FUZZ_DEFAULT_CASES 12000
#endif

// Events per simulated mutant: enough to reach every event type (LINK ones included), few enough
// for a fast test: a LINK step of a large cluster costs milliseconds (tens under ASan).
#define POOL_FUZZ_MAX_EVENTS 1000
// s of simulated time per mutant, for the same reason.
#define POOL_FUZZ_MAX_TIME 5.0

// ---------------------------------------------------------------------------------------------
// Growable byte buffer (mutants are not NUL-terminated when parsed: ASan sees over-reads).

typedef struct buf {
	char *data;
	size_t len, cap;
} buf;

static void buf_reserve(buf *b, size_t n) {
	if (n + 1 <= b->cap)
		return;
	size_t cap = b->cap ? b->cap : 256;
	while (cap < n + 1)
		cap *= 2;
	b->data = realloc(b->data, cap);
	assert_non_null(b->data);
	b->cap = cap;
}

static void buf_set(buf *b, const char *s, size_t n) {
	buf_reserve(b, n);
	memcpy(b->data, s, n);
	b->len = n;
	b->data[n] = '\0';
}

static void buf_cat(buf *b, const char *s) {
	size_t n = strlen(s);
	buf_reserve(b, b->len + n);
	memcpy(b->data + b->len, s, n + 1);
	b->len += n;
}

static void buf_printf(buf *b, const char *format, ...) {
	char tmp[512];
	va_list args;
	va_start(args, format);
	vsnprintf(tmp, sizeof tmp, format, args);
	va_end(args);
	buf_cat(b, tmp);
}

// Replaces [at, at + del) with n bytes of s.
static void buf_splice(buf *b, size_t at, size_t del, const char *s, size_t n) {
	assert_true(at + del <= b->len);
	buf_reserve(b, b->len - del + n);
	memmove(b->data + at + n, b->data + at + del, b->len - at - del + 1);
	memcpy(b->data + at, s, n);
	b->len = b->len - del + n;
}

// ---------------------------------------------------------------------------------------------
// Deterministic randomness.

static uint64_t rng_state;

static uint64_t splitmix64(void) {
	uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

static size_t rnd(size_t n) { return n ? (size_t)(splitmix64() % n) : 0; }

static const char *pick(const char *const *list, size_t n) { return list[rnd(n)]; }
#define PICK(list) pick(list, sizeof list / sizeof list[0])

// ---------------------------------------------------------------------------------------------
// Seeds.

typedef struct seed_set {
	char **docs;
	size_t *lens;
	char **names;
	size_t count;
} seed_set;

static seed_set seeds;

static void add_seed(const char *name, const char *doc, size_t len) {
	seeds.docs = realloc(seeds.docs, (seeds.count + 1) * sizeof *seeds.docs);
	seeds.lens = realloc(seeds.lens, (seeds.count + 1) * sizeof *seeds.lens);
	seeds.names = realloc(seeds.names, (seeds.count + 1) * sizeof *seeds.names);
	assert_true(seeds.docs && seeds.lens && seeds.names);
	seeds.docs[seeds.count] = malloc(len + 1);
	assert_non_null(seeds.docs[seeds.count]);
	memcpy(seeds.docs[seeds.count], doc, len);
	seeds.docs[seeds.count][len] = '\0';
	seeds.lens[seeds.count] = len;
	seeds.names[seeds.count] = strdup(name);
	seeds.count++;
}

static int compare_names(const void *a, const void *b) {
	return strcmp(*(char *const *)a, *(char *const *)b);
}

static size_t load_directory_seeds(const char *dir) {
	DIR *d = opendir(dir);
	if (!d)
		fail_msg("cannot open %s", dir);
	char *names[256];
	size_t n = 0;
	struct dirent *ent;
	while ((ent = readdir(d)) && n < 256) {
		size_t l = strlen(ent->d_name);
		if (l > 5 && strcmp(ent->d_name + l - 5, ".json") == 0)
			names[n++] = strdup(ent->d_name);
	}
	closedir(d);
	qsort(names, n, sizeof names[0], compare_names); // readdir order is not deterministic
	for (size_t i = 0; i < n; ++i) {
		char path[1024];
		snprintf(path, sizeof path, "%s/%s", dir, names[i]);
		FILE *f = fopen(path, "rb");
		assert_non_null(f);
		buf b = {0};
		char chunk[4096];
		size_t got;
		while ((got = fread(chunk, 1, sizeof chunk, f)) > 0) {
			buf_reserve(&b, b.len + got);
			memcpy(b.data + b.len, chunk, got);
			b.len += got;
		}
		fclose(f);
		add_seed(names[i], b.data, b.len);
		free(b.data);
		free(names[i]);
	}
	return n;
}

// 200 balls on a grid, the first one struck into the others.
static void make_many_balls(buf *b) {
	buf_set(b, "", 0);
	buf_cat(b, "{\"format\": \"libpool-scenario/1\", \"balls\": [");
	for (int i = 0; i < 200; ++i)
		buf_printf(b, "%s{\"id\": %d, \"pos\": [%.4f, %.4f]}", i ? ", " : "", i, 0.1 + 0.11 * (i % 20),
		           0.1 + 0.11 * (i / 20));
	buf_cat(b, "], \"strike\": {\"ball\": 0, \"speed\": 5, \"phi\": 30, \"a\": 0.005}}");
}

static const char seed_rack[] =
	"{\"format\": \"libpool-scenario/1\", \"name\": \"rack\", \"description\": \"6 balls\","
	" \"table\": {\"preset\": \"wpa-8ft\"},"
	" \"balls\": [{\"id\": 0, \"pos\": [0.5842, 0.5842]},"
	"  {\"id\": 1, \"pos\": [1.7526, 0.5842]},"
	"  {\"id\": 2, \"pos\": [1.8026, 0.5552]}, {\"id\": 3, \"pos\": [1.8026, 0.6132]},"
	"  {\"id\": 4, \"pos\": [1.8526, 0.5262]}, {\"id\": 5, \"pos\": [1.8526, 0.5842]}],"
	" \"strike\": {\"ball\": 0, \"speed\": 7, \"phi\": 0.2, \"theta\": 5, \"a\": 0.004, \"b\": 0.01}}";

static const char seed_table[] =
	"{\"format\": \"libpool-scenario/1\","
	" \"table\": {\"preset\": \"wpa-7ft\", \"length\": 2.0, \"width\": 1.0, \"cushion_height\": 0.035,"
	"  \"corner_mouth\": 0.12, \"side_mouth\": 0.13},"
	" \"balls\": [{\"id\": 7, \"pos\": [0.4, 0.3], \"vel\": [1.5, 0.8], \"omega\": [0, 0, 20]},"
	"  {\"id\": 9, \"pos\": [1.6, 0.7]}],"
	" \"strike\": {\"ball\": 9, \"speed\": 3, \"phi\": 200, \"b\": -0.012}}";

static const char seed_params[] =
	"{\"format\": \"libpool-scenario/1\","
	" \"params\": {\"g\": 9.8, \"mu_slide\": 0.25, \"mu_roll\": 0.012, \"mu_spin\": 0.02,"
	"  \"mu_ball\": 0.05, \"e_ball\": 0.93, \"mu_cushion\": 0.15, \"e_cushion\": 0.8,"
	"  \"mu_table\": 0.3, \"e_table\": 0.6, \"ball_radius\": 0.0286, \"ball_mass\": 0.16,"
	"  \"cue_mass\": 0.5},"
	" \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635]}, {\"id\": 1, \"pos\": [1.905, 0.7]},"
	"  {\"id\": 2, \"pos\": [2.2, 0.2]}],"
	" \"strike\": {\"ball\": 0, \"speed\": 4, \"phi\": 2, \"a\": -0.01, \"b\": 0.015}}";

static const char seed_options[] =
	"{\"format\": \"libpool-scenario/1\","
	" \"options\": {\"airborne\": false, \"max_time\": 15, \"max_events\": 5000},"
	" \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635, 0.028575]},"
	"  {\"id\": 1, \"pos\": [1.2, 0.6, 0.028575], \"vel\": [0.5, 0.1, 0], \"omega\": [3, -2, 1]},"
	"  {\"id\": 2, \"pos\": [1.905, 0.635]}],"
	" \"strike\": {\"ball\": 0, \"speed\": 6, \"phi\": 0, \"theta\": 45, \"b\": -0.02}}";

static const char seed_extreme_ids[] =
	"{\"format\": \"libpool-scenario/1\","
	" \"balls\": [{\"id\": 2147483647, \"pos\": [0.635, 0.635]}, {\"id\": -2147483648, \"pos\": [1.0, 0.65]}],"
	" \"strike\": {\"ball\": -2147483648, \"speed\": 1, \"phi\": 180}}";

static void load_seeds(void) {
	size_t from_dir = load_directory_seeds(POOL_FUZZ_SCENARIO_DIR);
	assert_true(from_dir >= 1);
	add_seed("rack", seed_rack, strlen(seed_rack));
	add_seed("table", seed_table, strlen(seed_table));
	add_seed("params", seed_params, strlen(seed_params));
	add_seed("options", seed_options, strlen(seed_options));
	add_seed("extreme_ids", seed_extreme_ids, strlen(seed_extreme_ids));
	buf b = {0};
	make_many_balls(&b);
	add_seed("200_balls", b.data, b.len);
	free(b.data);
}

static void free_seeds(void) {
	for (size_t i = 0; i < seeds.count; ++i) {
		free(seeds.docs[i]);
		free(seeds.names[i]);
	}
	free(seeds.docs);
	free(seeds.lens);
	free(seeds.names);
	memset(&seeds, 0, sizeof seeds);
}

// ---------------------------------------------------------------------------------------------
// A tiny JSON scanner for the structural mutations; on broken text it just finds less.

typedef struct span {
	size_t start, end;
} span;

// End of the value starting at i (balanced brackets, strings with escapes), or i if none.
static size_t value_end(const char *s, size_t len, size_t i) {
	if (i >= len)
		return i;
	if (s[i] == '"') {
		for (size_t j = i + 1; j < len; ++j) {
			if (s[j] == '\\')
				++j;
			else if (s[j] == '"')
				return j + 1;
		}
		return len;
	}
	if (s[i] == '[' || s[i] == '{') {
		int depth = 0;
		bool in_string = false;
		for (size_t j = i; j < len; ++j) {
			char c = s[j];
			if (in_string) {
				if (c == '\\')
					++j;
				else if (c == '"')
					in_string = false;
			} else if (c == '"') {
				in_string = true;
			} else if (c == '[' || c == '{') {
				++depth;
			} else if (c == ']' || c == '}') {
				if (--depth == 0)
					return j + 1;
			}
		}
		return len;
	}
	size_t j = i;
	while (j < len && (isalnum((unsigned char)s[j]) || strchr("+-.", s[j])))
		++j;
	return j;
}

// Values (after ':' or '[' or ',') outside strings; numbers_only keeps number tokens.
static size_t find_values(const buf *b, span *out, size_t max, bool numbers_only) {
	size_t n = 0;
	bool in_string = false;
	for (size_t i = 0; i < b->len && n < max; ++i) {
		char c = b->data[i];
		if (in_string) {
			if (c == '\\')
				++i;
			else if (c == '"')
				in_string = false;
			continue;
		}
		if (c == '"') {
			in_string = true;
			continue;
		}
		if (c != ':' && c != '[' && c != ',')
			continue;
		size_t j = i + 1;
		while (j < b->len && isspace((unsigned char)b->data[j]))
			++j;
		if (j >= b->len)
			break;
		char v = b->data[j];
		bool number = v == '-' || isdigit((unsigned char)v);
		if (numbers_only && !number)
			continue;
		if (!numbers_only && !(number || strchr("\"[{tfn", v)))
			continue;
		size_t e = value_end(b->data, b->len, j);
		if (e > j)
			out[n++] = (span){j, e};
	}
	return n;
}

// The value of the first or a random occurrence of "key": in the text.
static bool find_key_value(const buf *b, const char *key, span *out) {
	char needle[64];
	snprintf(needle, sizeof needle, "\"%s\"", key);
	size_t hits[512];
	size_t n = 0;
	const char *p = b->data;
	while (n < 512 && (p = strstr(p, needle))) {
		hits[n++] = (size_t)(p - b->data);
		p += strlen(needle);
	}
	if (n == 0)
		return false;
	size_t i = hits[rnd(n)] + strlen(needle);
	while (i < b->len && (isspace((unsigned char)b->data[i]) || b->data[i] == ':'))
		++i;
	size_t e = value_end(b->data, b->len, i);
	if (e <= i)
		return false;
	*out = (span){i, e};
	return true;
}

// ---------------------------------------------------------------------------------------------
// Mutations.

static const char *const extreme_numbers[] = {
	"0", "-0", "0.0", "-0.0", "1e308", "-1e308", "1.7976931348623157e308", "1e-320", "-1e-320",
	"4.9e-324", "1e999", "-1e999", "1e-999", "9223372036854775807", "9223372036854775808",
	"-9223372036854775809", "18446744073709551616", "2147483647", "2147483648", "-2147483648",
	"-2147483649", "1e9", "1000000000.0000001", "-1e9", "1", "-1", "0.5", "1.5", "-7", "1e-9",
	"2.2250738585072014e-308", "99999999999999999999999999999999999999", "0.028575", "0.05715",
	"90", "89.99999999999999", "-0.000000001", "1E2", "1e+2", "00", "01", "-", "1.", ".5", "1e",
	"+1", "0x10", "NaN", "Infinity", "-Infinity",
};

static const char *const other_types[] = {
	"\"1\"", "\"\"", "[]", "[0]", "[1, 2, 3, 4]", "[[0.5, 0.5]]", "null", "{}", "{\"a\": 1}", "true",
	"false", "\"wpa-9ft\"", "\"\\u0000\"", "\"\\ud800\"", "[null, null]", "[1e308, 1e308]",
};

static const char *const significant[] = {
	"{", "}", "[", "]", "\"", ",", ":", "-", ".", "e", "0", "\\", " ", "\n", "\x7f", "\xff",
	"\xc3\xa9", "\x00", "null", "true", "1e999", "{}", "[]", "\"\":", ",,", "/*",
};

static const char *const keys[] = {
	"format", "name", "description", "table", "preset", "length", "width", "cushion_height",
	"corner_mouth", "side_mouth", "params", "g", "mu_slide", "mu_roll", "mu_spin", "mu_ball",
	"e_ball", "mu_cushion", "e_cushion", "mu_table", "e_table", "ball_radius", "ball_mass",
	"cue_mass", "balls", "id", "pos", "vel", "omega", "strike", "ball", "speed", "phi", "theta",
	"a", "b", "options", "airborne", "max_time", "max_events",
};

static const char *const ids[] = {
	"2147483647", "-2147483648", "2147483648", "-2147483649", "1.5", "0.0", "1e3", "-0", "\"0\"",
	"null", "9223372036854775807", "-9223372036854775808", "99999999999999999999",
};

static void mutate_once(buf *b) {
	size_t len = b->len;
	switch (rnd(16)) {
	case 0: // flip one bit
		if (len)
			b->data[rnd(len)] ^= (char)(1u << rnd(8));
		break;
	case 1: { // delete a short range
		if (!len)
			break;
		size_t at = rnd(len);
		size_t n = 1 + rnd(rnd(2) ? 4 : 64);
		if (at + n > len)
			n = len - at;
		buf_splice(b, at, n, "", 0);
		break;
	}
	case 2: { // insert JSON-significant characters
		const char *s = PICK(significant);
		size_t n = s[0] ? strlen(s) : 1; // "\x00" inserts one NUL byte
		buf_splice(b, rnd(len + 1), 0, s, n);
		break;
	}
	case 3: // truncate
		b->len = rnd(len + 1);
		b->data[b->len] = '\0';
		break;
	case 4: { // duplicate a fragment somewhere else
		if (!len)
			break;
		size_t at = rnd(len);
		size_t n = 1 + rnd(len - at < 200 ? len - at : 200);
		char *copy = malloc(n);
		assert_non_null(copy);
		memcpy(copy, b->data + at, n);
		buf_splice(b, rnd(len + 1), 0, copy, n);
		free(copy);
		break;
	}
	case 5:
	case 6: { // a number becomes an extreme value
		span v[4096];
		size_t n = find_values(b, v, 4096, true);
		if (n) {
			span s = v[rnd(n)];
			const char *x = PICK(extreme_numbers);
			buf_splice(b, s.start, s.end - s.start, x, strlen(x));
		}
		break;
	}
	case 7: { // a value changes type
		span v[4096];
		size_t n = find_values(b, v, 4096, false);
		if (n) {
			span s = v[rnd(n)];
			const char *x = rnd(3) ? PICK(other_types) : PICK(extreme_numbers);
			buf_splice(b, s.start, s.end - s.start, x, strlen(x));
		}
		break;
	}
	case 8: { // a value becomes deeply nested arrays (closed or not)
		span v[4096];
		size_t n = find_values(b, v, 4096, false);
		size_t depth = rnd(2) ? 10000 : 1 + rnd(3000);
		bool close = rnd(2);
		buf nest = {0};
		buf_reserve(&nest, 2 * depth + 1);
		memset(nest.data, '[', depth);
		if (close)
			memset(nest.data + depth, ']', depth);
		nest.len = close ? 2 * depth : depth;
		span s = n ? v[rnd(n)] : (span){0, len};
		buf_splice(b, s.start, s.end - s.start, nest.data, nest.len);
		free(nest.data);
		break;
	}
	case 9: { // a key-value pair disappears (missing field)
		span s;
		const char *key = PICK(keys);
		if (!find_key_value(b, key, &s))
			break;
		size_t start = s.start;
		while (start > 0 && b->data[start - 1] != '"')
			--start;
		if (start > 0)
			--start;
		while (start > 0 && b->data[start - 1] != '"')
			--start; // opening quote of the key
		if (start > 0)
			--start;
		size_t end = s.end;
		while (end < b->len && isspace((unsigned char)b->data[end]))
			++end;
		if (end < b->len && b->data[end] == ',')
			++end;
		else {
			while (start > 0 && isspace((unsigned char)b->data[start - 1]))
				--start;
			if (start > 0 && b->data[start - 1] == ',')
				--start; // last member: take the comma before it
		}
		buf_splice(b, start, end - start, "", 0);
		break;
	}
	case 10: { // an extra field after some '{'
		size_t opens[4096];
		size_t n = 0;
		for (size_t i = 0; i < len && n < 4096; ++i)
			if (b->data[i] == '{')
				opens[n++] = i;
		if (!n)
			break;
		char field[96];
		snprintf(field, sizeof field, "\"%s\": %s, ", rnd(3) ? PICK(keys) : "extra",
		         rnd(2) ? PICK(extreme_numbers) : PICK(other_types));
		buf_splice(b, opens[rnd(n)] + 1, 0, field, strlen(field));
		break;
	}
	case 11: { // ids (and the struck ball) at the edges of int32 and beyond
		span s;
		if (find_key_value(b, rnd(4) ? "id" : "ball", &s)) {
			const char *x = PICK(ids);
			buf_splice(b, s.start, s.end - s.start, x, strlen(x));
		}
		break;
	}
	case 12: { // the balls list becomes empty, or one ball is repeated many times
		span s;
		if (!find_key_value(b, "balls", &s))
			break;
		if (rnd(2)) {
			buf_splice(b, s.start, s.end - s.start, "[]", 2);
		} else {
			buf many = {0};
			buf_cat(&many, "[");
			size_t count = 1 + rnd(300);
			for (size_t i = 0; i < count; ++i)
				buf_printf(&many, "%s{\"id\": %zu, \"pos\": [%.3f, %.3f]}", i ? "," : "", i,
				           0.05 + 0.06 * (double)(i % 40), 0.05 + 0.06 * (double)(i / 40));
			buf_cat(&many, "]");
			buf_splice(b, s.start, s.end - s.start, many.data, many.len);
			free(many.data);
		}
		break;
	}
	case 14: { // a number is scaled or nudged: still valid, different physics
		span v[4096];
		size_t n = find_values(b, v, 4096, true);
		if (!n)
			break;
		span s = v[rnd(n)];
		char token[64];
		size_t tl = s.end - s.start < 63 ? s.end - s.start : 63;
		memcpy(token, b->data + s.start, tl);
		token[tl] = '\0';
		double x = strtod(token, NULL);
		static const double factors[] = {0.0, 0.5, 0.9, 0.999999, 1.000001, 1.1, 2.0, 10.0, -1.0, 1e-6};
		x = rnd(4) ? x * factors[rnd(sizeof factors / sizeof factors[0])]
		           : x + ((double)rnd(2001) - 1000.0) * 1e-4;
		char out[64];
		snprintf(out, sizeof out, "%.17g", x);
		buf_splice(b, s.start, s.end - s.start, out, strlen(out));
		break;
	}
	default: { // a whole object value is replaced by another type or emptied
		const char *key = PICK(keys);
		span s;
		if (find_key_value(b, key, &s)) {
			const char *x = rnd(2) ? "{}" : PICK(other_types);
			buf_splice(b, s.start, s.end - s.start, x, strlen(x));
		}
		break;
	}
	}
}

// ---------------------------------------------------------------------------------------------
// The oracle.

typedef struct fuzz_stats {
	long accepted, rejected, run_errors, stopped_by_events;
} fuzz_stats;

static bool is_path_char(char c) { return isalnum((unsigned char)c) || c == '_'; }

// "root", "root.field", "balls[3].pos[1]", ...: a known root then fields and indices.
static bool starts_with_field_path(const char *m) {
	static const char *const roots[] = {"format", "name", "description", "table", "params",
	                                    "balls", "strike", "options", "models", "(document)"};
	for (size_t r = 0; r < sizeof roots / sizeof roots[0]; ++r) {
		size_t n = strlen(roots[r]);
		if (strncmp(m, roots[r], n) != 0)
			continue;
		const char *p = m + n;
		for (;;) {
			if (*p == '.' && is_path_char(p[1])) {
				++p;
				while (is_path_char(*p))
					++p;
			} else if (*p == '[' && isdigit((unsigned char)p[1])) {
				++p;
				while (isdigit((unsigned char)*p))
					++p;
				if (*p++ != ']')
					return false;
			} else {
				break;
			}
		}
		if (p[0] == ':' && p[1] == ' ' && p[2] != '\0')
			return true;
	}
	return false;
}

static void check_rejection(const char *doc, size_t len, const char *err, const pool_scenario *s,
                            const char *label) {
	// An unknown key is quoted verbatim (it may be any text), so that message is checked by its end.
	size_t n = strlen(err);
	const char *unknown = ": unknown field";
	bool unknown_field = n > strlen(unknown) && strcmp(err + n - strlen(unknown), unknown) == 0;
	if (!(unknown_field || starts_with_field_path(err)))
		fail_msg("%s: message does not start with a field path: \"%s\" (input %zu bytes: %.200s)",
		         label, err, len, doc);
	if (s->balls != NULL || s->ball_count != 0 || s->has_strike)
		fail_msg("%s: a failed parse left a non-empty scenario", label);
}

static bool state_finite(const pool_ball_state *b) {
	return isfinite(b->pos.x) && isfinite(b->pos.y) && isfinite(b->pos.z) && isfinite(b->vel.x) &&
	       isfinite(b->vel.y) && isfinite(b->vel.z) && isfinite(b->omega.x) &&
	       isfinite(b->omega.y) && isfinite(b->omega.z);
}

static void check_simulation(pool_scenario *s, bool sample, const char *label, fuzz_stats *stats) {
	if (s->def.max_events > POOL_FUZZ_MAX_EVENTS)
		s->def.max_events = POOL_FUZZ_MAX_EVENTS;
	if (s->def.max_time > POOL_FUZZ_MAX_TIME)
		s->def.max_time = POOL_FUZZ_MAX_TIME;
	pool_sim *sim = NULL;
	pool_error e = {{0}};
	pool_result r = pool_scenario_setup(s, &sim, &e);
	// The parser validated the scenario with the library's own rules: setup cannot refuse it,
	// except an airborne scenario while the library does not simulate airborne motion (the
	// parser checks those itself and setup answers with the library's options.airborne error).
	if (r != POOL_OK && s->def.airborne && strstr(e.message, "options.airborne") == e.message) {
		pool_sim_destroy(sim);
		return;
	}
	if (r != POOL_OK)
		fail_msg("%s: parse accepted but setup failed: %d %s", label, (int)r, e.message);
	r = pool_sim_run(sim);
	if (r != POOL_OK) {
		// A run may fail (e.g. an internal invariant), but with a real error code and text.
		if (!(r < 0 && r >= POOL_ERR_INTERNAL))
			fail_msg("%s: pool_sim_run returned %d", label, (int)r);
		const char *text = pool_result_str(r);
		if (!text || !text[0])
			fail_msg("%s: error %d has no description", label, (int)r);
		stats->run_errors++;
	} else {
		pool_stop_reason why = pool_sim_stop_reason(sim);
		if (why != POOL_STOP_REST && why != POOL_STOP_MAX_TIME && why != POOL_STOP_MAX_EVENTS)
			fail_msg("%s: finished run has stop reason %d", label, (int)why);
		if (why == POOL_STOP_MAX_EVENTS)
			stats->stopped_by_events++;
	}
	int count = -1;
	const pool_event *events = pool_sim_events(sim, &count);
	if (count < 0 || count > s->def.max_events + 1 || (count > 0 && !events))
		fail_msg("%s: %d events (max_events %d)", label, count, s->def.max_events);
	double last = 0.0;
	for (int i = 0; i < count; ++i) {
		const pool_event *ev = &events[i];
		if (!(ev->time >= last) || !isfinite(ev->time))
			fail_msg("%s: event %d at t = %.17g after t = %.17g", label, i, ev->time, last);
		last = ev->time;
		if (ev->time > s->def.max_time)
			fail_msg("%s: event %d at t = %.17g is after max_time %.17g", label, i, ev->time,
			         s->def.max_time);
		if (ev->ball_count < 1 || ev->ball_count > s->ball_count)
			fail_msg("%s: event %d involves %d balls", label, i, ev->ball_count);
		const pool_ball_state *after = pool_sim_event_states(sim, ev);
		assert_non_null(after);
		for (int k = 0; k < ev->ball_count; ++k)
			if (!state_finite(&after[k]))
				fail_msg("%s: event %d (%s at t = %.17g): after-state of ball %d is not finite",
				         label, i, pool_event_type_name(ev->type), ev->time, (int)after[k].id);
	}
	const pool_ball_state *balls = pool_sim_balls(sim);
	for (int i = 0; i < pool_sim_ball_count(sim); ++i)
		if (!state_finite(&balls[i]))
			fail_msg("%s: final state of ball %d is not finite", label, (int)balls[i].id);

	pool_result_options o = {.sample_dt = sample ? 0.05 : 0.0, .pretty = sample, .def = &s->def};
	char *text = pool_result_json(sim, &o);
	if (!text || text[0] != '{')
		fail_msg("%s: pool_result_json gave %s", label, text ? "no object" : "NULL");
	json_error_t jerr;
	json_t *doc = json_loads(text, 0, &jerr);
	if (!doc)
		fail_msg("%s: result is not valid JSON: line %d: %s", label, jerr.line, jerr.text);
	json_t *events_json = json_object_get(doc, "events");
	if (!json_is_array(events_json) || (int)json_array_size(events_json) != count)
		fail_msg("%s: result lists %zu events, the simulation %d", label,
		         json_array_size(events_json), count);
	json_decref(doc);
	free(text);
	pool_sim_destroy(sim);
}

// Parses len bytes (copied into an exact-size, unterminated buffer) and checks whatever happens.
static void fuzz_one(const char *data, size_t len, bool sample, const char *label,
                     fuzz_stats *stats) {
	char *exact = malloc(len ? len : 1);
	assert_non_null(exact);
	memcpy(exact, data, len);
	pool_scenario s;
	memset(&s, 0xA5, sizeof s); // parse must not rely on a zeroed scenario
	char err[256];
	memset(err, 'x', sizeof err);
	if (pool_scenario_parse(exact, len, &s, err, sizeof err) != 0) {
		check_rejection(data, len, err, &s, label);
		stats->rejected++;
	} else {
		assert_true(s.ball_count >= 1 && s.balls != NULL);
		check_simulation(&s, sample, label, stats);
		stats->accepted++;
	}
	pool_scenario_free(&s);
	pool_scenario_free(&s);
	free(exact);
}

static long fuzz_case_count(void) {
	const char *env = getenv("POOL_FUZZ_CASES");
	if (env && *env) {
		char *end;
		long n = strtol(env, &end, 10);
		if (*end == '\0' && n >= 0)
			return n;
		fail_msg("POOL_FUZZ_CASES: '%s' is not a count", env);
	}
	return POOL_FUZZ_DEFAULT_CASES;
}

// ---------------------------------------------------------------------------------------------
// Tests.

static void test_seeds_are_valid(void **state) {
	(void)state;
	fuzz_stats stats = {0};
	for (size_t i = 0; i < seeds.count; ++i) {
		pool_scenario s;
		char err[256];
		if (pool_scenario_parse(seeds.docs[i], seeds.lens[i], &s, err, sizeof err) != 0)
			fail_msg("seed %s does not parse: %s", seeds.names[i], err);
		pool_scenario_free(&s);
		fuzz_one(seeds.docs[i], seeds.lens[i], true, seeds.names[i], &stats);
	}
	assert_int_equal(stats.accepted, (long)seeds.count);
}

// Every number field set to every extreme, one at a time, so the corners are always covered
// (the random mutants reach them only by chance).
static void test_every_field_at_extremes(void **state) {
	(void)state;
	static const char *const fields[] = {
		"params.g", "params.mu_slide", "params.mu_roll", "params.mu_spin", "params.mu_ball",
		"params.e_ball", "params.mu_cushion", "params.e_cushion", "params.mu_table",
		"params.e_table", "params.ball_radius", "params.ball_mass", "params.cue_mass",
		"table.length", "table.width", "table.cushion_height", "table.corner_mouth",
		"table.side_mouth", "strike.speed", "strike.phi", "strike.theta", "strike.a", "strike.b",
		"options.max_time", "options.max_events", "vel", "omega",
	};
	static const char *const values[] = {"0", "-0", "1e-320", "1e-9", "0.999999999", "1", "1e9",
	                                     "-1e9", "1e308", "1e999", "-1"};
	fuzz_stats stats = {0};
	buf b = {0};
	for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
		for (size_t v = 0; v < sizeof values / sizeof values[0]; ++v) {
			const char *x = values[v];
			const char *dot = strchr(fields[f], '.');
			char section[16] = "", key[32] = "";
			if (dot) {
				snprintf(section, sizeof section, "%.*s", (int)(dot - fields[f]), fields[f]);
				snprintf(key, sizeof key, "%s", dot + 1);
			}
			bool in_strike = strcmp(section, "strike") == 0;
			buf_set(&b, "", 0);
			buf_cat(&b, "{\"format\": \"libpool-scenario/1\"");
			if (dot && !in_strike)
				buf_printf(&b, ", \"%s\": {\"%s\": %s}", section, key, x);
			// Ball 1 moves (vel/omega under test), ball 0 is struck, ball 2 waits near a pocket.
			buf_printf(&b, ", \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635]},"
			               " {\"id\": 1, \"pos\": [1.2, 0.4], \"vel\": [%s, %s], \"omega\": [%s, 1, %s]},"
			               " {\"id\": 2, \"pos\": [2.45, 1.18]}]",
			           strcmp(fields[f], "vel") == 0 ? x : "0.3", strcmp(fields[f], "vel") == 0 ? x : "0",
			           strcmp(fields[f], "omega") == 0 ? x : "0", strcmp(fields[f], "omega") == 0 ? x : "0");
			buf_printf(&b, ", \"strike\": {\"ball\": 0, \"speed\": %s, \"phi\": %s, \"theta\": %s,"
			               " \"a\": %s, \"b\": %s}}",
			           in_strike && strcmp(key, "speed") == 0 ? x : "3",
			           in_strike && strcmp(key, "phi") == 0 ? x : "10",
			           in_strike && strcmp(key, "theta") == 0 ? x : "0",
			           in_strike && strcmp(key, "a") == 0 ? x : "0.005",
			           in_strike && strcmp(key, "b") == 0 ? x : "-0.01");
			char label[96];
			snprintf(label, sizeof label, "%s = %s", fields[f], x);
			fuzz_one(b.data, b.len, v % 4 == 0, label, &stats);
		}
	}
	free(b.data);
	printf("[ extremes ] %ld accepted and simulated, %ld rejected\n", stats.accepted, stats.rejected);
	assert_true(stats.accepted > 0 && stats.rejected > 0);
}

// Regressions found by this fuzzer, kept as fixed inputs (minimised from the mutant).

// Mutant 487 (seed follow.json) inserted '"":' before a value: the empty key gave the message
// ": unknown field", which names no field. Now the enclosing object is named and the key quoted.
static void test_regression_empty_key_is_named(void **state) {
	(void)state;
	static const struct {
		const char *doc;
		const char *expect;
	} cases[] = {
		{"{\"format\": \"libpool-scenario/1\", \"\": 1, \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		 "(document): unknown field \"\""},
		{"{\"format\": \"libpool-scenario/1\", \"params\": {\"\": 0.2},"
		 " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		 "params: unknown field \"\""},
		{"{\"format\": \"libpool-scenario/1\", \"balls\": [{\"id\": 0, \"\": [], \"pos\": [0.5, 0.5]}]}",
		 "balls[0]: unknown field \"\""},
		{"{\"format\": \"libpool-scenario/1\", \"table\": {\"\": null},"
		 " \"balls\": [{\"id\": 0, \"pos\": [0.5, 0.5]}]}",
		 "table: unknown field \"\""},
	};
	fuzz_stats stats = {0};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
		pool_scenario s;
		char err[256];
		assert_int_equal(pool_scenario_parse(cases[i].doc, strlen(cases[i].doc), &s, err, sizeof err), -1);
		assert_string_equal(err, cases[i].expect);
		fuzz_one(cases[i].doc, strlen(cases[i].doc), false, "empty key", &stats);
	}
	assert_int_equal(stats.rejected, 4);
}

// Mutant 1017 of POOL_FUZZ_SEED=99 (seed "params") set ball_mass to 4.9e-324: the strike's
// 0.4 m R^2 underflowed to 0 and the cue ball's spin after the strike was NaN; a moving ball of
// that mass got a NaN spin at its first cushion. libpool now rejects such a mass.
static void test_regression_subnormal_mass_is_rejected(void **state) {
	(void)state;
	static const char *const docs[] = {
		"{\"format\": \"libpool-scenario/1\", \"params\": {\"g\": 9.8, \"mu_slide\": 0.25, \"mu_roll\": 0.012,"
		" \"mu_spin\": 0.02,  \"mu_ball\": 0.05, \"e_ball\": 0.93, \"mu_cushion\": 0.15, \"e_cushion\": 0.8,"
		"  \"mu_table\": 0.3, \"e_table\": 0.6, \"ball_radius\": 0.0286, \"ball_mass\": 4.9e-324,"
		"  \"cue_mass\": 0.5}, \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635]}, {\"id\": 1, \"pos\": [1.905, 0.7]},"
		"  {\"id\": 2, \"pos\": [2.2, 0.2]}], \"strike\": {\"ball\": 0, \"speed\": 4, \"phi\": 2, \"a\": -0.01,"
		" \"b\": 0.015}}",
		"{\"format\": \"libpool-scenario/1\", \"params\": {\"ball_mass\": 4.9e-324},"
		" \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635], \"vel\": [3, 0.5]}]}",
	};
	fuzz_stats stats = {0};
	for (size_t i = 0; i < sizeof docs / sizeof docs[0]; ++i) {
		pool_scenario s;
		char err[256];
		assert_int_equal(pool_scenario_parse(docs[i], strlen(docs[i]), &s, err, sizeof err), -1);
		assert_non_null(strstr(err, "params.ball_mass: "));
		fuzz_one(docs[i], strlen(docs[i]), false, "subnormal mass", &stats);
	}
	// A tiny but normal mass still works, and the shot stays finite (checked by fuzz_one).
	const char *normal_strike = "{\"format\": \"libpool-scenario/1\", \"params\": {\"ball_mass\": 1e-300},"
	                            " \"balls\": [{\"id\": 0, \"pos\": [0.635, 0.635]}, {\"id\": 1, \"pos\": [1.9, 0.7]}],"
	                            " \"strike\": {\"ball\": 0, \"speed\": 4, \"phi\": 3, \"a\": 0.01}}";
	fuzz_one(normal_strike, strlen(normal_strike), false, "tiny normal mass", &stats);
	assert_int_equal(stats.rejected, 2);
	assert_int_equal(stats.accepted, 1);
}

// Mutant 1684 of the fuzz (seed "params"): 51 balls in two rows, 40 of them touching nothing
// but their neighbours 3.2 mm away, struck along the row. At max_events 1000 a ball-ball collision
// cut a LINK step with one event of room left, and both were recorded: 1001 events (the sanitizer
// build's world check caught it). Every limit around it must hold: never more events than
// max_events, and a shot cut there says so.
static void test_regression_event_limit_with_a_cut_step(void **state) {
	(void)state;
	char doc[4096];
	size_t len = (size_t)snprintf(doc, sizeof doc,
	    "{\"format\": \"libpool-scenario/1\", \"params\": {\"g\": 9.8, \"mu_slide\": 0.25, \"mu_roll\": 0.012,"
	    " \"mu_spin\": 0.02, \"mu_ball\": 0.05, \"e_ball\": 0.93, \"mu_cushion\": 0.15, \"e_cushion\": 0.8,"
	    " \"mu_table\": 0.3, \"e_table\": 0.6, \"ball_radius\": 0.0286, \"ball_mass\": 0.16, \"cue_mass\": 0.5},"
	    " \"balls\": [");
	for (int i = 0; i < 51; ++i)
		len += (size_t)snprintf(doc + len, sizeof doc - len, "%s{\"id\": %d, \"pos\": [%.3f, %.3f]}", i ? "," : "", i,
		                        0.05 + 0.06 * (i % 40), 0.05 + 0.06 * (i / 40));
	len += (size_t)snprintf(doc + len, sizeof doc - len,
	                        "], \"strike\": {\"ball\": 0, \"speed\": 4, \"phi\": 2, \"a\": -0.01, \"b\": 0.015}}");
	assert_true(len < sizeof doc);
	int cut_at_limit = 0;
	for (int limit = 940; limit <= 1060; limit += 4) {
		pool_scenario s;
		char err[256];
		assert_int_equal(pool_scenario_parse(doc, len, &s, err, sizeof err), 0);
		s.def.max_events = limit;
		pool_sim *sim = NULL;
		pool_error e = {{0}};
		assert_int_equal(pool_scenario_setup(&s, &sim, &e), POOL_OK);
		assert_int_equal(pool_sim_run(sim), POOL_OK);
		int count = 0;
		pool_sim_events(sim, &count);
		if (count > limit)
			fail_msg("max_events %d: %d events recorded", limit, count);
		assert_int_equal(pool_sim_stop_reason(sim), POOL_STOP_MAX_EVENTS);
		cut_at_limit += count < limit; // (stopped short: the next event and its cuts had no room)
		pool_sim_destroy(sim);
		pool_scenario_free(&s);
	}
	print_message("[ limits   ] 31 limits from 940 to 1060, %d stopped short of theirs to keep an event whole\n",
	              cut_at_limit);
}

static void test_mutants(void **state) {
	(void)state;
	long cases = fuzz_case_count();
	fuzz_stats stats = {0};
	buf b = {0};
	const char *print_env = getenv("POOL_FUZZ_PRINT");
	long print_case = print_env && *print_env ? strtol(print_env, NULL, 10) : -1;
	rng_state = 0x706F6F6C2D66757Aull; // "pool-fuz": fixed, so every run sees the same mutants
	const char *seed_env = getenv("POOL_FUZZ_SEED"); // for exploring; ctest never sets it
	if (seed_env && *seed_env)
		rng_state = strtoull(seed_env, NULL, 0);
	for (long c = 0; c < cases; ++c) {
		size_t k = rnd(seeds.count);
		buf_set(&b, seeds.docs[k], seeds.lens[k]);
		// Mostly one mutation (inputs stay close to valid, so they reach the simulation).
		size_t mutations = rnd(4) ? 1 : 2 + rnd(4);
		for (size_t m = 0; m < mutations; ++m)
			mutate_once(&b);
		char label[96];
		snprintf(label, sizeof label, "mutant %ld (seed %s)", c, seeds.names[k]);
		if (print_case == c) // POOL_FUZZ_PRINT=N: show mutant N to turn it into a regression case
			fprintf(stderr, "%s:\n%.*s\n", label, (int)b.len, b.data);
		fuzz_one(b.data, b.len, c % 16 == 0, label, &stats);
	}
	free(b.data);
	printf("[ fuzz     ] %ld mutants: %ld accepted and simulated (%ld stopped at max_events, %ld "
	       "run errors), %ld rejected with a field message\n",
	       cases, stats.accepted, stats.stopped_by_events, stats.run_errors, stats.rejected);
	assert_int_equal(stats.accepted + stats.rejected, cases);
}

static int setup(void **state) {
	(void)state;
	load_seeds();
	return 0;
}

static int teardown(void **state) {
	(void)state;
	free_seeds();
	return 0;
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_seeds_are_valid),
		cmocka_unit_test(test_every_field_at_extremes),
		cmocka_unit_test(test_regression_empty_key_is_named),
		cmocka_unit_test(test_regression_subnormal_mass_is_rejected),
		cmocka_unit_test(test_regression_event_limit_with_a_cut_step),
		cmocka_unit_test(test_mutants),
	};
	return cmocka_run_group_tests(tests, setup, teardown);
}
