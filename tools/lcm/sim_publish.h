// Live publication of a shot while pool-sim simulates it: its table on POOL_TABLE, each event on
// POOL_EVENT (and with its cushion part on POOL_EVENT2) as it is produced, optional real-time
// playback frames on POOL_STATE, the finished shot on POOL_SHOT and POOL_SHOT2.
// pool-sim calls this only when built with LCM (POOL_HAVE_LCM).
#ifndef POOL_TOOLS_LCM_SIM_PUBLISH_H
#define POOL_TOOLS_LCM_SIM_PUBLISH_H

#include <stddef.h>

#include "pool/game.h"
#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Highest --playback rate in Hz: a frame carries every ball, and faster than a display refreshes
/// only floods the network (1e9 Hz would publish a frame per simulated nanosecond).
#define POOL_LCM_PLAYBACK_MAX_HZ 1000.0

/// An open LCM connection plus the shot being published.
typedef struct pool_lcm_sim_publisher pool_lcm_sim_publisher;

/// Opens LCM on url (NULL or empty: $LCM_DEFAULT_URL, else POOL_LCM_DEFAULT_URL).
/// playback_hz > 0 paces the shot in real time and publishes every ball on POOL_STATE that many
/// times per simulated second (at most POOL_LCM_PLAYBACK_MAX_HZ). Returns NULL with a message in
/// err when the rate is out of range or LCM cannot be opened.
pool_lcm_sim_publisher *pool_lcm_sim_publisher_create(const char *url, double playback_hz,
                                                      char *err, size_t err_size);

/// Per-event hook (pool-sim's sim_event_hook shape; user is the publisher): publishes the event
/// on POOL_EVENT and POOL_EVENT2 (the table first, on the shot's first event); with playback, first publishes the frames before it, each at its wall time.
/// Call it for every event in order, the strike included, right after the sim produced it.
void pool_lcm_sim_publisher_event(const pool_sim *sim, const pool_event *event, void *user);

/// The shot's setup, before its first event: def's table goes on POOL_TABLE before the first event
/// and into the shot2_t on POOL_SHOT2, with the verdict of the rules when game (a scenario's
/// "game") is not NULL. Without it (the default) neither table nor verdict is published.
void pool_lcm_sim_publisher_set_shot(pool_lcm_sim_publisher *publisher, const pool_sim_def *def,
                                     const pool_game_state *game);

/// After the last event: the remaining playback frames up to pool_sim_time, then the shot on
/// POOL_SHOT and on POOL_SHOT2 (shot2_t: the same with the game's verdict). Returns 0, or -1 with a message in err (the first failure of the whole shot).
int pool_lcm_sim_publisher_finish(pool_lcm_sim_publisher *publisher, const pool_sim *sim,
                                  char *err, size_t err_size);

/// Closes LCM and frees the publisher. NULL is a no-op.
void pool_lcm_sim_publisher_destroy(pool_lcm_sim_publisher *publisher);

#ifdef __cplusplus
}
#endif

#endif
