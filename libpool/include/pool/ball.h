// libpool: the state of one ball.
#ifndef POOL_BALL_H
#define POOL_BALL_H

#include <stdint.h>

#include "pool/base.h"
#include "pool/table.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Motion state of a ball; values are stable (they travel in LCM messages).
typedef enum pool_motion {
	POOL_MOTION_STATIONARY = 0, ///< at rest on the cloth
	POOL_MOTION_SPINNING = 1,   ///< on the cloth, only spin about z
	POOL_MOTION_SLIDING = 2,    ///< on the cloth, contact point slips
	POOL_MOTION_ROLLING = 3,    ///< on the cloth, no slip
	POOL_MOTION_AIRBORNE = 4,   ///< in flight
	POOL_MOTION_LINKED = 5,     ///< part of a LINK cluster (persistent contact)
	POOL_MOTION_POCKETED = 6,   ///< fell into a pocket; no longer simulated
	POOL_MOTION_OFF_TABLE = 7,  ///< left the table; no longer simulated
} pool_motion;

/// Lower-case name as in docs/interfaces.md ("stationary", "sliding", ...).
POOL_API const char *pool_motion_name(pool_motion motion);

/// Parses a name from pool_motion_name; returns -1 when unknown.
POOL_API int pool_motion_from_name(const char *name);

/// m/s, the fastest motion libpool simulates: a ball's speed, its spin's surface speed |w| R and
/// the cue speed of a strike above it are refused (POOL_ERR_INVALID_ARGUMENT / _BAD_STRIKE). It
/// is seven times the fastest measured break cue (about 14 m/s); the library's tolerances (a
/// nanometre of overlap, 1e-9 m/s of approach) are sized for table-scale motion, and absurd
/// speeds (1e200 m/s) would overflow the contact polynomials into nonsense.
#define POOL_MAX_SPEED 100.0

/// One ball: identity, motion state and kinematics (world frame).
typedef struct pool_ball_state {
	int32_t id;         ///< user-chosen, unique in a simulation
	pool_motion motion; ///< derived from the velocities when a ball is added
	pool_vec3 pos;      ///< m, centre; z = R on the cloth
	pool_vec3 vel;      ///< m/s
	pool_vec3 omega;    ///< rad/s
} pool_ball_state;

/// A ball at rest on the cloth at (x, y): centre at z = params->ball_radius, no velocity, no
/// spin, motion stationary; what pool_sim_add_ball needs in planar mode (a zero-initialised
/// state has z = 0, under the cloth). params NULL means pool_default_params().
POOL_API pool_ball_state pool_ball_on_cloth(int32_t id, double x, double y, const pool_params *params);

#ifdef __cplusplus
}
#endif

#endif
