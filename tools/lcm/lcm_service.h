// The plumbing of an LCM command that runs until told to stop (pool-shot-server,
// pool-lcm-subscribe): the --lcm-url option, stop flags set by SIGINT/SIGTERM, opening the URL,
// waiting for datagrams.
#ifndef POOL_TOOLS_LCM_SERVICE_H
#define POOL_TOOLS_LCM_SERVICE_H

#include <stdbool.h>
#include <stddef.h>

#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Recognises the URL option at argv[*i]: "--lcm-url URL" (moving *i onto URL) or
/// "--lcm-url=URL". Sets *url and returns true; false, changing nothing, for any other argument
/// (a "--lcm-url" with nothing after it included).
bool pool_lcm_url_option(int argc, char **argv, int *i, const char **url);

/// Makes SIGINT and SIGTERM set the stop flag instead of killing the process, so the command can
/// leave its loop and clean up.
void pool_lcm_catch_stop_signals(void);

/// True once SIGINT or SIGTERM arrived (after pool_lcm_catch_stop_signals).
bool pool_lcm_stop_requested(void);

/// Opens LCM on url resolved by pool_lcm_resolve_url. Returns NULL with
/// "--lcm-url: cannot open LCM on 'URL'" in err when liblcm refuses.
lcm_t *pool_lcm_open(const char *url, char *err, size_t err_size);

/// Waits up to timeout_ms for a datagram on lcm without handling it. Returns 1 when one is ready
/// (call lcm_handle), 0 on timeout or when a signal interrupted the wait, -1 when poll failed
/// (errno set).
int pool_lcm_wait(lcm_t *lcm, int timeout_ms);

#ifdef __cplusplus
}
#endif

#endif
