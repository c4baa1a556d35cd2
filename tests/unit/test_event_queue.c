// The event queue: total deterministic order (time, kind, ids, slot) under random updates.
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "event_queue.h"

static uint64_t seed = 7;
static uint32_t next(void) {
	seed = seed * 6364136223846793005ull + 1442695040888963407ull;
	return (uint32_t)(seed >> 33);
}

static void test_order(void **state) {
	(void)state;
	pool_event_key a = {1.0, 4, 1, 2, 0}, b = a;
	assert_int_equal(pool_event_key_cmp(&a, &b), 0);
	b.time = nextafter(1.0, 2.0);
	assert_int_equal(pool_event_key_cmp(&a, &b), -1);
	b = a;
	b.kind = 1; // slide_roll before ball_ball at the same time
	assert_int_equal(pool_event_key_cmp(&a, &b), 1);
	b = a;
	b.order_hi = 3;
	assert_int_equal(pool_event_key_cmp(&a, &b), -1);
	b = a;
	b.order_lo = 0;
	assert_int_equal(pool_event_key_cmp(&a, &b), 1);
	b = a;
	b.slot = 1;
	assert_int_equal(pool_event_key_cmp(&a, &b), -1);
	b.time = INFINITY;
	assert_int_equal(pool_event_key_cmp(&a, &b), -1);
}

// The top is always the minimum over all slots, with many ties; slots with no event (time
// INFINITY) are on top only when every slot has none, in any order among themselves.
static void test_heap(void **state) {
	(void)state;
	enum { N = 40 };
	pool_event_key keys[N];
	int heap[N], pos[N];
	pool_event_queue q = {keys, heap, pos, 0};
	for (int i = 0; i < N; ++i)
		keys[i] = (pool_event_key){(double)(next() % 5), (int)(next() % 3), (int32_t)(next() % 4), 0, i};
	pool_event_queue_build(&q, N);
	for (int step = 0; step < 20000; ++step) {
		int top = pool_event_queue_top(&q);
		for (int i = 0; i < N; ++i)
			assert_true(keys[top].time == INFINITY ? keys[i].time == INFINITY : pool_event_key_cmp(&keys[top], &keys[i]) <= 0);
		int slot = (int)(next() % N);
		pool_event_key k = {next() % 7 == 0 ? INFINITY : (double)(next() % 5), (int)(next() % 3),
		                    (int32_t)(next() % 4), (int32_t)(next() % 4), slot};
		pool_event_queue_update(&q, slot, &k);
		for (int i = 0; i < N; ++i)
			assert_int_equal(heap[pos[i]], i);
	}
	// Every slot's event goes, one at a time: the top has one while any slot does; then an event
	// in any slot comes to the top.
	for (int i = 0; i < N; ++i) {
		const pool_event_key k = {INFINITY, (int)(next() % 3), (int32_t)(next() % 4), (int32_t)(next() % 4), i};
		pool_event_queue_update(&q, i, &k);
		assert_true((keys[pool_event_queue_top(&q)].time == INFINITY) == (i == N - 1));
	}
	for (int i = 0; i < N; ++i) {
		const pool_event_key k = {(double)i, 0, 0, 0, i};
		pool_event_queue_update(&q, i, &k);
		assert_int_equal(pool_event_queue_top(&q), 0);
		for (int j = 0; j < N; ++j)
			assert_int_equal(heap[pos[j]], j);
	}
}

int main(void) {
	const struct CMUnitTest tests[] = {cmocka_unit_test(test_order), cmocka_unit_test(test_heap)};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
