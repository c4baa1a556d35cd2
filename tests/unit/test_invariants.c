// The invariant checks can fail (libpool/src/invariants.c, assert.h): in builds that check them
// (the sanitizer build), a world whose heap, cluster or history is broken behind the library's
// back is caught by pool_world_check, which aborts; each is broken in a child process, which must
// die of SIGABRT, while the intact world passes. Without the checks (Release) the test says so.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "invariants.h"
#include "pool/pool.h"
#include "world.h"

typedef void (*breaker)(pool_sim *sim);

// A 0.1 mm-gap break run to its first LINK step, so the world has a heap, clusters and a history
// to break: under the 2012 laws on their table (pockets "mouth_lines") it forms clusters (13 link
// steps), under the default laws none.
static pool_sim *running_break(void) {
	pool_sim_def def = thesis_sim_def();
	def.table.pockets = POOL_POCKETS_MOUTH_LINES;
	pool_sim *sim = make_sim(&def);
	pool_ball_state balls[16];
	const int n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 1e-4, balls, 16);
	for (int i = 0; i < n; ++i)
		add_ball(sim, &balls[i]);
	pool_strike s = pool_break_strike(8.0);
	assert_int_equal(pool_sim_strike(sim, 0, &s, NULL), POOL_OK);
	for (int k = 0; k < 100000; ++k) {
		int count = 0;
		const pool_event *ev = pool_sim_events(sim, &count);
		if (count > 0 && ev[count - 1].type == POOL_EVENT_LINK_STEP)
			break;
		assert_true(pool_sim_step(sim) > 0);
	}
	return sim;
}

static void break_heap(pool_sim *sim) { // two heap positions swapped: a parent after its child
	int *heap = sim->queue.heap;
	const int a = heap[0], b = heap[1];
	heap[0] = b;
	heap[1] = a;
	sim->queue.pos[a] = 1;
	sim->queue.pos[b] = 0;
}

static void break_cluster(pool_sim *sim) { // a linked ball LINK no longer holds
	for (int i = 0; i < sim->n; ++i)
		if (sim->link.cluster_of[i] >= 0) {
			sim->link.cluster_of[i] = -1;
			return;
		}
	fail_msg("no linked ball to break");
}

static void break_history(pool_sim *sim) { // an event back in time
	pool_history *h = &sim->history;
	assert_true(h->n_events > 2);
	h->checked_events = 0;
	h->events[1].time = h->events[h->n_events - 1].time + 1.0;
}

static void break_partner(pool_sim *sim) { // a pending contact with a ball out of range
	sim->body[0].partner = sim->n;
}

// 1 when pool_world_check aborts on the world `breaker` leaves.
static int aborts(breaker brk) {
	fflush(NULL);
	const pid_t child = fork();
	assert_true(child >= 0);
	if (child == 0) {
		pool_sim *sim = running_break();
		if (brk)
			brk(sim);
		pool_world_check(sim);
		_exit(0);
	}
	int status = 0;
	assert_int_equal(waitpid(child, &status, 0), child);
	if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
		return 0;
	if (WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT)
		return 1;
	fail_msg("the child ended neither normally nor by SIGABRT (status %d)", status);
	return -1;
}

static void test_world_check_can_fail(void **state) {
	(void)state;
	if (!POOL_ASSERTS_ON) {
		print_message("invariant checks compiled out (configure with -DPOOL_ASSERTS=ON or -DPOOL_SANITIZE=ON)\n");
		skip();
	}
	assert_int_equal(aborts(NULL), 0); // the intact world passes
	assert_int_equal(aborts(break_heap), 1);
	assert_int_equal(aborts(break_cluster), 1);
	assert_int_equal(aborts(break_history), 1);
	assert_int_equal(aborts(break_partner), 1);
}

int main(void) {
	const struct CMUnitTest tests[] = {
	    cmocka_unit_test(test_world_check_can_fail),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
