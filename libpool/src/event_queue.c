// Indexed binary min-heap of predicted events with a total, deterministic order.
#include "event_queue.h"

#include "assert.h"

static int less(const pool_event_queue *q, int i, int j) {
	return pool_event_key_cmp(&q->keys[q->heap[i]], &q->keys[q->heap[j]]) < 0;
}

static void swap(pool_event_queue *q, int i, int j) {
	int a = q->heap[i], b = q->heap[j];
	q->heap[i] = b;
	q->heap[j] = a;
	q->pos[b] = i;
	q->pos[a] = j;
}

static void sift_up(pool_event_queue *q, int i) {
	while (i > 0) {
		int parent = (i - 1) / 2;
		if (!less(q, i, parent))
			break;
		swap(q, i, parent);
		i = parent;
	}
}

static void sift_down(pool_event_queue *q, int i) {
	for (;;) {
		int l = 2 * i + 1, r = l + 1, m = i;
		if (l < q->count && less(q, l, m))
			m = l;
		if (r < q->count && less(q, r, m))
			m = r;
		if (m == i)
			break;
		swap(q, i, m);
		i = m;
	}
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
	q->keys[slot] = *key;
	int i = q->pos[slot];
	sift_up(q, i);
	sift_down(q, q->pos[slot]);
}
