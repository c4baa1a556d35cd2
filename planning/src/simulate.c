// A candidate simulated: did it succeed, and by how much did the potted ball's path miss?
#include <math.h>

#include "aim_internal.h"

// After a pocket, the potted ball's path is extended this far along its last direction, so its
// closest approach to the pocket's aiming point (behind the mouth) is on the path.
#define AIM_EXTEND 0.3
// Points inside each sliding stretch of the potted ball's path (a parabola; rolling stretches are
// straight, their ends suffice).
#define AIM_SLIDE_POINTS 6
// The path's points: the approach ends at its next collision, pocket or stop, within this many of
// the ball's events.
#define AIM_PATH_EVENTS 16
#define AIM_PATH_POINTS ((AIM_PATH_EVENTS + 2) * (AIM_SLIDE_POINTS + 1) + 3)

pool_result aim_simulate(aim_search *s, aim_worker *w, const aim_candidate *c, const pool_strike *strike) {
	(void)c;
	const pool_aim_def *d = s->def;
	pool_error err;
	pool_result r = w->sim ? pool_sim_reset(w->sim, &d->sim, &err) : pool_sim_create(&d->sim, &w->sim, &err);
	for (int k = 0; r == POOL_OK && k < d->ball_count; ++k)
		r = pool_sim_add_ball(w->sim, &d->balls[k], &err);
	if (r == POOL_OK)
		r = pool_sim_strike(w->sim, d->balls[s->cue].id, strike, &err);
	if (r == POOL_OK)
		r = pool_sim_run(w->sim);
	w->simulations++;
	return r;
}

static bool involves(const pool_sim *sim, const pool_event *e, int32_t id) {
	const pool_ball_state *after = pool_sim_event_states(sim, e);
	for (int k = 0; k < e->ball_count; ++k)
		if (after[k].id == id)
			return true;
	return false;
}

/// The other ball of a two-ball event involving id.
static int32_t other_ball(const pool_sim *sim, const pool_event *e, int32_t id) {
	const pool_ball_state *after = pool_sim_event_states(sim, e);
	for (int k = 0; k < e->ball_count; ++k)
		if (after[k].id != id)
			return after[k].id;
	return POOL_AIM_NO_BALL;
}

bool aim_success(const aim_search *s, const aim_worker *w, const aim_candidate *c) {
	const pool_aim_def *d = s->def;
	const int32_t id = d->balls[c->ball].id;
	if (d->game) {
		pool_game_state state = *d->game;
		if (state.rules == POOL_GAME_8BALL) { // the shot is called: this ball, this pocket (WPA 3.6)
			state.called_ball = id;
			state.called_pocket = c->pocket;
		}
		pool_game_shot shot = pool_game_shot_of_sim(w->sim);
		pool_game_result r;
		if (pool_game_judge(&state, &shot, &d->sim.table, &r, NULL) != POOL_OK || !r.legal)
			return false;
		if (r.outcome != POOL_OUTCOME_CONTINUE && r.outcome != POOL_OUTCOME_WIN)
			return false;
		for (int k = 0; k < r.pocketed_count; ++k)
			if (r.pocketed[k] == id && r.pocketed_in[k] == c->pocket)
				return true;
		return false;
	}
	int count = 0;
	const pool_event *events = pool_sim_events(w->sim, &count);
	bool potted = false;
	for (int e = 0; e < count && !potted; ++e)
		potted = events[e].type == POOL_EVENT_POCKET && events[e].pocket == c->pocket && involves(w->sim, &events[e], id);
	const pool_motion cue = pool_sim_balls(w->sim)[s->cue].motion;
	return potted && cue != POOL_MOTION_POCKETED && cue != POOL_MOTION_OFF_TABLE;
}

static bool is_collision(pool_event_type t) { return t == POOL_EVENT_BALL_BALL || t == POOL_EVENT_BALL_CUSHION; }

/// Whether the collision that starts the potted ball's approach is the one c means.
static bool approach_as_meant(const aim_search *s, const pool_sim *sim, const aim_candidate *c, const pool_event *e,
                              int32_t id) {
	const pool_ball_state *balls = s->def->balls;
	switch (c->kind) {
	case POOL_AIM_BANK: return e->type == POOL_EVENT_BALL_CUSHION && e->rail == c->rail;
	case POOL_AIM_CAROM:
	case POOL_AIM_COMBINATION:
		return e->type == POOL_EVENT_BALL_BALL && other_ball(sim, e, id) == balls[c->via].id;
	default: return e->type == POOL_EVENT_BALL_BALL && other_ball(sim, e, id) == balls[s->cue].id;
	}
}

bool aim_miss(const aim_search *s, const aim_worker *w, const aim_candidate *c, double *miss, bool *short_) {
	const pool_aim_def *d = s->def;
	const int32_t id = d->balls[c->ball].id, cue = d->balls[s->cue].id;
	const int32_t first = c->kind == POOL_AIM_COMBINATION ? d->balls[c->via].id : id;
	int count = 0;
	const pool_event *events = pool_sim_events(w->sim, &count);
	// The cue ball must meet the ball c means first.
	int32_t hit = POOL_AIM_NO_BALL;
	for (int e = 0; e < count && hit == POOL_AIM_NO_BALL; ++e)
		if ((events[e].type == POOL_EVENT_BALL_BALL || events[e].type == POOL_EVENT_LINK_BEGIN) &&
		    involves(w->sim, &events[e], cue))
			hit = other_ball(w->sim, &events[e], cue);
	if (hit != first)
		return false;
	// The potted ball's approaching collision.
	int start = -1;
	for (int e = 0, seen = 0; e < count && start < 0; ++e)
		if (is_collision(events[e].type) && involves(w->sim, &events[e], id) && ++seen == c->approach)
			start = approach_as_meant(s, w->sim, c, &events[e], id) ? e : count;
	if (start < 0 || start >= count)
		return false;
	// Its path from there: the ball's events, with points inside sliding stretches, until its next
	// collision, its pocket, or its stop.
	aim_xy path[AIM_PATH_POINTS];
	int n = 0, used = 0;
	bool ended_at_rest = false, pocketed = false;
	double t = events[start].time;
	pool_motion motion = POOL_MOTION_SLIDING;
	for (int e = start;; ) {
		if (pool_sim_state_at(w->sim, t, w->states) != POOL_OK)
			return false;
		path[n++] = (aim_xy){w->states[c->ball].pos.x, w->states[c->ball].pos.y};
		motion = w->states[c->ball].motion;
		int next = e + 1;
		while (next < count && !involves(w->sim, &events[next], id))
			++next;
		if (next >= count || ++used > AIM_PATH_EVENTS) {
			ended_at_rest = motion == POOL_MOTION_STATIONARY || motion == POOL_MOTION_SPINNING;
			if (!ended_at_rest && next >= count) { // still moving at the shot's end (max_time)
				double end = pool_sim_end_time(w->sim);
				if (end > t && pool_sim_state_at(w->sim, end, w->states) == POOL_OK)
					path[n++] = (aim_xy){w->states[c->ball].pos.x, w->states[c->ball].pos.y};
			}
			break;
		}
		double t_next = events[next].time;
		if (motion == POOL_MOTION_SLIDING)
			for (int k = 1; k <= AIM_SLIDE_POINTS; ++k) {
				if (pool_sim_state_at(w->sim, t + (t_next - t) * k / (AIM_SLIDE_POINTS + 1), w->states) != POOL_OK)
					return false;
				path[n++] = (aim_xy){w->states[c->ball].pos.x, w->states[c->ball].pos.y};
			}
		e = next;
		t = t_next;
		if (is_collision(events[e].type) || events[e].type == POOL_EVENT_POCKET || events[e].type == POOL_EVENT_OFF_TABLE) {
			if (pool_sim_state_at(w->sim, t, w->states) != POOL_OK)
				return false;
			path[n++] = (aim_xy){w->states[c->ball].pos.x, w->states[c->ball].pos.y};
			pocketed = events[e].type == POOL_EVENT_POCKET;
			break;
		}
	}
	if (pocketed && n >= 2) { // on along its last direction, past the pocket's aiming point
		aim_xy dir = aim_unit(aim_sub(path[n - 1], path[n - 2]));
		path[n] = aim_add_scaled(path[n - 1], dir, AIM_EXTEND);
		++n;
	}
	// The closest approach to the aiming point, signed by the side the point lies on.
	const aim_xy T = s->table.target[c->pocket];
	double best = INFINITY, sign = 1.0;
	bool at_end = false;
	for (int k = 0; k + 1 < n; ++k) {
		aim_xy seg = aim_sub(path[k + 1], path[k]), to = aim_sub(T, path[k]);
		double length2 = aim_dot(seg, seg);
		if (length2 <= 0.0)
			continue;
		double f = fmin(fmax(aim_dot(to, seg) / length2, 0.0), 1.0);
		double dist = aim_norm(aim_add_scaled(to, seg, -f));
		if (dist < best) {
			best = dist;
			sign = aim_cross(seg, to) >= 0.0 ? 1.0 : -1.0;
			at_end = k + 2 == n && f >= 1.0;
		}
	}
	if (!isfinite(best))
		return false;
	*miss = sign * best;
	*short_ = at_end && ended_at_rest;
	return true;
}
