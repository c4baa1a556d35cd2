// libpool: events of a shot (docs/interfaces.md, result file).
#ifndef POOL_EVENT_H
#define POOL_EVENT_H

#include "pool/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Kind of event; values are stable. Equal-time events are ordered by this value, then ball ids.
typedef enum pool_event_type {
	POOL_EVENT_STRIKE = 0,       ///< cue strike ("strike")
	POOL_EVENT_SLIDE_ROLL = 1,   ///< sliding ball starts rolling ("slide_roll")
	POOL_EVENT_ROLL_STOP = 2,    ///< rolling ball stops translating ("roll_stop")
	POOL_EVENT_SPIN_STOP = 3,    ///< z-spin ends ("spin_stop")
	POOL_EVENT_BALL_BALL = 4,    ///< two balls collide ("ball_ball")
	POOL_EVENT_BALL_CUSHION = 5, ///< a ball hits a cushion nose ("ball_cushion")
	POOL_EVENT_BALL_TABLE = 6,   ///< a ball lands on / is pressed into the cloth ("ball_table")
	POOL_EVENT_POCKET = 7,       ///< a ball falls into a pocket ("pocket")
	POOL_EVENT_OFF_TABLE = 8,    ///< a ball leaves the table ("off_table")
	POOL_EVENT_LINK_BEGIN = 9,   ///< a persistent-contact cluster forms ("link_begin")
	POOL_EVENT_LINK_STEP = 10,   ///< one LCP step of a cluster ("link_step")
	POOL_EVENT_LINK_END = 11,    ///< a cluster dissolves ("link_end")
} pool_event_type;

/// Name as in docs/interfaces.md ("ball_ball", ...).
POOL_API const char *pool_event_type_name(pool_event_type type);

/// Rails (cushion noses). South is y = 0, north y = W, west x = 0, east x = L.
typedef enum pool_rail {
	POOL_RAIL_NONE = -1,
	POOL_RAIL_SOUTH = 0,
	POOL_RAIL_NORTH = 1,
	POOL_RAIL_WEST = 2,
	POOL_RAIL_EAST = 3,
} pool_rail;

/// "south", "north", "west", "east" (NULL for POOL_RAIL_NONE).
POOL_API const char *pool_rail_name(pool_rail rail);

/// Pockets: four corners and the two side pockets at x = L/2.
typedef enum pool_pocket {
	POOL_POCKET_NONE = -1,
	POOL_POCKET_SW = 0,
	POOL_POCKET_SE = 1,
	POOL_POCKET_NW = 2,
	POOL_POCKET_NE = 3,
	POOL_POCKET_S = 4,
	POOL_POCKET_N = 5,
} pool_pocket;

/// "sw", "se", "nw", "ne", "s", "n" (NULL for POOL_POCKET_NONE).
POOL_API const char *pool_pocket_name(pool_pocket pocket);

/// Part of a cushion's nose curve a ball touched (docs/physics.md "Table geometry"); values are
/// stable.
typedef enum pool_cushion_part {
	POOL_PART_NONE = -1, ///< not a cushion event, or the thesis model (pockets "mouth_lines")
	POOL_PART_NOSE = 0,  ///< a nose segment along its rail ("nose")
	POOL_PART_FACING = 1, ///< a pocket's facing ("facing")
	POOL_PART_JAW = 2,   ///< a pocket's rounded jaw ("jaw")
} pool_cushion_part;

/// "nose", "facing", "jaw" (NULL for POOL_PART_NONE).
POOL_API const char *pool_cushion_part_name(pool_cushion_part part);

/// One processed event. The states of the balls it involved, just after it, are
/// pool_sim_event_states(sim, event)[0 .. ball_count-1] (they carry the ball ids).
typedef struct pool_event {
	double time;          ///< s, absolute time since the start of the shot
	pool_event_type type; ///< what happened
	pool_rail rail;       ///< for POOL_EVENT_BALL_CUSHION, else POOL_RAIL_NONE
	pool_pocket pocket;   ///< for POOL_EVENT_POCKET; for a cushion event, the pocket of the facing or jaw hit
	int ball_count;       ///< balls involved (1 or 2; more for link events)
	int first_state;      ///< index of the first involved ball's state in the event-state array
	pool_cushion_part part; ///< for POOL_EVENT_BALL_CUSHION with pockets "jaws" or "none", else POOL_PART_NONE
} pool_event;

#ifdef __cplusplus
}
#endif

#endif
