// The event list: an indexed binary min-heap with one slot per body (a ball today, a LINK
// cluster later) holding that body's next predicted event. Keys are absolute times with a
// deterministic tie-break (time, event kind, the bodies' order ids, slot); nothing in the heap
// assumes how many balls an event involves.
#ifndef POOL_EVENT_QUEUE_H
#define POOL_EVENT_QUEUE_H

#include <math.h>
#include <stdint.h>

/// Ordering key of a predicted event.
typedef struct pool_event_key {
	double time;    ///< s, absolute; INFINITY when the slot has no event
	int kind;       ///< pool_event_type
	int32_t order_lo; ///< smaller order id of the bodies involved (a ball's id)
	int32_t order_hi; ///< larger one (= order_lo for an event of one body)
	int slot;         ///< owning slot (body index), last resort so the order is total
} pool_event_key;

/// -1, 0, 1 as a orders before, equal to, after b. Inline: the heap and the pair loop compare keys
/// at every step.
static inline int pool_event_key_cmp(const pool_event_key *a, const pool_event_key *b) {
	if (a->time != b->time)
		return a->time < b->time ? -1 : 1;
	if (a->kind != b->kind)
		return a->kind < b->kind ? -1 : 1;
	if (a->order_lo != b->order_lo)
		return a->order_lo < b->order_lo ? -1 : 1;
	if (a->order_hi != b->order_hi)
		return a->order_hi < b->order_hi ? -1 : 1;
	if (a->slot != b->slot)
		return a->slot < b->slot ? -1 : 1;
	return 0;
}

/// 1 when key a goes above key b in the heap: the keys' order, except that slots with no event
/// (time INFINITY, most of the balls at rest) stay in any order among themselves. Their order
/// never matters: one of them on top means that nothing will happen again, whichever it is (the
/// world stops at rest), and comparing such ties in full took a fifth of the sifts.
static inline int pool_event_queue_before(const pool_event_key *a, const pool_event_key *b) {
	if (a->time != b->time)
		return a->time < b->time;
	return a->time != INFINITY && pool_event_key_cmp(a, b) < 0;
}

/// Heap over `count` slots; the caller owns the arrays (capacity >= count each).
typedef struct pool_event_queue {
	pool_event_key *keys; ///< by slot
	int *heap;            ///< slots in heap order
	int *pos;             ///< heap position of each slot
	int count;
} pool_event_queue;

/// Puts slots 0..count-1 in the heap with their current keys (O(count)).
void pool_event_queue_build(pool_event_queue *q, int count);

/// Sets a slot's key and restores the heap order (O(log count)).
void pool_event_queue_update(pool_event_queue *q, int slot, const pool_event_key *key);

/// Slot with the smallest key (count must be > 0).
static inline int pool_event_queue_top(const pool_event_queue *q) { return q->heap[0]; }

#endif
