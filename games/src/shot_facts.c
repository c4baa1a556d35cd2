// The facts the rules read from a shot's events (shot_facts.h), in one pass.
#include "shot_facts.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

// Two balls of a LINK cluster whose centres are at most 2R plus this apart touch: libpool gathers
// balls this close into one cluster (POOL_LINK_TOUCH_GAP, docs/library.md "LINK"), and a cluster's
// balls meet without ball_ball events.
#define POOL_GAME_TOUCH_GAP 1e-6

int pool_game_ball_index(const pool_game_shot *shot, int32_t id) {
	for (int i = 0; i < shot->ball_count; ++i)
		if (shot->balls[i].id == id)
			return i;
	return -1;
}

static double distance(pool_vec3 a, pool_vec3 b) {
	const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
	return sqrt(dx * dx + dy * dy + dz * dz);
}

// The balls an event brings into contact with the cue ball, nearest first (at most two: the
// rules need the first and the second ball it meets). A ball_ball event: the other ball. A LINK
// event (begin or step) that holds the cue ball: the balls touching it in the after-states.
static int contacts_of(const pool_event *ev, const pool_ball_state *after, int32_t cue, double radius,
                       int32_t out[2]) {
	int cue_at = -1;
	for (int k = 0; k < ev->ball_count; ++k)
		if (after[k].id == cue)
			cue_at = k;
	if (cue_at < 0)
		return 0;
	if (ev->type == POOL_EVENT_BALL_BALL) {
		out[0] = after[1 - cue_at].id;
		return 1;
	}
	if (ev->type != POOL_EVENT_LINK_BEGIN && ev->type != POOL_EVENT_LINK_STEP)
		return 0;
	int n = 0;
	double d_out[2] = {0.0, 0.0};
	for (int k = 0; k < ev->ball_count; ++k) {
		if (k == cue_at)
			continue;
		const double d = distance(after[k].pos, after[cue_at].pos);
		if (d > 2.0 * radius + POOL_GAME_TOUCH_GAP)
			continue;
		// Keep the two nearest, in order (ties: the event's order, which is by id).
		if (n < 2 || d < d_out[1]) {
			int at = n < 2 ? n++ : 1;
			while (at > 0 && d < d_out[at - 1]) {
				out[at] = out[at - 1];
				d_out[at] = d_out[at - 1];
				--at;
			}
			out[at] = after[k].id;
			d_out[at] = d;
		}
	}
	return n;
}

static void push_ball(int32_t *ids, pool_pocket *pockets, int *count, int32_t id, pool_pocket pocket) {
	if (*count >= POOL_GAME_MAX_BALLS)
		return; // cannot happen: a ball is pocketed or leaves the table once, and shots hold at most that many
	ids[*count] = id;
	if (pockets)
		pockets[*count] = pocket;
	++*count;
}

pool_result pool_game_read_facts(const pool_game_shot *shot, pool_game_facts *f, pool_error *error) {
	memset(f, 0, sizeof *f);
	f->first_hit_event = -1;
	f->first_hit = f->second_hit = POOL_GAME_NO_BALL;
	if (!shot->events || shot->event_count < 1 || shot->events[0].type != POOL_EVENT_STRIKE ||
	    shot->events[0].ball_count != 1 || !shot->event_states) {
		if (error)
			snprintf(error->message, sizeof error->message,
			         "events: a shot judged by the rules starts with a strike");
		return POOL_ERR_INVALID_ARGUMENT;
	}
	const pool_ball_state *struck = &shot->event_states[shot->events[0].first_state];
	f->struck = struck->id;
	f->struck_pos = struck->pos;
	// The struck ball stood on the cloth (libpool strikes only a ball at rest there): z = R.
	const double radius = struck->pos.z;
	int cue_cushions = 0;
	for (int i = 1; i < shot->event_count; ++i) {
		const pool_event *ev = &shot->events[i];
		const pool_ball_state *after = &shot->event_states[ev->first_state];
		switch (ev->type) {
		case POOL_EVENT_BALL_CUSHION: {
			const int at = pool_game_ball_index(shot, after[0].id);
			if (at >= 0)
				f->railed |= 1u << at;
			if (f->first_hit_event >= 0)
				f->rails_after_contact++;
			if (after[0].id == f->struck && f->second_hit == POOL_GAME_NO_BALL)
				cue_cushions++;
			break;
		}
		case POOL_EVENT_POCKET:
			push_ball(f->pocketed, f->pocketed_in, &f->pocketed_count, after[0].id, ev->pocket);
			break;
		case POOL_EVENT_OFF_TABLE:
			push_ball(f->off_table, NULL, &f->off_table_count, after[0].id, POOL_POCKET_NONE);
			break;
		default: {
			int32_t met[2];
			const int n = contacts_of(ev, after, f->struck, radius, met);
			for (int k = 0; k < n; ++k) {
				if (f->first_hit == POOL_GAME_NO_BALL) {
					f->first_hit = met[k];
					f->first_hit_event = i;
				} else if (f->second_hit == POOL_GAME_NO_BALL && met[k] != f->first_hit) {
					f->second_hit = met[k];
				}
			}
			break;
		}
		}
	}
	f->cue_cushions_before_second = cue_cushions;
	return POOL_OK;
}

bool pool_game_facts_pocketed(const pool_game_facts *f, int32_t id) {
	for (int i = 0; i < f->pocketed_count; ++i)
		if (f->pocketed[i] == id)
			return true;
	return false;
}

bool pool_game_facts_off_table(const pool_game_facts *f, int32_t id) {
	for (int i = 0; i < f->off_table_count; ++i)
		if (f->off_table[i] == id)
			return true;
	return false;
}

void pool_game_report_facts(const pool_game_facts *f, pool_game_result *r) {
	r->first_hit = f->first_hit;
	r->rails_after_contact = f->rails_after_contact;
	r->cue_cushions = f->cue_cushions_before_second;
	r->pocketed_count = f->pocketed_count;
	memcpy(r->pocketed, f->pocketed, sizeof r->pocketed);
	memcpy(r->pocketed_in, f->pocketed_in, sizeof r->pocketed_in);
	r->off_table_count = f->off_table_count;
	memcpy(r->off_table, f->off_table, sizeof r->off_table);
}
