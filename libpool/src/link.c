// LINK clusters in the world (link.h): the trigger, forming and merging clusters, their steps
// and their lengths, balls leaving them, and their dissolution.
#include "link.h"

#include <math.h>
#include <string.h>

#include "contact.h"
#include "geometry.h"
#include "handlers.h"
#include "motion.h"
#include "schedule.h"
#include "vec3.h"

int pool_link_note_collision(pool_sim *sim, int i, int partner, double t) {
	pool_contact_streak *streak = sim->body[i].streak;
	int slot = -1, oldest = 0;
	for (int k = 0; k < POOL_LINK_PARTNERS; ++k) {
		if (streak[k].partner == partner)
			slot = k;
		// The slot to reuse: an unused one, else the one whose streak began first.
		if (streak[oldest].partner == -1)
			continue;
		if (streak[k].partner == -1 || streak[k].t0 < streak[oldest].t0)
			oldest = k;
	}
	pool_contact_streak *k = NULL;
	if (slot >= 0 && t - streak[slot].t0 <= POOL_LINK_TRIGGER_WINDOW) {
		k = &streak[slot];
		if (t == k->t_last) {
			k->same++;
		} else {
			k->count++;
			k->same = 1;
		}
	} else {
		k = &streak[slot < 0 ? oldest : slot];
		k->partner = partner;
		k->count = k->same = 1;
		k->t0 = t;
	}
	k->t_last = t;
	return k->count >= POOL_LINK_TRIGGER_COLLISIONS || k->same >= POOL_LINK_TRIGGER_SAME_INSTANT;
}

// The cluster's balls, ascending by index (so every step reads them in the same order).
static int members(const pool_sim *sim, int c, int *out) {
	int m = 0;
	for (int i = 0; i < sim->n; ++i)
		if (sim->body[i].cluster == c)
			out[m++] = i;
	return m;
}

// Adds a step's tail (link_step.h: v, then w) to s's velocities.
static void add_tail(pool_ball_state *s, const double *tail) {
	s->vel = pool_v3_add(s->vel, pool_v3(tail[0], tail[1], tail[2]));
	s->omega = pool_v3_add(s->omega, pool_v3(tail[3], tail[4], tail[5]));
}

// Ball b keeps its linked segment's mean velocities (the tail is dropped, or not yet known).
static void drop_tail(pool_body *b) {
	for (int e = 0; e < 6; ++e)
		b->tail[e] = 0.0;
}

// Linked ball i's state at t, the end of its step: the segment's mean velocity plus the step's
// tail (zero after an interruption).
static void step_end_state(const pool_sim *sim, int i, double t, pool_ball_state *s) {
	pool_world_state_now(sim, i, t, s);
	add_tail(s, sim->body[i].tail);
}

// Ball i joins cluster c at t: it (or the whole cluster it is in) starts linked segments there.
static void join(pool_sim *sim, int i, int c, double t) {
	pool_body *b = &sim->body[i];
	if (b->cluster == c)
		return;
	if (b->cluster >= 0) {
		const int other = b->cluster;
		sim->clusters[other].active = 0;
		for (int k = 0; k < sim->n; ++k)
			if (sim->body[k].cluster == other)
				sim->body[k].cluster = -1, join(sim, k, c, t);
		return;
	}
	pool_ball_state s;
	pool_world_state_now(sim, i, t, &s);
	s.motion = POOL_MOTION_LINKED;
	b->cluster = c;
	b->loose = 0;
	drop_tail(b);
	pool_schedule_begin_segment(sim, i, &s, t);
}

void pool_link_adopt(pool_sim *sim, int i, int c, double t) { join(sim, i, c, t); }

// pool_link_pressed_pair with the two balls' accelerations given.
static int pressed_with(const pool_ball_state *s, pool_vec3 a0, pool_vec3 a1) {
	const pool_vec3 d = pool_v3_sub(s[0].pos, s[1].pos);
	const double dist = pool_v3_len(d);
	const pool_vec3 n = pool_v3_scale(d, 1.0 / dist);
	const pool_vec3 dv = pool_v3_sub(s[0].vel, s[1].vel);
	const pool_vec3 da = pool_v3_sub(a0, a1);
	const double vn = pool_v3_dot(n, dv);
	const double approach_accel = -pool_v3_dot(n, da) - (pool_v3_dot(dv, dv) - vn * vn) / dist;
	return approach_accel > 0.0;
}

int pool_link_pressed_pair(const pool_sim *sim, const pool_ball_state *s) {
	const pool_params *p = &sim->def.params;
	return pressed_with(s, pool_motion_accel(p, &s[0]), pool_motion_accel(p, &s[1]));
}

// Every ball in play touching one of cluster c's balls at t and closing on it (faster than
// POOL_LINK_REST_SPEED, up to POOL_LINK_IMPACT_SPEED: faster is a hit, an event) joins it,
// transitively. A ball that touches without closing stays out:
// the balls of a frozen rack touch one another, and a step that linked them all would solve
// the whole rack's contacts; should the cluster press it later, the collision prediction
// (which sees linked balls) finds the contact and the trigger links it then.
static void absorb(pool_sim *sim, int c, double t) {
	const double reach = 2.0 * sim->def.params.ball_radius + POOL_LINK_TOUCH_GAP;
	for (int changed = 1; changed;) {
		changed = 0;
		for (int k = 0; k < sim->n; ++k) {
			const pool_body *bk = &sim->body[k];
			if (!bk->active || bk->cluster == c)
				continue;
			pool_vec3 pk, vk;
			pool_segment_path(&bk->seg, t - bk->seg.t0, &pk, &vk);
			for (int i = 0; i < sim->n; ++i) {
				const pool_body *bi = &sim->body[i];
				if (bi->cluster != c)
					continue;
				pool_vec3 pi, vi;
				pool_segment_path(&bi->seg, t - bi->seg.t0, &pi, &vi);
				const pool_vec3 d = pool_v3_sub(pk, pi);
				const double dist = pool_v3_len(d);
				if (!(dist <= reach) || !(dist > 0.0))
					continue;
				const double closing = pool_closing_speed(pk, vk, pi, vi);
				if (closing > POOL_LINK_REST_SPEED && closing <= POOL_LINK_IMPACT_SPEED) {
					join(sim, k, c, t);
					changed = 1;
					break;
				}
			}
		}
	}
}

// Every member's next event becomes the cluster's step at t_next.
static void reschedule(pool_sim *sim, int c, double now) {
	int *idx = sim->link_members;
	const int m = members(sim, c, idx);
	for (int k = 0; k < m; ++k) {
		const int i = idx[k];
		pool_ball_state s = sim->cur[i];
		pool_schedule_begin_segment(sim, i, &s, sim->body[i].seg.t0);
	}
	pool_schedule_after_event(sim, idx, m, now);
}

// Something from outside changed cluster c: what its last step decided about who leaves no
// longer holds, and the next step decides afresh.
// The current step is cut short, so its forces were applied for longer than the time that
// passed: the next step is POOL_LINK_STEP_TIME again, and the velocities stay the step's mean
// (its tail, half a step of cloth resistance, is dropped: at most 1/2 mu_roll g
// POOL_LINK_STEP_MAX, 0.8 mm/s).
static void unsettle(pool_sim *sim, int c) {
	sim->clusters[c].quiet = 0;
	sim->clusters[c].dt = POOL_LINK_STEP_TIME;
	for (int k = 0; k < sim->n; ++k)
		if (sim->body[k].cluster == c) {
			sim->body[k].loose = 0;
			drop_tail(&sim->body[k]);
		}
}

pool_result pool_link_begin(pool_sim *sim, const int *seed, int m, double t) {
	int c = -1;
	for (int k = 0; k < m; ++k) {
		const int in = sim->body[seed[k]].cluster;
		if (in >= 0 && (c < 0 || in < c))
			c = in;
	}
	if (c < 0) {
		for (c = 0; c < sim->n && sim->clusters[c].active; ++c) {
		}
		sim->clusters[c].steps = 0;
		sim->link_stats.clusters++;
	}
	sim->clusters[c].active = 1;
	sim->clusters[c].t_next = t;
	unsettle(sim, c);
	for (int k = 0; k < m; ++k)
		join(sim, seed[k], c, t);
	absorb(sim, c, t);
	int *idx = sim->link_members;
	const int count = members(sim, c, idx);
	// Balls already linked restart their segments here, so link_begin records every ball's state
	// at t (the history evolves each recorded state from its event's time).
	for (int k = 0; k < count; ++k)
		if (sim->body[idx[k]].seg.t0 < t) {
			pool_ball_state s;
			pool_world_state_now(sim, idx[k], t, &s);
			pool_schedule_begin_segment(sim, idx[k], &s, t);
		}
	pool_world_record_event(sim, t, POOL_EVENT_LINK_BEGIN, POOL_RAIL_NONE, POOL_POCKET_NONE, idx, count);
	reschedule(sim, c, t);
	return POOL_OK;
}

// Every ball of the cluster still (a heap resting on itself: nothing to step until hit).
static int all_still(const pool_sim *sim, const pool_ball_state *s, int m) {
	const double R = sim->def.params.ball_radius;
	for (int k = 0; k < m; ++k)
		if (pool_v3_len(s[k].vel) > POOL_LINK_REST_SPEED || pool_v3_len(s[k].omega) * R > POOL_LINK_REST_SPEED)
			return 0;
	return 1;
}

// Groups (in group[0..m)) the balls of s[0..m) that touch and whose velocities, and with
// `spin_too` their spins' surface speeds, agree to within POOL_APPROACH_EPS.
static void group_common(const pool_sim *sim, const pool_ball_state *s, int m, int spin_too, int *group) {
	const double R = sim->def.params.ball_radius, reach = 2.0 * R + POOL_LINK_TOUCH_GAP;
	for (int k = 0; k < m; ++k)
		group[k] = k;
	for (int a = 0; a < m; ++a)
		for (int b = a + 1; b < m; ++b) {
			const double dv = pool_v3_len(pool_v3_sub(s[a].vel, s[b].vel));
			const double dw = spin_too ? pool_v3_len(pool_v3_sub(s[a].omega, s[b].omega)) * R : 0.0;
			if (pool_v3_len(pool_v3_sub(s[a].pos, s[b].pos)) > reach || dv > POOL_APPROACH_EPS || dw > POOL_APPROACH_EPS)
				continue;
			const int ga = group[a], gb = group[b];
			for (int k = 0; k < m; ++k)
				if (group[k] == gb)
					group[k] = ga;
		}
}

// Balls of s[0..m) that touch and move together to within POOL_APPROACH_EPS get their group's
// mean velocity, exactly the same doubles, and those whose spins agree too the group's mean
// spin: two balls rolling (or sliding) together in contact then decelerate identically in
// closed form and never meet again, where the rounding of the LCP's solution (1e-14 m/s)
// would make them "collide" by nothing at every event. The means keep momentum and never add
// energy.
static void merge_common_motion(const pool_sim *sim, pool_ball_state *s, int m, int *group) {
	for (int pass = 0; pass < 2; ++pass) {
		group_common(sim, s, m, pass, group);
		for (int g = 0; g < m; ++g) {
			pool_vec3 mean = {0.0, 0.0, 0.0};
			int count = 0;
			for (int k = 0; k < m; ++k)
				if (group[k] == g) {
					mean = pool_v3_add(mean, pass ? s[k].omega : s[k].vel);
					count++;
				}
			if (count < 2)
				continue;
			mean = pool_v3_scale(mean, 1.0 / count);
			for (int k = 0; k < m; ++k)
				if (group[k] == g)
					*(pass ? &s[k].omega : &s[k].vel) = mean;
		}
	}
}

/// m/s: a ball leaving a cluster on the cloth slower than this (velocity, and spin's surface
/// speed) leaves at rest. The LCP's rounding leaves touching balls drifting at up to ~1e-10 m/s,
/// which the closed forms would take for balls rolling into their neighbours, "colliding" again
/// and again at one instant; stopping a ball 100 times faster than that moves it from the path
/// the step gave it by 1e-11 m per millisecond, far inside POOL_TOUCH_TOLERANCE. (Inside a step
/// the velocities stay exactly the LCP's, whose contacts they keep apart.)
#define POOL_LINK_SETTLE_SPEED 1e-8

/// Relative residual above which a step longer than POOL_LINK_STEP_TIME is taken again at
/// that length. A solve's velocities are off by at most its residual times 1 + the cluster's
/// speeds (link_step.h), and the positions by that times dt: the steps' own limit,
/// POOL_LINK_RESIDUAL_MAX, over 16 ms would let balls into each other by 1.6e-8 m; 1e-9 keeps
/// a long step's error below 1e-10 m, a tenth of POOL_TOUCH_TOLERANCE. (Lemke's residuals are
/// 1e-16 to 1e-12 on most solves.)
#define POOL_LINK_LONG_STEP_RESIDUAL 1e-9

static void settle(const pool_sim *sim, pool_ball_state *s) {
	const double R = sim->def.params.ball_radius;
	const pool_vec3 w_perp = pool_v3(s->omega.x, s->omega.y, 0.0);
	if (s->pos.z > R + POOL_TOUCH_TOLERANCE || pool_v3_len(s->vel) > POOL_LINK_SETTLE_SPEED ||
	    pool_v3_len(w_perp) * R > POOL_LINK_SETTLE_SPEED)
		return;
	s->vel = pool_v3(0.0, 0.0, 0.0);
	s->omega.x = s->omega.y = 0.0;
	if (fabs(s->omega.z) * R <= POOL_LINK_SETTLE_SPEED)
		s->omega.z = 0.0;
}

// Turns the end-of-step states s[0..m) of balls leaving a cluster together into the closed-form
// states they resume: balls moving together share their motion, a crawling ball on the cloth
// settles, and the on-cloth state of the velocities is derived (airborne above the cloth).
static void leaving_states(pool_sim *sim, pool_ball_state *s, int m) {
	merge_common_motion(sim, s, m, sim->work);
	for (int k = 0; k < m; ++k) {
		settle(sim, &s[k]);
		s[k].motion = POOL_MOTION_SLIDING;
		pool_motion_after_impulse(&sim->def, &s[k]);
	}
}

// Balls idx[0..m) of a cluster leave it at t and resume their closed-form states, with the
// velocities of the last step (its motion up to t): airborne above the cloth, else the on-cloth
// state of the velocities (pool_motion_after_impulse derives it); link_end records them.
static void release(pool_sim *sim, const int *idx, int m, double t) {
	pool_ball_state *s = sim->link_states;
	for (int k = 0; k < m; ++k)
		step_end_state(sim, idx[k], t, &s[k]);
	leaving_states(sim, s, m);
	for (int k = 0; k < m; ++k) {
		sim->body[idx[k]].cluster = -1;
		sim->body[idx[k]].loose = 0;
		pool_schedule_begin_segment(sim, idx[k], &s[k], t);
	}
	pool_world_record_event(sim, t, POOL_EVENT_LINK_END, POOL_RAIL_NONE, POOL_POCKET_NONE, idx, m);
	pool_schedule_after_event(sim, idx, m, t);
}

// Members past a rail's contact line inside a pocket mouth at t (the step's LCP has no rail
// there; the crossing's own pocket event is predicted, this catches a ball that was already
// past the line when its segment began) fall into that pocket now.
static pool_result pocket_strays(pool_sim *sim, int c, double t) {
	const pool_table_def *table = &sim->def.table;
	for (int k = 0; k < sim->n; ++k) {
		if (sim->body[k].cluster != c)
			continue;
		pool_ball_state s;
		pool_world_state_now(sim, k, t, &s);
		// Pockets "jaws": over a hole; the thesis model: past a contact line inside a mouth.
		const pool_pocket hole = pool_shape_hole_at(&sim->shape, s.pos.x, s.pos.y);
		for (int rail = POOL_RAIL_SOUTH; rail <= POOL_RAIL_EAST; ++rail) {
			const int along_x = pool_rail_along_x((pool_rail)rail);
			const double across = along_x ? s.pos.y : s.pos.x, along = along_x ? s.pos.x : s.pos.y;
			const double line = pool_rail_contact_line(table, sim->dc, (pool_rail)rail);
			const pool_pocket pocket = table->pockets == POOL_POCKETS_JAWS ? hole : pool_pocket_at(table, (pool_rail)rail, along);
			if (table->pockets != POOL_POCKETS_JAWS && !(pool_rail_side((pool_rail)rail) * (across - line) > 0.0))
				continue;
			if (pocket == POOL_POCKET_NONE)
				continue;
			if (pool_world_reserve_history(sim, 1, 1))
				return POOL_ERR_OUT_OF_MEMORY;
			pool_take_out_of_play(&s, POOL_MOTION_POCKETED);
			sim->body[k].cluster = -1;
			sim->body[k].active = 0;
			pool_schedule_begin_segment(sim, k, &s, t);
			pool_world_record_event(sim, t, POOL_EVENT_POCKET, POOL_RAIL_NONE, pocket, &k, 1);
			pool_schedule_after_event(sim, &k, 1, t);
			break;
		}
	}
	return POOL_OK;
}

// Loose balls (states s[0..m) after the step, the cluster's idx[0..m)) that the closed forms
// would press together again at once stay linked: leaving, they would collide at once with
// nothing to part them and the trigger would link them again, one cluster per step where one
// cluster holds them.
static void hold_pressed(pool_sim *sim, const int *idx, const pool_ball_state *s, int m, double dt) {
	pool_ball_state *free_state = sim->link_leaving;
	for (int k = 0; k < m; ++k) {
		free_state[k] = s[k];
		add_tail(&free_state[k], sim->link_ws.ball_tail + 6 * k);
		// link_accel held the velocity at the step's start (pool_link_step_event)
		sim->link_accel[k] = pool_v3_scale(pool_v3_sub(free_state[k].vel, sim->link_accel[k]), 1.0 / dt);
	}
	leaving_states(sim, free_state, m); // as release() would make them
	// A loose ball touching one that stays is held too when that one closes on it or presses
	// it (the staying ball moving uniformly, as linked balls do): it would be hit at once.
	const double reach = 2.0 * sim->def.params.ball_radius + POOL_LINK_TOUCH_GAP;
	for (int changed = 1; changed;) {
		changed = 0;
		for (int a = 0; a < m; ++a)
			for (int b = a + 1; b < m; ++b) {
				pool_body *ba = &sim->body[idx[a]], *bb = &sim->body[idx[b]];
				if ((!ba->loose && !bb->loose) || !(pool_v3_len(pool_v3_sub(s[a].pos, s[b].pos)) <= reach))
					continue;
				// A staying ball goes on as its last step did (its acceleration over it).
				const pool_ball_state pair[2] = {free_state[a], free_state[b]};
				const pool_vec3 aa = ba->loose ? pool_motion_accel(&sim->def.params, &pair[0]) : sim->link_accel[a];
				const pool_vec3 ab = bb->loose ? pool_motion_accel(&sim->def.params, &pair[1]) : sim->link_accel[b];
				const double closing = pool_closing_speed(pair[0].pos, pair[0].vel, pair[1].pos, pair[1].vel);
				if (closing > POOL_APPROACH_EPS || pressed_with(pair, aa, ab)) {
					changed |= ba->loose | bb->loose;
					ba->loose = bb->loose = 0;
				}
			}
	}
}

// The length of the step after one of length dt whose contacts accelerated a ball by at most
// accel (POOL_LINK_STEP_MAX says why).
static double next_step_length(double dt, double accel) {
	const double bound = accel > 0.0 ? sqrt(2.0 * POOL_LINK_STEP_ERROR / accel) : INFINITY;
	return fmax(POOL_LINK_STEP_TIME, fmin(fmin(2.0 * dt, POOL_LINK_STEP_MAX), bound));
}

pool_result pool_link_step_event(pool_sim *sim, int i, double t) {
	const int c = sim->body[i].cluster;
	pool_cluster *cl = &sim->clusters[c];
	absorb(sim, c, t);
	const pool_result rp = pocket_strays(sim, c, t);
	if (rp)
		return rp;
	int *idx = sim->link_members;
	pool_ball_state *s = sim->link_states;
	int m = members(sim, c, idx);
	if (m == 0) {
		cl->active = 0;
		return POOL_OK;
	}
	// Leaving is decided by the last step, so every cluster takes at least one step (a Zeno
	// pair is merged by it) and a leaving ball keeps the motion it had.
	if (cl->quiet) {
		cl->active = 0;
		release(sim, idx, m, t);
		return POOL_OK;
	}
	// The loose balls first (members keep ascending order within each part), then they leave:
	// one link_end with them (pool_sim_step reserved the history for it and the step).
	int loose = 0;
	for (int k = 0; k < m; ++k)
		if (sim->body[idx[k]].loose) {
			const int ball = idx[k];
			for (int j = k; j > loose; --j)
				idx[j] = idx[j - 1];
			idx[loose++] = ball;
		}
	if (loose > 0) {
		release(sim, idx, loose, t);
		m = members(sim, c, idx);
		if (m == 0) {
			cl->active = 0;
			return POOL_OK;
		}
	}
	for (int k = 0; k < m; ++k)
		step_end_state(sim, idx[k], t, &s[k]);
	for (int k = 0; k < m; ++k)
		sim->link_accel[k] = s[k].vel;
	pool_link_step_stats st;
	pool_result r = pool_link_step(&sim->def, s, m, cl->dt, &sim->link_ws, &sim->alloc, &st);
	if (r == POOL_OK && cl->dt > POOL_LINK_STEP_TIME && st.residual > POOL_LINK_LONG_STEP_RESIDUAL) {
		// A long step moves the balls by its velocity error times dt: one the solve left less
		// accurate is taken again at POOL_LINK_STEP_TIME.
		sim->link_stats.pivots += st.pivots;
		cl->dt = POOL_LINK_STEP_TIME;
		for (int k = 0; k < m; ++k)
			step_end_state(sim, idx[k], t, &s[k]);
		r = pool_link_step(&sim->def, s, m, cl->dt, &sim->link_ws, &sim->alloc, &st);
	}
	if (r)
		return r;
	pool_link_stats *total = &sim->link_stats;
	total->steps++;
	total->pivots += st.pivots;
	total->warm_solves += st.warm;
	total->max_balls = m > total->max_balls ? m : total->max_balls;
	total->max_contacts = st.contacts > total->max_contacts ? st.contacts : total->max_contacts;
	total->max_residual = fmax(total->max_residual, st.residual);
	cl->steps++;
	const int still = all_still(sim, s, m);
	const double this_dt = cl->dt;
	// A ball nothing presses leaves at the next step: on the cloth the closed forms take over
	// its contacts (two balls rolling together in contact stay so by themselves; if friction
	// presses them again, the trigger links them again), above it only once it touches
	// nothing. The cluster dissolves when every ball leaves; a heap at rest above the cloth
	// sleeps instead.
	for (int k = 0; k < m; ++k) {
		const int on_cloth = s[k].pos.z <= sim->def.params.ball_radius + POOL_TOUCH_TOLERANCE;
		// (the push of a step of dt: POOL_LINK_PUSH_MIN per POOL_LINK_STEP_TIME)
		const int unpressed = sim->link_ws.ball_push[k] <= POOL_LINK_PUSH_MIN * (this_dt / POOL_LINK_STEP_TIME);
		sim->body[idx[k]].loose = (on_cloth && (unpressed || still)) || (unpressed && sim->link_ws.ball_touching[k] == 0);
	}
	hold_pressed(sim, idx, s, m, cl->dt);
	int leaving = 0;
	for (int k = 0; k < m; ++k)
		leaving += sim->body[idx[k]].loose;
	cl->quiet = leaving == m;
	// A cluster whose balls are all still and all held sleeps until something hits it: its
	// balls are then at rest (slower than POOL_LINK_REST_SPEED, they would otherwise creep on
	// for ever without another step: a ball held to a rail at 1e-7 m/s, the soak's rail_drift).
	const int sleeps = still && leaving == 0;
	cl->t_next = sleeps ? INFINITY : t + this_dt;
	cl->dt = next_step_length(this_dt, st.max_contact_accel);
	for (int k = 0; k < m; ++k) {
		if (sleeps) {
			s[k].vel = s[k].omega = pool_v3(0.0, 0.0, 0.0);
			for (int e = 0; e < 6; ++e)
				sim->link_ws.ball_tail[6 * k + e] = 0.0;
		}
		memcpy(sim->body[idx[k]].tail, sim->link_ws.ball_tail + 6 * k, sizeof sim->body[idx[k]].tail);
		s[k].motion = POOL_MOTION_LINKED;
		// The LCP's rounding (down to 1e-36 m/s) is no motion: a linked ball drifting at it
		// would "collide" with every touching ball outside. Below POOL_REST_EPS, as in the
		// closed-form states' own clean-up, a velocity or spin is zero (1e-15 m per step).
		if (pool_v3_len(s[k].vel) <= POOL_REST_EPS)
			s[k].vel = pool_v3(0.0, 0.0, 0.0);
		if (pool_v3_len(s[k].omega) * sim->def.params.ball_radius <= POOL_REST_EPS)
			s[k].omega = pool_v3(0.0, 0.0, 0.0);
		if (pool_world_planar(sim)) {
			s[k].pos.z = sim->def.params.ball_radius;
			s[k].vel.z = 0.0;
		}
		pool_schedule_begin_segment(sim, idx[k], &s[k], t);
	}
	pool_world_record_event(sim, t, POOL_EVENT_LINK_STEP, POOL_RAIL_NONE, POOL_POCKET_NONE, idx, m);
	pool_schedule_after_event(sim, idx, m, t);
	return POOL_OK;
}

// A contact inside cluster c (two of its balls, or one and a rail's nose, touching) closing
// faster than POOL_LINK_IMPACT_SPEED at t: a hit from outside passed on into the cluster.
static int hit_inside(pool_sim *sim, int c, double t) {
	const pool_params *p = &sim->def.params;
	const pool_table_def *table = &sim->def.table;
	const double reach = 2.0 * p->ball_radius + POOL_LINK_TOUCH_GAP;
	int *idx = sim->link_members;
	pool_ball_state *s = sim->link_states;
	const int m = members(sim, c, idx);
	for (int k = 0; k < m; ++k)
		pool_world_state_now(sim, idx[k], t, &s[k]);
	for (int a = 0; a < m; ++a) {
		for (int b = a + 1; b < m; ++b) {
			const pool_vec3 d = pool_v3_sub(s[b].pos, s[a].pos);
			const double dist = pool_v3_len(d);
			if (dist <= reach && dist > 0.0 &&
			    pool_closing_speed(s[a].pos, s[a].vel, s[b].pos, s[b].vel) > POOL_LINK_IMPACT_SPEED)
				return 1;
		}
		for (int rail = POOL_RAIL_SOUTH; rail <= POOL_RAIL_EAST; ++rail) {
			const int along_x = pool_rail_along_x((pool_rail)rail);
			const double side = pool_rail_side((pool_rail)rail);
			const double line = pool_rail_contact_line(table, sim->dc, (pool_rail)rail);
			const double across = along_x ? s[a].pos.y : s[a].pos.x, speed = along_x ? s[a].vel.y : s[a].vel.x;
			if (side * (line - across) <= POOL_LINK_TOUCH_GAP && side * speed > POOL_LINK_IMPACT_SPEED)
				return 1;
		}
	}
	return 0;
}

void pool_link_touched(pool_sim *sim, int i, double t) {
	const int c = sim->body[i].cluster;
	sim->clusters[c].t_next = t;
	unsettle(sim, c);
	// A hit passed on into the cluster (a ball hit into its neighbour or into the rail faster
	// than the cluster's own forces close a contact): the cluster dissolves and the impulses of
	// events pass it on, with restitution, where the inelastic step would absorb the bounce; if
	// the balls press one another again, the trigger links them again. (pool_sim_step reserved
	// the history for the link_end.)
	if (hit_inside(sim, c, t)) {
		int *idx = sim->link_members;
		const int m = members(sim, c, idx);
		sim->clusters[c].active = 0;
		release(sim, idx, m, t);
		return;
	}
	reschedule(sim, c, t);
}

void pool_link_left(pool_sim *sim, int i, double t) {
	const int c = sim->body[i].cluster;
	sim->body[i].cluster = -1;
	int any = 0;
	for (int k = 0; k < sim->n; ++k)
		any |= sim->body[k].cluster == c;
	if (!any) {
		sim->clusters[c].active = 0;
		return;
	}
	sim->clusters[c].t_next = t;
	unsettle(sim, c);
	reschedule(sim, c, t);
}

pool_result pool_sim_link_stats(const pool_sim *sim, pool_link_stats *out) {
	if (!sim || !out)
		return POOL_ERR_INVALID_ARGUMENT;
	*out = sim->link_stats;
	return POOL_OK;
}
