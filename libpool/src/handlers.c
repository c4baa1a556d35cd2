// Which handler processes which event kind (handlers.h).
#include "handlers.h"

pool_event_handler pool_event_handler_for(pool_event_type type) {
	switch (type) {
	case POOL_EVENT_SLIDE_ROLL:
	case POOL_EVENT_ROLL_STOP:
	case POOL_EVENT_SPIN_STOP: return pool_handle_state_change;
	case POOL_EVENT_BALL_BALL: return pool_handle_ball_ball;
	case POOL_EVENT_BALL_CUSHION: return pool_handle_ball_cushion;
	case POOL_EVENT_POCKET: return pool_handle_pocket;
	case POOL_EVENT_BALL_TABLE: return pool_handle_ball_table;
	case POOL_EVENT_OFF_TABLE: return pool_handle_off_table;
	default: return NULL;
	}
}
