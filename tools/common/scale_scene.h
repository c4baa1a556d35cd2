// Scenes at scale: the same kind of scene with 2 to 4,096 balls on a table whose area grows with
// the ball count (16 balls per standard 9 ft table area). Defined once here for the comparison's
// scale families (pool-compare --scale, docs/comparison.md) and the per-event benchmark
// (pool-bench-scale, docs/library.md). libpool only.
#ifndef POOL_TOOLS_SCALE_SCENE_H
#define POOL_TOOLS_SCALE_SCENE_H

#include <stdbool.h>
#include <stddef.h>

#include "pool/pool.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Largest ball count of a scale scene.
#define POOL_SCALE_MAX_BALLS 4096

/// Balls per standard table area (WPA 9 ft, 2.54 x 1.27 m): a racked 8-ball table.
#define POOL_SCALE_BALLS_PER_TABLE 16

/// Fills a scale scene of `balls` balls (ids 0 .. balls - 1) for `family`, the same on every
/// platform for the same arguments (a generator of its own, seeded by the ball count). Both
/// families play on a table of balls / 16 standard areas (2:1, the standard nose height,
/// pocketless: corner and side mouths 0, so every ball stays in play):
/// - "break": the cue ball (id 0) 1.27 m before the apex (on a table shorter than the standard
///   one, a quarter of the length before it) and 5 mm beside the axis of a triangular rack of
///   balls - 1 object balls 0.1 mm apart (rows of 1, 2, 3, ... balls, the last one partial, on its
///   middle sites), apex at 3/4 of the length; a centre-ball strike at 6 m/s along the table (on
///   the axis, the apex ball would meet the two balls behind it at one instant, where pairwise
///   events are ill-posed).
/// - "gas": balls at uniformly random places at least 3 mm apart and 1 cm inside R of the rail
///   lines, a quarter of them (ids 0 .. balls / 4 - 1) rolling at 0.5-2 m/s in random directions,
///   the rest at rest; no strike.
/// `out` holds `balls` states (z = R, motion left to the library). Returns 0, or -1 with a
/// message in err for an unknown family or a ball count outside [2, POOL_SCALE_MAX_BALLS].
int pool_scale_scene(const char *family, int balls, const pool_params *params, pool_table_def *table,
                     pool_ball_state *out, bool *has_strike, pool_strike *strike, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
