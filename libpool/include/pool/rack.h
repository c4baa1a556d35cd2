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
	POOL_RACK_SNOOKER = 2, ///< 15 reds (ids 1..15) behind the pink, the colours on their spots (id 20 + value:
	                       ///< yellow 22, green 23, brown 24, blue 25, pink 26, black 27), cue ball in the D
	POOL_RACK_CAROM = 3,   ///< the carom start: red (id 2) on the foot spot, yellow (id 1) on the head spot,
	                       ///< the cue ball (id 0) on the head string 0.1524 m to its side
} pool_rack_kind;

/// Writes the cue ball (id 0, on the head spot x = L/4, y = W/2) and the object balls, apex on
/// the foot spot (x = 3L/4, y = W/2), neighbours `gap` m apart (0 = frozen), all at rest on the
/// cloth. Snooker: the WPBSA spots (baulk line 737 mm from the west cushion, D of radius 292 mm,
/// black 324 mm from the east cushion, pink midway between the centre and that cushion), scaled
/// to the table, the reds' apex `gap` + 2 R behind the pink. Returns the number of balls written,
/// or a negative pool_result if capacity is too small.
POOL_API int pool_rack(pool_rack_kind kind, const pool_table_def *table, const pool_params *params,
                       double gap, pool_ball_state *balls, int capacity);

/// A centre-ball break straight at the apex, level cue, at `speed` m/s.
POOL_API pool_strike pool_break_strike(double speed);

/// The break of a rack written by pool_rack: centre ball, level cue, at `speed` m/s, aimed from
/// the cue ball (balls[0]) at the first object ball (balls[1]: the apex, the carom start's red...).
POOL_API pool_strike pool_rack_break_strike(const pool_ball_state *balls, int count, double speed);

#ifdef __cplusplus
}
#endif

#endif
