// Warm-start bases by contact (link_basis.h): open addressing with linear probing.
#include "link_basis.h"

#include <string.h>

typedef struct pool_link_basis_slot {
	pool_link_contact_id id;
	pool_link_contact_basis basis;
	int used;
} pool_link_basis_slot;

/// Slots of a new table: room for 64 contacts, more than a rack's cluster has (47).
#define POOL_LINK_BASES_INITIAL 128

static uint32_t hash_of(pool_link_contact_id id) {
	uint32_t h = 2166136261u;
	const int32_t v[3] = {id.kind, id.a, id.b};
	for (int i = 0; i < 3; ++i)
		h = (h ^ (uint32_t)v[i]) * 16777619u;
	return h ^ (h >> 15);
}

static int same(pool_link_contact_id x, pool_link_contact_id y) { return x.kind == y.kind && x.a == y.a && x.b == y.b; }

/// The slot holding id, or the free slot where it belongs.
static pool_link_basis_slot *slot_for(pool_link_basis_slot *slots, int capacity, pool_link_contact_id id) {
	uint32_t at = hash_of(id) & (uint32_t)(capacity - 1);
	while (slots[at].used && !same(slots[at].id, id))
		at = (at + 1) & (uint32_t)(capacity - 1);
	return &slots[at];
}

void pool_link_bases_clear(pool_link_bases *t) {
	// Empty already (count counts the used slots): a shot without LINK clears nothing, where the
	// table a large cluster grew would cost every reset a memset of all its slots.
	if (t->slots && t->count > 0)
		memset(t->slots, 0, sizeof *t->slots * (size_t)t->capacity);
	t->count = 0;
}

int pool_link_bases_find(const pool_link_bases *t, pool_link_contact_id id, pool_link_contact_basis *out) {
	if (t->capacity == 0)
		return 0;
	const pool_link_basis_slot *s = slot_for(t->slots, t->capacity, id);
	if (!s->used)
		return 0;
	*out = s->basis;
	return 1;
}

static pool_result grow(pool_link_bases *t, const pool_allocator *alloc) {
	const int capacity = t->capacity ? 2 * t->capacity : POOL_LINK_BASES_INITIAL;
	if (capacity <= 0 || (size_t)capacity > ((size_t)-1) / sizeof(pool_link_basis_slot))
		return POOL_ERR_OUT_OF_MEMORY;
	pool_link_basis_slot *slots = alloc->alloc(sizeof *slots * (size_t)capacity, alloc->context);
	if (!slots)
		return POOL_ERR_OUT_OF_MEMORY;
	memset(slots, 0, sizeof *slots * (size_t)capacity);
	for (int i = 0; i < t->capacity; ++i)
		if (t->slots[i].used)
			*slot_for(slots, capacity, t->slots[i].id) = t->slots[i];
	if (t->slots)
		alloc->free(t->slots, alloc->context);
	t->slots = slots;
	t->capacity = capacity;
	return POOL_OK;
}

pool_result pool_link_bases_store(pool_link_bases *t, const pool_allocator *alloc, pool_link_contact_id id,
                                  pool_link_contact_basis basis) {
	if (2 * (t->count + 1) > t->capacity) {
		const pool_result r = grow(t, alloc);
		if (r)
			return r;
	}
	pool_link_basis_slot *s = slot_for(t->slots, t->capacity, id);
	if (!s->used) {
		s->used = 1;
		s->id = id;
		++t->count;
	}
	s->basis = basis;
	return POOL_OK;
}

void pool_link_bases_free(pool_link_bases *t, const pool_allocator *alloc) {
	if (t->slots && alloc && alloc->free)
		alloc->free(t->slots, alloc->context);
	memset(t, 0, sizeof *t);
}
