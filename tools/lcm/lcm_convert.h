// Conversion between libpool simulations and the pool_lcm message types (lcm_types/), shared by
// pool-sim --lcm-url, pool-shot-server and the tests. Messages built here own heap arrays: release
// them with the matching *_release function, never with lcm-gen's *_destroy.
#ifndef POOL_TOOLS_LCM_CONVERT_H
#define POOL_TOOLS_LCM_CONVERT_H

#include <stddef.h>
#include <stdint.h>

#include "pool/game.h"
#include "pool/pool.h"
#include "pool_lcm_ball_state_t.h"
#include "pool_lcm_event2_t.h"
#include "pool_lcm_event_t.h"
#include "pool_lcm_shot_request_t.h"
#include "pool_lcm_shot2_t.h"
#include "pool_lcm_shot_t.h"
#include "pool_lcm_table_state_t.h"
#include "pool_lcm_table_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Channel of scenarios to simulate (shot_request_t).
#define POOL_LCM_CHANNEL_SHOT_REQUEST "POOL_SHOT_REQUEST"
/// Channel of finished shots (shot_t).
#define POOL_LCM_CHANNEL_SHOT "POOL_SHOT"
/// Channel of finished shots with the later fields (shot2_t), beside every shot_t on POOL_SHOT.
#define POOL_LCM_CHANNEL_SHOT2 "POOL_SHOT2"
/// Channel of events as they are produced (event_t).
#define POOL_LCM_CHANNEL_EVENT "POOL_EVENT"
/// Channel of events with the later fields (event2_t), right after each event_t on POOL_EVENT.
#define POOL_LCM_CHANNEL_EVENT2 "POOL_EVENT2"
/// Channel of the table of each streamed shot (table_t), before its first event.
#define POOL_LCM_CHANNEL_TABLE "POOL_TABLE"
/// Channel of real-time playback frames (table_state_t).
#define POOL_LCM_CHANNEL_STATE "POOL_STATE"
/// Channel of engine comparison results (bench_result_t).
#define POOL_LCM_CHANNEL_BENCH "POOL_BENCH"
/// URL used when neither --lcm-url nor LCM_DEFAULT_URL is given: docs/interfaces.md's group, port and
/// ttl, plus a receive buffer large enough for multi-megabyte shots (README, "Message size").
#define POOL_LCM_DEFAULT_URL "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"

/// Microseconds since the Unix epoch (wall clock), the utime of every message.
int64_t pool_lcm_utime_now(void);

/// The URL to open: the given one, else $LCM_DEFAULT_URL, else POOL_LCM_DEFAULT_URL.
const char *pool_lcm_resolve_url(const char *url);

/// Copies a libpool ball state into a message field.
void pool_lcm_ball_from_state(const pool_ball_state *state, pool_lcm_ball_state_t *out);

/// Fills an event message for processed event `seq` of sim (balls: its after-states).
/// Returns 0, or -1 when memory runs out or seq is out of range.
int pool_lcm_event_fill(const pool_sim *sim, int seq, int64_t shot_id, int64_t utime,
                        pool_lcm_event_t *out);

/// Frees what pool_lcm_event_fill allocated; safe on a zeroed message.
void pool_lcm_event_release(pool_lcm_event_t *msg);

/// Fills a shot message from a (finished or stopped) sim: every event, and the final states of
/// every ball at pool_sim_time. Returns 0, or -1 when memory runs out or the sim refuses.
int pool_lcm_shot_fill(const pool_sim *sim, int64_t shot_id, int64_t request_id, int64_t utime,
                       pool_lcm_shot_t *out);

/// Fills a shot message with no events: the final states of every ball at pool_sim_time,
/// sim_time and stop_reason (the answer to a request whose events do not fit in a message).
/// Returns 0, or -1 when memory runs out or the sim refuses.
int pool_lcm_shot_fill_final(const pool_sim *sim, int64_t shot_id, int64_t request_id,
                             int64_t utime, pool_lcm_shot_t *out);

/// Bytes the events of sim add to an encoded shot_t: pool_lcm_shot_t_encoded_size of what
/// pool_lcm_shot_fill builds equals that of pool_lcm_shot_fill_final plus this. Measured one
/// event at a time, without building the whole message. -1 when memory runs out.
int64_t pool_lcm_shot_events_encoded_size(const pool_sim *sim);

/// Replaces the error of a message built here with a copy of message. Returns 0, or -1 (message
/// unchanged) when memory runs out.
int pool_lcm_shot_set_error(pool_lcm_shot_t *msg, const char *message);

/// Fills a shot message that carries only an error (no events, no balls); copies message.
int pool_lcm_shot_fill_error(int64_t shot_id, int64_t request_id, int64_t utime,
                             const char *message, pool_lcm_shot_t *out);

/// Frees what pool_lcm_shot_fill / pool_lcm_shot_fill_error allocated; safe on a zeroed message.
void pool_lcm_shot_release(pool_lcm_shot_t *msg);

/// Fills a table message: def's table (cut angles in degrees), its balls' radius and the result
/// file's setup as JSON. def NULL: an empty message (has no table). Returns 0, or -1 when memory
/// runs out.
int pool_lcm_table_fill(const pool_sim_def *def, int64_t shot_id, int64_t utime, pool_lcm_table_t *out);

/// Frees what pool_lcm_table_fill allocated; safe on a zeroed message.
void pool_lcm_table_release(pool_lcm_table_t *msg);

/// Fills an event2_t for processed event `seq` of sim: its event_t and the cushion's part.
/// Returns 0, or -1 when memory runs out or seq is out of range.
int pool_lcm_event2_fill(const pool_sim *sim, int seq, int64_t shot_id, int64_t utime,
                         pool_lcm_event2_t *out);

/// Frees what pool_lcm_event2_fill allocated.
void pool_lcm_event2_release(pool_lcm_event2_t *msg);

/// Fills a shot2_t around shot (borrowed: out->shot is a shallow copy, so shot must outlive out):
/// the cushion's part of each of its events (from sim, whose events they are; sim may be NULL for
/// a shot without events), the table of def (NULL: none, an error answer), and the verdict of
/// the rules when game is not NULL: the shot sim ran judged under game on def's table. Returns 0,
/// or -1 when memory runs out, sim's events are not the shot's, or the rules refuse the shot.
int pool_lcm_shot2_fill(const pool_lcm_shot_t *shot, const pool_sim *sim, const pool_sim_def *def,
                        const pool_game_state *game, pool_lcm_shot2_t *out);

/// Frees what pool_lcm_shot2_fill allocated (the game fields, the parts and the table, not the
/// borrowed shot).
void pool_lcm_shot2_release(pool_lcm_shot2_t *msg);

/// Fills a playback frame: every ball at simulated time t (s), which the sim must have reached.
int pool_lcm_table_state_fill(const pool_sim *sim, double t, int64_t shot_id, int64_t utime,
                              pool_lcm_table_state_t *out);

/// Frees what pool_lcm_table_state_fill allocated; safe on a zeroed message.
void pool_lcm_table_state_release(pool_lcm_table_state_t *msg);

/// Checks a shot_request_t datagram's framing and type fingerprint, as pool_lcm_request_decode
/// does, without copying the scenario: sets *request_id (when not NULL) and returns 0, or returns
/// -1 with a message in err. Lets pool-shot-server refuse a large request without decoding it.
int pool_lcm_request_peek(const void *data, size_t size, int64_t *request_id, char *err,
                          size_t err_size);

/// Decodes a shot_request_t datagram after checking its framing by hand (lcm-gen's decoder trusts
/// the string length and terminator). Returns 0, or -1 with a message in err; on success release
/// with pool_lcm_shot_request_t_decode_cleanup.
int pool_lcm_request_decode(const void *data, size_t size, pool_lcm_shot_request_t *out,
                            char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
