// Indexed binary min-heap of predicted events with a total, deterministic order.
#include "event_queue.h"

#include "assert.h"

// Both sifts carry the moving slot along and shift the others into the hole it leaves, one
// write per level instead of a swap; keys are distinct (their slots differ), so the top is the
// same whatever path the sift takes.
static void sift_up(pool_event_queue *q, int i) {
	const int slot = q->heap[i];
	const pool_event_key *key = &q->keys[slot];
	while (i > 0) {
		const int parent = (i - 1) / 2, above = q->heap[parent];
		if (!pool_event_queue_before(key, &q->keys[above]))
			break;
		q->heap[i] = above;
		q->pos[above] = i;
		i = parent;
	}
	q->heap[i] = slot;
	q->pos[slot] = i;
}

static void sift_down(pool_event_queue *q, int i) {
	const int slot = q->heap[i];
	const pool_event_key *key = &q->keys[slot];
	for (;;) {
		const int l = 2 * i + 1, r = l + 1;
		if (l >= q->count)
			break;
		int child = l;
		if (r < q->count && pool_event_queue_before(&q->keys[q->heap[r]], &q->keys[q->heap[l]]))
			child = r;
		const int below = q->heap[child];
		if (!pool_event_queue_before(&q->keys[below], key))
			break;
		q->heap[i] = below;
		q->pos[below] = i;
		i = child;
	}
	q->heap[i] = slot;
	q->pos[slot] = i;
}

void pool_event_queue_build(pool_event_queue *q, int count) {
	q->count = count;
	for (int i = 0; i < count; ++i) {
		q->heap[i] = i;
		q->pos[i] = i;
	}
	for (int i = count / 2 - 1; i >= 0; --i)
		sift_down(q, i);
}

void pool_event_queue_update(pool_event_queue *q, int slot, const pool_event_key *key) {
	POOL_ASSERT(slot >= 0 && slot < q->count && key->slot == slot);
	// No event before and none now (a ball at rest predicted again): its place in the heap holds.
	const int none = key->time == INFINITY && q->keys[slot].time == INFINITY;
	const int earlier = pool_event_queue_before(key, &q->keys[slot]);
	q->keys[slot] = *key;
	if (none)
		return;
	if (earlier)
		sift_up(q, q->pos[slot]);
	else
		sift_down(q, q->pos[slot]);
}
