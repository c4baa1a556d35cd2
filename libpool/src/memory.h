// The simulation's memory: every block goes through the def's allocator (docs/library.md
// "Memory and the allocator"), and arrays grow all or nothing, so a failed allocation leaves a
// simulation as it was (usable again once memory is back).
#ifndef POOL_MEMORY_H
#define POOL_MEMORY_H

#include <stddef.h>

#include "pool/base.h"

/// A block of `size` bytes (at least 1) from the allocator, or NULL.
void *pool_mem_alloc(const pool_allocator *a, size_t size);

/// Returns a block to the allocator; NULL is a no-op.
void pool_mem_free(const pool_allocator *a, void *p);

/// The capacity after `cap` that holds `need`: doubling from 16.
int pool_mem_next_cap(int cap, int need);

/// Replaces each *arrays[i] (elems[i] bytes per element, `used` of them live, copied over) by an
/// array of new_cap elements: all of them or none (POOL_ERR_OUT_OF_MEMORY, nothing changed).
pool_result pool_mem_grow(const pool_allocator *a, void **arrays[], const size_t elems[], int count, int used,
                          int new_cap);

#endif
