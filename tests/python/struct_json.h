// The JSON of the struct_sizes programs (tests/python, tests/games): sizeof and offsetof of each
// structure a ctypes binding mirrors, {"pool_vec3": {"size": 24, "fields": {"x": 0, ...}}, ...}.
// Call begin() for each structure, then FIELD() for each of its fields (last: 1 for the last).
#ifndef POOL_TESTS_STRUCT_JSON_H
#define POOL_TESTS_STRUCT_JSON_H

#include <stddef.h>
#include <stdio.h>

static int struct_json_first = 1;

static void begin(const char *name, size_t size) {
	printf("%s\"%s\": {\"size\": %zu, \"fields\": {", struct_json_first ? "" : ", ", name, size);
	struct_json_first = 0;
}

#define FIELD(type, field, last) printf("\"%s\": %zu%s", #field, offsetof(type, field), (last) ? "}}" : ", ")

#endif
