// The simulation's memory (memory.h).
#include "memory.h"

#include <string.h>

/// Arrays one pool_mem_grow call replaces at most.
#define POOL_MEM_GROW_MAX 16

void *pool_mem_alloc(const pool_allocator *a, size_t size) { return a->alloc(size ? size : 1, a->context); }

void pool_mem_free(const pool_allocator *a, void *p) {
	if (p)
		a->free(p, a->context);
}

int pool_mem_next_cap(int cap, int need) {
	int c = cap > 0 ? cap : 16;
	while (c < need)
		c *= 2;
	return c;
}

pool_result pool_mem_grow(const pool_allocator *a, void **arrays[], const size_t elems[], int count, int used,
                          int new_cap) {
	void *fresh[POOL_MEM_GROW_MAX];
	if (count > POOL_MEM_GROW_MAX)
		return POOL_ERR_INVALID_ARGUMENT;
	for (int i = 0; i < count; ++i) {
		fresh[i] = pool_mem_alloc(a, elems[i] * (size_t)new_cap);
		if (!fresh[i]) {
			for (int j = 0; j < i; ++j)
				pool_mem_free(a, fresh[j]);
			return POOL_ERR_OUT_OF_MEMORY;
		}
	}
	for (int i = 0; i < count; ++i) {
		if (*arrays[i] && used > 0)
			memcpy(fresh[i], *arrays[i], elems[i] * (size_t)used);
		pool_mem_free(a, *arrays[i]);
		*arrays[i] = fresh[i];
	}
	return POOL_OK;
}
