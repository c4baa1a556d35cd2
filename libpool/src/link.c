// LINK clusters in the world (link.h): the trigger, forming and merging clusters, their steps,
// and their dissolution.
#include "link.h"

#include <math.h>

#include "contact.h"
#include "geometry.h"
#include "handlers.h"
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
	pool_schedule_begin_segment(sim, i, &s, t);
}

// Every ball in play touching one of cluster c's balls at t joins it, transitively.
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
				if (pool_v3_len(pool_v3_sub(pk, pi)) <= reach) {
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
	sim->clusters[c].quiet = 0;
	sim->clusters[c].t_next = t;
	for (int k = 0; k < m; ++k)
		join(sim, seed[k], c, t);
	absorb(sim, c, t);
	int *idx = sim->link_members;
	const int count = members(sim, c, idx);
	pool_world_record_event(sim, t, POOL_EVENT_LINK_BEGIN, POOL_RAIL_NONE, POOL_POCKET_NONE, idx, count);
	reschedule(sim, c, t);
	return POOL_OK;
}

// Every ball of the cluster on the cloth (the closed forms can take over its contacts).
static int all_on_cloth(const pool_sim *sim, const pool_ball_state *s, int m) {
	for (int k = 0; k < m; ++k)
		if (s[k].pos.z > sim->def.params.ball_radius + POOL_TOUCH_TOLERANCE)
			return 0;
	return 1;
}

// Every ball of the cluster still (a heap resting on itself: nothing to step until hit).
static int all_still(const pool_sim *sim, const pool_ball_state *s, int m) {
	const double R = sim->def.params.ball_radius;
	for (int k = 0; k < m; ++k)
		if (pool_v3_len(s[k].vel) > POOL_LINK_REST_SPEED || pool_v3_len(s[k].omega) * R > POOL_LINK_REST_SPEED)
			return 0;
	return 1;
}

// Balls of s[0..m) that touch and move together to within POOL_APPROACH_EPS (velocity, and
// spin's surface speed) get their group's mean velocity and spin, exactly the same doubles:
// two balls rolling together in contact then decelerate identically in closed form and never
// meet again, where the rounding of the LCP's solution (1e-14 m/s) would make them "collide"
// by nothing at every event. The mean keeps momentum and never adds energy.
static void merge_common_motion(const pool_sim *sim, pool_ball_state *s, int m, int *group) {
	const double R = sim->def.params.ball_radius, reach = 2.0 * R + POOL_LINK_TOUCH_GAP;
	for (int k = 0; k < m; ++k)
		group[k] = k;
	for (int a = 0; a < m; ++a)
		for (int b = a + 1; b < m; ++b) {
			const double dv = pool_v3_len(pool_v3_sub(s[a].vel, s[b].vel));
			const double dw = pool_v3_len(pool_v3_sub(s[a].omega, s[b].omega)) * R;
			if (pool_v3_len(pool_v3_sub(s[a].pos, s[b].pos)) > reach || dv > POOL_APPROACH_EPS || dw > POOL_APPROACH_EPS)
				continue;
			const int ga = group[a], gb = group[b];
			for (int k = 0; k < m; ++k)
				if (group[k] == gb)
					group[k] = ga;
		}
	for (int g = 0; g < m; ++g) {
		pool_vec3 v = {0.0, 0.0, 0.0}, w = {0.0, 0.0, 0.0};
		int count = 0;
		for (int k = 0; k < m; ++k)
			if (group[k] == g) {
				v = pool_v3_add(v, s[k].vel);
				w = pool_v3_add(w, s[k].omega);
				count++;
			}
		if (count < 2)
			continue;
		v = pool_v3_scale(v, 1.0 / count);
		w = pool_v3_scale(w, 1.0 / count);
		for (int k = 0; k < m; ++k)
			if (group[k] == g) {
				s[k].vel = v;
				s[k].omega = w;
			}
	}
}

// The cluster's balls resume their closed-form states at t, with the velocities of the last
// step (its motion up to t): airborne above the cloth, else the on-cloth state of the
// velocities (pool_motion_after_impulse derives it); link_end records them.
static void dissolve(pool_sim *sim, int c, const int *idx, int m, double t) {
	pool_ball_state *s = sim->link_states;
	sim->clusters[c].active = 0;
	for (int k = 0; k < m; ++k)
		pool_world_state_now(sim, idx[k], t, &s[k]);
	merge_common_motion(sim, s, m, sim->work);
	for (int k = 0; k < m; ++k) {
		s[k].motion = POOL_MOTION_SLIDING;
		pool_motion_after_impulse(&sim->def, &s[k]);
		sim->body[idx[k]].cluster = -1;
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
		for (int rail = POOL_RAIL_SOUTH; rail <= POOL_RAIL_EAST; ++rail) {
			const int along_x = pool_rail_along_x((pool_rail)rail);
			const double across = along_x ? s.pos.y : s.pos.x, along = along_x ? s.pos.x : s.pos.y;
			const double line = pool_rail_contact_line(table, sim->dc, (pool_rail)rail);
			const pool_pocket pocket = pool_pocket_at(table, (pool_rail)rail, along);
			if (!(pool_rail_side((pool_rail)rail) * (across - line) > 0.0) || pocket == POOL_POCKET_NONE)
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

pool_result pool_link_step_event(pool_sim *sim, int i, double t) {
	const int c = sim->body[i].cluster;
	pool_cluster *cl = &sim->clusters[c];
	absorb(sim, c, t);
	const pool_result rp = pocket_strays(sim, c, t);
	if (rp)
		return rp;
	int *idx = sim->link_members;
	pool_ball_state *s = sim->link_states;
	const int m = members(sim, c, idx);
	if (m == 0) {
		cl->active = 0;
		return POOL_OK;
	}
	// Dissolution is decided by the last step, so every cluster takes at least one step (a
	// Zeno pair is merged by it) and a dissolving cluster keeps the motion it had.
	if (cl->quiet) {
		dissolve(sim, c, idx, m, t);
		return POOL_OK;
	}
	for (int k = 0; k < m; ++k)
		pool_world_state_now(sim, idx[k], t, &s[k]);
	pool_link_step_stats st;
	const pool_result r = pool_link_step(&sim->def, s, m, POOL_LINK_STEP_TIME, &sim->link_ws, &sim->alloc, &st);
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
	const int still = all_still(sim, s, m), on_cloth = all_on_cloth(sim, s, m);
	// Apart, or touching on the cloth without pressing: the closed forms take over (two balls
	// rolling together in contact stay so by themselves; if friction presses them again, the
	// trigger forms a new cluster). A heap at rest above the cloth sleeps instead.
	cl->quiet = st.touching == 0 || (on_cloth && (still || st.max_push <= POOL_LINK_REST_SPEED));
	cl->t_next = still && !cl->quiet ? INFINITY : t + POOL_LINK_STEP_TIME;
	for (int k = 0; k < m; ++k) {
		s[k].motion = POOL_MOTION_LINKED;
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

void pool_link_touched(pool_sim *sim, int i, double t) {
	const int c = sim->body[i].cluster;
	sim->clusters[c].t_next = t;
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
	reschedule(sim, c, t);
}

pool_result pool_sim_link_stats(const pool_sim *sim, pool_link_stats *out) {
	if (!sim || !out)
		return POOL_ERR_INVALID_ARGUMENT;
	*out = sim->link_stats;
	return POOL_OK;
}
