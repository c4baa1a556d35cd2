// The energy of LINK steps, checked from a shot's recorded events alone (header-only, shared by
// the soak's hostile.h and the unit tests that run clusters).
//
// A LINK step (docs/physics.md "LINK") changes its balls' velocities at its start for the whole
// step it plans (gravity's kick, the contact impulses, the cloth wrenches), and the positions
// then follow them over the step. So the energy of the recorded states is not monotone inside a
// step: a falling ball's kinetic energy rises at the step's start by what its fall releases
// over the step, a cloth contact's dissipation shows at the start. What is monotone is the
// energy where a step ends: at its planned end (the states just before the next step: the step
// has released what its start gave), and where an event from outside cuts it short (the states
// the cut recorded: the step's changes taken for the time it lasted). So for every step S of a
// cluster, with E(S) its balls' energy entering it (just before its link_step event):
//   - at every later event that involves one of S's balls while they are still its (no event
//     from outside has touched one of them since S, and none of them has entered a later step:
//     that step, held to the energy S left it, takes over), the energy of S's balls is at most
//     E(S) + LE_TOLERANCE, taken just before that event, or for a LINK event (the cut, the next
//     step, balls leaving) the lower of just before and just after it;
//   - in particular just before an event from outside reaches a ball of S in mid-step (a step
//     that kept its whole kick there gained energy from nowhere: issue 21's reproducer 2).
// Kinetic plus potential energy above the cloth, m g (z - R); out-of-play balls have none.
#ifndef POOL_TESTS_LINK_ENERGY_H
#define POOL_TESTS_LINK_ENERGY_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "motion.h"
#include "pool/pool.h"

/// J: what a step may gain over the energy entering it, beyond LE_TOLERANCE_REL of it. The
/// step's LCP only dissipates (inelastic contacts, friction; semi-implicit gravity loses
/// m g^2 dt^2 / 2 a step in free fall), up to Lemke's residual on impulses of a few mN s and the
/// capped push out of an existing penetration (link_step.c), which rounding-level overlaps keep
/// far below this.
#define LE_TOLERANCE 1e-9
/// Relative part of the tolerance: the rounding of energy sums of a few joules.
#define LE_TOLERANCE_REL 1e-12

/// The balls a check follows (the tests' shots have at most 16).
#define LE_MAX_BALLS 64

typedef struct le_result {
	double worst;      ///< J, the largest gain over a step's entering energy, less the relative tolerance
	int checks;        ///< the comparisons made
	int worst_event;   ///< the event of the worst one
	double worst_time; ///< s, its time
	int worst_step;    ///< the link_step event whose step it was held to
} le_result;

/// Energy of one ball (kinetic + potential above the cloth), J.
static inline double le_energy(const pool_params *p, const pool_ball_state *s) {
	if (s->motion == POOL_MOTION_POCKETED || s->motion == POOL_MOTION_OFF_TABLE)
		return 0.0;
	return pool_motion_energy(p, s) + p->ball_mass * p->g * (s->pos.z - p->ball_radius);
}

static inline int le_is_link(pool_event_type type) {
	return type == POOL_EVENT_LINK_BEGIN || type == POOL_EVENT_LINK_STEP || type == POOL_EVENT_LINK_END;
}

typedef struct le_step {
	int event;      // its link_step event
	uint64_t balls; // by index
	double energy;  // J, entering the step
	double time;    // s
	int open;       // no event from outside has touched its balls since
} le_step;

/// Checks the steps of the finished shot of sim; initial[0..n) are the balls' first states (as
/// placed, by index). ok is set to 0 when a comparison exceeds the tolerance.
static inline le_result le_check(const pool_sim *sim, const pool_params *p, const pool_ball_state *initial, int n,
                                 int *ok) {
	le_result r = {-INFINITY, 0, -1, 0.0, -1};
	if (n > LE_MAX_BALLS)
		n = LE_MAX_BALLS;
	int count = 0;
	const pool_event *ev = pool_sim_events(sim, &count);
	pool_ball_state seg[LE_MAX_BALLS];
	double t0[LE_MAX_BALLS];
	int last_step[LE_MAX_BALLS];
	for (int i = 0; i < n; ++i) {
		seg[i] = initial[i];
		t0[i] = 0.0;
		last_step[i] = -1;
	}
	le_step *steps = malloc(sizeof *steps * (size_t)(count + 1));
	int n_steps = 0;
	for (int e = 0; e < count; ++e) {
		const double t = ev[e].time;
		const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
		int idx[LE_MAX_BALLS];
		uint64_t in_event = 0;
		for (int k = 0; k < ev[e].ball_count && k < LE_MAX_BALLS; ++k) {
			idx[k] = -1;
			for (int i = 0; i < n; ++i)
				if (initial[i].id == after[k].id)
					idx[k] = i;
			if (idx[k] >= 0)
				in_event |= (uint64_t)1 << idx[k];
		}
		const int m = ev[e].ball_count < LE_MAX_BALLS ? ev[e].ball_count : LE_MAX_BALLS;
		const int link = le_is_link(ev[e].type);
		// The steps this event reaches: those of its balls that are linked now.
		for (int k = 0; k < m; ++k) {
			if (idx[k] < 0 || seg[idx[k]].motion != POOL_MOTION_LINKED)
				continue;
			const int s = last_step[idx[k]];
			if (s < 0 || !steps[s].open || !(steps[s].time < t))
				continue;
			int seen = 0;
			for (int j = 0; j < k; ++j)
				seen |= idx[j] >= 0 && last_step[idx[j]] == s && seg[idx[j]].motion == POOL_MOTION_LINKED;
			if (seen)
				continue;
			double before = 0.0, with_after = 0.0;
			for (int i = 0; i < n; ++i) {
				if (!(steps[s].balls >> i & 1))
					continue;
				pool_ball_state now;
				pool_motion_evolve(p, &seg[i], t - t0[i], &now);
				const double ei = le_energy(p, &now);
				before += ei;
				double ea = ei;
				if (in_event >> i & 1)
					for (int q = 0; q < m; ++q)
						if (idx[q] == i)
							ea = le_energy(p, &after[q]);
				with_after += ea;
			}
			const double energy = link ? fmin(before, with_after) : before;
			const double gain = energy - steps[s].energy - LE_TOLERANCE_REL * fmax(steps[s].energy, 1.0);
			++r.checks;
			if (gain > r.worst) {
				r.worst = gain;
				r.worst_event = e;
				r.worst_time = t;
				r.worst_step = steps[s].event;
			}
			if (!(gain <= LE_TOLERANCE))
				*ok = 0;
		}
		// An event from outside ends what every step of its balls can be held to.
		if (!link)
			for (int q = 0; q < n_steps; ++q)
				if (steps[q].balls & in_event)
					steps[q].open = 0;
		if (ev[e].type == POOL_EVENT_LINK_STEP) {
			le_step *s = &steps[n_steps];
			s->event = e;
			s->balls = in_event;
			s->time = t;
			s->open = 1;
			s->energy = 0.0;
			for (int k = 0; k < m; ++k)
				if (idx[k] >= 0) {
					pool_ball_state now;
					pool_motion_evolve(p, &seg[idx[k]], t - t0[idx[k]], &now);
					s->energy += le_energy(p, &now);
					// The ball's previous step is done (checked above at this event): its other
					// balls may now share a cluster with balls an outside event has hit.
					if (last_step[idx[k]] >= 0)
						steps[last_step[idx[k]]].open = 0;
					last_step[idx[k]] = n_steps;
				}
			++n_steps;
		}
		for (int k = 0; k < m; ++k)
			if (idx[k] >= 0) {
				seg[idx[k]] = after[k];
				t0[idx[k]] = t;
			}
	}
	free(steps);
	return r;
}

#endif
