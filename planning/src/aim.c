// pool_aim_search: the def checked, the candidates generated, refined by simulation on every
// core, ranked under noise (docs/planning.md).
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aim_internal.h"

// The share of a time budget the refinement may use; the rest ranks what it found.
#define AIM_REFINE_SHARE 0.6
// Limits of the def (a search of more would not finish in any useful time).
#define AIM_MAX_SAMPLES 1000000
#define AIM_MAX_THREADS 1024
// Two refined strikes closer than this in speed (m/s) and aim (rad) are one shot.
#define AIM_SAME_SPEED 1e-3
#define AIM_SAME_PHI 1e-5

static const char *const kind_names[POOL_AIM_KINDS] = {"straight", "bank", "kick", "combination", "carom"};

const char *pool_aim_kind_name(pool_aim_kind kind) {
	return (int)kind >= 0 && kind < POOL_AIM_KINDS ? kind_names[kind] : NULL;
}

int pool_aim_kind_from_name(const char *name) {
	for (int k = 0; name && k < POOL_AIM_KINDS; ++k)
		if (strcmp(name, kind_names[k]) == 0)
			return k;
	return -1;
}

pool_aim_def pool_default_aim_def(void) {
	pool_aim_def d;
	memset(&d, 0, sizeof d);
	d.sim = pool_default_sim_def();
	d.cue_ball = 0;
	d.ball = POOL_AIM_NO_BALL;
	d.pocket = POOL_POCKET_NONE;
	pool_noise_preset("fastfiz", &d.noise);
	d.seed = 1;
	d.samples = 400;
	d.top = 5;
	return d;
}

static pool_result fail(pool_error *error, pool_result r, const char *format, ...) __attribute__((format(printf, 3, 4)));
static pool_result fail(pool_error *error, pool_result r, const char *format, ...) {
	if (error) {
		va_list args;
		va_start(args, format);
		vsnprintf(error->message, sizeof error->message, format, args);
		va_end(args);
	}
	return r;
}

bool aim_legal_first(const aim_search *s, int i) {
	const pool_game_state *g = s->def->game;
	const int32_t id = s->def->balls[i].id;
	if (!g)
		return true;
	if (g->rules == POOL_GAME_9BALL) { // the lowest ball on the table (WPA 2.2)
		for (int k = 0; k < s->def->ball_count; ++k)
			if (k != s->cue && s->def->balls[k].id < id)
				return false;
		return true;
	}
	// 8-ball (WPA 3.4, 3.5): a ball of the shooter's group, any but the 8 on an open table, the 8
	// once the group is cleared.
	bool solids_left = false, stripes_left = false;
	for (int k = 0; k < s->def->ball_count; ++k) {
		int32_t b = s->def->balls[k].id;
		solids_left = solids_left || (b >= 1 && b <= 7);
		stripes_left = stripes_left || (b >= 9 && b <= 15);
	}
	switch (g->group) {
	case POOL_GROUP_SOLIDS: return (id >= 1 && id <= 7) || (id == 8 && !solids_left);
	case POOL_GROUP_STRIPES: return (id >= 9 && id <= 15) || (id == 8 && !stripes_left);
	default: return id != 8 && id != s->def->cue_ball;
	}
}

/// Checks the def; the message names the field.
static pool_result check(const pool_aim_def *d, pool_aim_shot *shots, int capacity, int *count, pool_error *e,
                         int *cue) {
	if (!d || !count || capacity < 0 || (capacity > 0 && !shots))
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim: missing def, shots or count");
	if (d->ball_count < 2 || !d->balls)
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.balls: a position needs the cue ball and another ball");
	if (d->samples < 1 || d->samples > AIM_MAX_SAMPLES)
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.samples: must be from 1 to %d", AIM_MAX_SAMPLES);
	if (d->top < 1)
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.top: must be at least 1");
	if (!isfinite(d->time_budget) || d->time_budget < 0.0)
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.time_budget: must be a time in seconds >= 0");
	if (d->threads < 0 || d->threads > AIM_MAX_THREADS)
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.threads: must be from 0 (all CPUs) to %d", AIM_MAX_THREADS);
	if (d->kinds >= 1u << POOL_AIM_KINDS)
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.kinds: unknown kind bits 0x%x", d->kinds);
	if (d->pocket != POOL_POCKET_NONE && ((int)d->pocket < 0 || d->pocket > POOL_POCKET_N))
		return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.pocket: not a pocket");
	pool_result r = pool_noise_validate(&d->noise, e);
	if (r != POOL_OK)
		return r;
	*cue = -1;
	bool target = d->ball == POOL_AIM_NO_BALL;
	for (int k = 0; k < d->ball_count; ++k) {
		const pool_ball_state *b = &d->balls[k];
		if (b->id == d->cue_ball)
			*cue = k;
		target = target || (b->id == d->ball && d->ball != d->cue_ball);
		double speed = fabs(b->vel.x) + fabs(b->vel.y) + fabs(b->vel.z) + fabs(b->omega.x) + fabs(b->omega.y) +
		               fabs(b->omega.z);
		if (speed != 0.0)
			return fail(e, POOL_ERR_INVALID_ARGUMENT, "balls[%d]: must be at rest (a shot is planned between shots)", k);
	}
	if (*cue < 0)
		return fail(e, POOL_ERR_UNKNOWN_BALL, "aim.cue_ball: no ball has id %d", (int)d->cue_ball);
	if (!target)
		return fail(e, POOL_ERR_UNKNOWN_BALL, "aim.ball: no object ball has id %d", (int)d->ball);
	if (d->game) {
		if ((r = pool_game_state_validate(d->game, e)) != POOL_OK)
			return r;
		if (d->game->rules == POOL_GAME_THREE_CUSHION)
			return fail(e, POOL_ERR_INVALID_ARGUMENT, "aim.game: three_cushion has no pockets to aim at");
		if ((r = pool_game_check_balls(d->game, d->balls, d->ball_count, e)) != POOL_OK)
			return r;
	}
	// The balls as the library sees them: on the table, apart, ids unique (its own messages).
	pool_sim *sim = NULL;
	r = pool_sim_create(&d->sim, &sim, e);
	for (int k = 0; r == POOL_OK && k < d->ball_count; ++k)
		r = pool_sim_add_ball(sim, &d->balls[k], e);
	pool_sim_destroy(sim);
	return r;
}

/// Refinements of one geometry from different first guesses can end on the same strike (a speed
/// raised to reach the pocket meets the next guess): the later copies are dropped.
static void drop_duplicates(aim_search *s) {
	for (int k = 0; k < s->count; ++k) {
		aim_candidate *c = &s->cands[k];
		for (int j = 0; j < k && c->state == AIM_POTS; ++j) {
			const aim_candidate *o = &s->cands[j];
			if (o->state == AIM_POTS && o->kind == c->kind && o->ball == c->ball && o->via == c->via &&
			    o->pocket == c->pocket && o->rail == c->rail && o->strike.a == c->strike.a &&
			    o->strike.b == c->strike.b && o->strike.theta == c->strike.theta &&
			    fabs(o->strike.speed - c->strike.speed) < AIM_SAME_SPEED &&
			    fabs(remainder(o->strike.phi - c->strike.phi, 2.0 * AIM_PI)) < AIM_SAME_PHI)
				c->state = AIM_DUPLICATE;
		}
	}
}

static void refine_task(aim_search *s, aim_worker *w, long i, void *ctx) {
	(void)ctx;
	aim_refine(s, w, &s->cands[i]);
}

pool_result pool_aim_def_validate(const pool_aim_def *def, pool_error *error) {
	int count = 0, cue = -1;
	if (error)
		error->message[0] = '\0';
	return check(def, NULL, 0, &count, error, &cue);
}

pool_result pool_aim_search(const pool_aim_def *def, pool_aim_shot *shots, int capacity, int *count,
                            pool_aim_stats *stats, pool_error *error) {
	aim_search s = {.def = def};
	pool_aim_stats st = {0};
	if (count)
		*count = 0;
	if (error)
		error->message[0] = '\0';
	pool_result r = check(def, shots, capacity, count, error, &s.cue);
	if (r != POOL_OK)
		return r;
	s.started = aim_now();
	s.deadline = def->time_budget > 0.0 ? s.started + def->time_budget : INFINITY;
	s.refine_deadline = def->time_budget > 0.0 ? s.started + AIM_REFINE_SHARE * def->time_budget : INFINITY;
	atomic_init(&s.out_of_time, false);
	atomic_init(&s.failure, 0);
	aim_table_init(&s.table, &def->sim);
	int *order = NULL;
	int blocked = aim_candidates(&s);
	if (blocked < 0 || aim_workers_create(&s) != 0) {
		r = fail(error, POOL_ERR_OUT_OF_MEMORY, "aim: out of memory");
		goto done;
	}
	st.blocked = blocked;
	st.candidates = s.count + blocked;
	aim_parallel(&s, s.count, refine_task, NULL);
	if ((r = (pool_result)atomic_load(&s.failure)) != POOL_OK) {
		fail(error, r, "aim: the library failed to simulate a shot: %s", pool_result_str(r));
		goto done;
	}
	drop_duplicates(&s);
	for (int k = 0; k < s.count; ++k) {
		const int state = s.cands[k].state;
		st.refined += state != AIM_SKIPPED;
		st.potting += state == AIM_POTS || state == AIM_DUPLICATE;
		st.blocked += state == AIM_BLOCKED;
	}
	order = malloc((size_t)(s.count > 0 ? s.count : 1) * sizeof *order);
	int chosen = order ? aim_rank(&s, order) : -1;
	if (chosen < 0) {
		r = fail(error, POOL_ERR_OUT_OF_MEMORY, "aim: out of memory");
		goto done;
	}
	if ((r = (pool_result)atomic_load(&s.failure)) != POOL_OK) {
		fail(error, r, "aim: the library failed to simulate a shot: %s", pool_result_str(r));
		goto done;
	}
	int n = chosen < capacity ? chosen : capacity;
	for (int k = 0; k < n; ++k) {
		const aim_candidate *c = &s.cands[order[k]];
		pool_aim_shot *o = &shots[k];
		*o = (pool_aim_shot){.strike = c->strike, .ball = def->balls[c->ball].id, .pocket = c->pocket, .kind = c->kind,
		                     .via = c->via >= 0 ? def->balls[c->via].id : POOL_AIM_NO_BALL, .rail = c->rail,
		                     .samples = (int)c->report_samples,
		                     .cue_final = {c->cue_final.x, c->cue_final.y, s.table.radius}, .position = c->position};
		o->p_success = c->report_samples > 0 ? (double)c->report_successes / (double)c->report_samples : 0.0;
		aim_wilson(c->report_successes, c->report_samples, &o->ci_low, &o->ci_high);
	}
	*count = n;
done:
	for (int k = 0; k < s.threads && s.workers; ++k)
		st.simulations += s.workers[k].simulations;
	st.seconds = aim_now() - s.started;
	st.budget_reached = atomic_load(&s.out_of_time) || (isfinite(s.deadline) && aim_now() > s.deadline);
	if (stats)
		*stats = st;
	aim_workers_free(&s);
	free(s.cands);
	free(order);
	return r;
}
