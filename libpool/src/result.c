// Result codes and the names of enumerations that travel in files and messages.
#include "pool/base.h"
#include "pool/ball.h"
#include "pool/event.h"
#include "pool/sim.h"

#include <string.h>

const char *pool_result_str(pool_result result) {
	switch (result) {
	case POOL_OK: return "success";
	case POOL_ERR_INVALID_ARGUMENT: return "invalid argument";
	case POOL_ERR_NON_FINITE: return "non-finite number";
	case POOL_ERR_OUT_OF_MEMORY: return "out of memory";
	case POOL_ERR_OVERLAP: return "balls overlap";
	case POOL_ERR_OFF_TABLE: return "ball off the table";
	case POOL_ERR_DUPLICATE_ID: return "duplicate ball id";
	case POOL_ERR_UNKNOWN_BALL: return "unknown ball id";
	case POOL_ERR_BAD_STRIKE: return "impossible cue strike";
	case POOL_ERR_UNKNOWN_PRESET: return "unknown preset (table or model set)";
	case POOL_ERR_STATE: return "not allowed in the current state";
	case POOL_ERR_INTERNAL: return "internal error";
	}
	return "unknown result code";
}

static const char *const motion_names[] = {
	"stationary", "spinning", "sliding", "rolling", "airborne", "linked", "pocketed", "off_table",
};

const char *pool_motion_name(pool_motion motion) {
	if ((int)motion < 0 || (size_t)motion >= sizeof motion_names / sizeof motion_names[0])
		return "unknown";
	return motion_names[motion];
}

int pool_motion_from_name(const char *name) {
	for (size_t i = 0; name && i < sizeof motion_names / sizeof motion_names[0]; ++i)
		if (strcmp(name, motion_names[i]) == 0)
			return (int)i;
	return -1;
}

static const char *const event_names[] = {
	"strike", "slide_roll", "roll_stop", "spin_stop", "ball_ball", "ball_cushion",
	"ball_table", "pocket", "off_table", "link_begin", "link_step", "link_end",
};

const char *pool_event_type_name(pool_event_type type) {
	if ((int)type < 0 || (size_t)type >= sizeof event_names / sizeof event_names[0])
		return "unknown";
	return event_names[type];
}

const char *pool_rail_name(pool_rail rail) {
	static const char *const names[] = {"south", "north", "west", "east"};
	return (int)rail >= 0 && (int)rail < 4 ? names[rail] : NULL;
}

const char *pool_pocket_name(pool_pocket pocket) {
	static const char *const names[] = {"sw", "se", "nw", "ne", "s", "n"};
	return (int)pocket >= 0 && (int)pocket < 6 ? names[pocket] : NULL;
}

const char *pool_cushion_part_name(pool_cushion_part part) {
	static const char *const names[] = {"nose", "facing", "jaw"};
	return (int)part >= 0 && (int)part < 3 ? names[part] : NULL;
}

const char *pool_stop_reason_name(pool_stop_reason reason) {
	switch (reason) {
	case POOL_STOP_NONE: return "none";
	case POOL_STOP_REST: return "rest";
	case POOL_STOP_MAX_TIME: return "max_time";
	case POOL_STOP_MAX_EVENTS: return "max_events";
	}
	return "unknown";
}
