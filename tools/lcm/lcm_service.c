// Stop signals, opening LCM and waiting for datagrams, for the long-running LCM commands.
#define _POSIX_C_SOURCE 200809L // sigaction
#include "lcm_service.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

#include "lcm_convert.h"

// Set by the signal handler, read by every thread (pool-shot-server's workers look at it between
// chunks of a shot): a lock-free atomic, so the handler may write it (C11 7.14.1.1) and the other
// threads' reads are not a data race (a volatile sig_atomic_t is only safe within one thread).
static atomic_int pool_lcm_stop_flag = 0;
_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "the stop flag must be lock-free to be set by a signal");

static void pool_lcm_on_stop_signal(int signal_number)
{
	(void)signal_number;
	int saved_errno = errno;
	atomic_store(&pool_lcm_stop_flag, 1);
	errno = saved_errno;
}

bool pool_lcm_url_option(int argc, char **argv, int *i, const char **url)
{
	const char *a = argv[*i];
	if (strcmp(a, "--lcm-url") == 0 && *i + 1 < argc) {
		*url = argv[++*i];
		return true;
	}
	if (strncmp(a, "--lcm-url=", 10) == 0) {
		*url = a + 10;
		return true;
	}
	return false;
}

void pool_lcm_catch_stop_signals(void)
{
	struct sigaction action;
	memset(&action, 0, sizeof action);
	action.sa_handler = pool_lcm_on_stop_signal;
	sigemptyset(&action.sa_mask);
	sigaction(SIGINT, &action, NULL);
	sigaction(SIGTERM, &action, NULL);
}

bool pool_lcm_stop_requested(void)
{
	return atomic_load(&pool_lcm_stop_flag) != 0;
}

lcm_t *pool_lcm_open(const char *url, char *err, size_t err_size)
{
	const char *resolved = pool_lcm_resolve_url(url);
	lcm_t *lcm = lcm_create(resolved);
	if (lcm == NULL) {
		snprintf(err, err_size, "--lcm-url: cannot open LCM on '%s'", resolved);
	}
	return lcm;
}

int pool_lcm_wait(lcm_t *lcm, int timeout_ms)
{
	struct pollfd pfd = {.fd = lcm_get_fileno(lcm), .events = POLLIN};
	int ready = poll(&pfd, 1, timeout_ms);
	if (ready < 0) {
		return errno == EINTR ? 0 : -1;
	}
	return ready > 0 ? 1 : 0;
}
