// The warm starts of LINK steps, by contact: which of each contact's LCP unknowns (its normal
// impulse, its eta friction impulses, its lambda) were basic in the last step that solved it.
//
// A step's answer is usually its previous step's basis (link_step.c, solve_from_basis). Kept
// per contact, rather than for the step's whole contact set, it survives what changes between
// two steps of a cluster without changing most contacts' roles: a contact opening or closing
// elsewhere in the cluster, a ball joining or leaving, another cluster's step in between.
#ifndef POOL_LINK_BASIS_H
#define POOL_LINK_BASIS_H

#include <stdint.h>

#include "pool/base.h"

/// Who a contact is between: the kind (ball-ball, cloth, cushion), then the ball ids in the
/// step's order, or the ball id and the rail. The same two balls in the other order are another
/// contact (its normal, and so its friction directions, point the other way).
typedef struct pool_link_contact_id {
	int32_t kind, a, b;
} pool_link_contact_id;

/// A contact's basic unknowns: bit j - 1 of friction for friction direction j (eta <= 64).
typedef struct pool_link_contact_basis {
	uint64_t friction;
	uint8_t normal, lambda;
} pool_link_contact_basis;

/// Open-addressing table from contact to basis, grown by the allocator (load at most 1/2).
typedef struct pool_link_bases {
	struct pool_link_basis_slot *slots;
	int capacity; ///< a power of two, or 0
	int count;
} pool_link_bases;

/// Forgets every basis (a new shot: the same input gives the same bits whatever ran before).
void pool_link_bases_clear(pool_link_bases *t);

/// The basis last stored for contact id into *out; 0 when there is none (out untouched).
int pool_link_bases_find(const pool_link_bases *t, pool_link_contact_id id, pool_link_contact_basis *out);

/// Stores contact id's basis. POOL_ERR_OUT_OF_MEMORY when the table cannot grow (it is then
/// unchanged: a missing basis only costs a cold solve).
pool_result pool_link_bases_store(pool_link_bases *t, const pool_allocator *alloc, pool_link_contact_id id,
                                  pool_link_contact_basis basis);

/// Frees the table's memory.
void pool_link_bases_free(pool_link_bases *t, const pool_allocator *alloc);

#endif
