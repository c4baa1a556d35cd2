// libpool: standard racks and break strikes, so users need not compute triangle coordinates.
#ifndef POOL_RACK_H
#define POOL_RACK_H

#include "pool/ball.h"
#include "pool/strike.h"
#include "pool/table.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Game whose rack to build.
typedef enum pool_rack_kind {
	POOL_RACK_8BALL = 0, ///< 15 object balls (ids 1..15) in a triangle, 8 in the centre
	POOL_RACK_9BALL = 1, ///< 9 object balls (ids 1..9) in a diamond, 1 at the apex, 9 in the centre
} pool_rack_kind;

/// Writes the cue ball (id 0, on the head spot x = L/4, y = W/2) and the object balls, apex on
/// the foot spot (x = 3L/4, y = W/2), neighbours `gap` m apart (0 = frozen), all at rest on the
/// cloth. Returns the number of balls written, or a negative pool_result if capacity is too small.
POOL_API int pool_rack(pool_rack_kind kind, const pool_table_def *table, const pool_params *params,
                       double gap, pool_ball_state *balls, int capacity);

/// A centre-ball break straight at the apex, level cue, at `speed` m/s.
POOL_API pool_strike pool_break_strike(double speed);

#ifdef __cplusplus
}
#endif

#endif
