// Candidate shots from the geometry: ghost balls for straight shots, mirror images across a
// cushion's contact line for banks and kicks, ghost balls in turn for combinations, and the
// 90-degree rule for caroms. Each is only a first guess: throw, cut-induced spin, the cushion's
// real rebound and the balls' curves are the simulation's (refine.c).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "aim_internal.h"

// Cuts thinner than these are not tried: the ball goes off far from its line (throw), and a
// noisy stroke misses it anyway. A combination's and a carom's two contacts each get less.
#define AIM_MAX_CUT_DEG 78.0
#define AIM_MAX_CUT_TWO_DEG 60.0
// A carom: the potted ball's path after the kiss, at most this far from its path before it.
#define AIM_MAX_KISS_DEG 70.0
// m/s the potted ball should still have at the pocket for the first guess of the speed: enough to
// fall through a mouth rather than stop in its jaws.
#define AIM_ARRIVAL_SPEED 0.6
// Share of a ball's speed a cushion gives back along its new path, for the first guess only
// (e_cushion and the friction of the impact; docs/measurements.md: 0.76 to 0.91 straight on).
#define AIM_CUSHION_KEEP 0.75
// The grid of first guesses per geometry: speeds as multiples of the estimated least speed, and
// vertical tip offsets (centre, follow, draw) in ball radii.
static const double speed_factors[] = {1.0, 1.5, 2.2};
static const double spins[] = {0.0, 0.35, -0.35};
// m/s: the softest and hardest first guesses.
#define AIM_MIN_SPEED 0.3
#define AIM_MAX_SPEED 7.0
// Harder kinds are tried after easier ones at the same distance (the order only matters when the
// time budget stops the search).
static const double kind_weight[POOL_AIM_KINDS] = {1.0, 2.0, 2.5, 3.0, 3.0};

/// A candidate's geometry, before the grid of speeds and spins.
typedef struct shot_plan {
	pool_aim_kind kind;
	int ball, via;
	pool_pocket pocket;
	pool_rail rail;
	aim_xy aim;          ///< where the cue ball's path is aimed
	double cue_path;     ///< m the cue ball travels to its first ball
	double object_path;  ///< m the potted ball travels to the pocket (after the kiss, for a carom)
	double transfer;     ///< share of the cue ball's speed the potted ball leaves with
	double cut;          ///< cosine of the thinnest cut of the shot
	int approach;
} shot_plan;

static aim_xy at(const aim_search *s, int i) {
	return (aim_xy){s->def->balls[i].pos.x, s->def->balls[i].pos.y};
}

static bool clear_path(const aim_search *s, aim_xy a, aim_xy b, int skip1, int skip2) {
	return aim_clear(s->def->balls, s->def->ball_count, s->table.radius, a, b, skip1, skip2);
}

/// Whether a ball's centre can be at p (inside the cushions' contact lines).
static bool on_table(const aim_search *s, aim_xy p) {
	const aim_table *t = &s->table;
	return p.x >= t->contact && p.x <= t->length - t->contact && p.y >= t->contact && p.y <= t->width - t->contact;
}

/// Whether a ball heading along u can enter pocket p.
static bool enters(const aim_search *s, aim_xy u, pool_pocket p) {
	return aim_dot(u, s->table.axis[p]) >= s->table.accept[p];
}

/// The cue speed (m/s) that gets the potted ball to the pocket at AIM_ARRIVAL_SPEED: each ball
/// rolls at 5/7 of the speed it leaves with (docs/validation.md 1) and slows by mu_roll g.
static double least_speed(const aim_search *s, const shot_plan *plan) {
	const pool_params *p = &s->def->sim.params;
	double roll = 2.0 * p->mu_roll * p->g;
	double v_object = 1.4 * sqrt(AIM_ARRIVAL_SPEED * AIM_ARRIVAL_SPEED + roll * plan->object_path);
	double v_impact = v_object / fmax(plan->transfer, 0.05);
	double v_cue = 1.4 * sqrt(v_impact * v_impact / 1.96 + roll * plan->cue_path);
	return v_cue * (1.0 + p->ball_mass / p->cue_mass) / 2.0; // the strike gives 2 V / (1 + m/M)
}

static int push(aim_search *s, const aim_candidate *c) {
	if (s->count == s->capacity) {
		int capacity = s->capacity ? 2 * s->capacity : 256;
		aim_candidate *bigger = realloc(s->cands, (size_t)capacity * sizeof *bigger);
		if (!bigger)
			return -1;
		s->cands = bigger;
		s->capacity = capacity;
	}
	s->cands[s->count++] = *c;
	return 0;
}

/// The grid of speeds and spins of one geometry, each with the elevation its cue needs.
static int add_plan(aim_search *s, const shot_plan *plan, int *blocked) {
	const double R = s->table.radius;
	const aim_xy from = at(s, s->cue);
	const double phi = atan2(plan->aim.y - from.y, plan->aim.x - from.x);
	const double base = least_speed(s, plan);
	const double difficulty = kind_weight[plan->kind] * (plan->cue_path + plan->object_path) / fmax(plan->cut, 0.05);
	for (size_t v = 0; v < sizeof speed_factors / sizeof speed_factors[0]; ++v)
		for (size_t k = 0; k < sizeof spins / sizeof spins[0]; ++k) {
			double b = spins[k] * R, theta = aim_cue_elevation(s, phi, 0.0, b, 0.0);
			if (theta < 0.0) {
				++*blocked;
				continue;
			}
			double speed = fmin(fmax(base * speed_factors[v], AIM_MIN_SPEED), AIM_MAX_SPEED);
			aim_candidate c = {.kind = plan->kind, .ball = plan->ball, .via = plan->via, .pocket = plan->pocket,
			                   .rail = plan->rail, .approach = plan->approach,
			                   .strike = {speed, phi, theta, 0.0, b},
			                   .difficulty = difficulty * (1.0 + 0.01 * (double)(v * 3 + k)), .position = -1};
			if (push(s, &c) != 0)
				return -1;
		}
	return 0;
}

static double cos_deg(double deg) { return cos(deg * AIM_DEG); }

static bool rail_of_pocket(pool_rail r, pool_pocket p) {
	switch (p) {
	case POOL_POCKET_SW: return r == POOL_RAIL_SOUTH || r == POOL_RAIL_WEST;
	case POOL_POCKET_SE: return r == POOL_RAIL_SOUTH || r == POOL_RAIL_EAST;
	case POOL_POCKET_NW: return r == POOL_RAIL_NORTH || r == POOL_RAIL_WEST;
	case POOL_POCKET_NE: return r == POOL_RAIL_NORTH || r == POOL_RAIL_EAST;
	case POOL_POCKET_S: return r == POOL_RAIL_SOUTH;
	default: return r == POOL_RAIL_NORTH;
	}
}

/// Straight shots and kicks of ball i into pocket p.
static int straight_and_kicks(aim_search *s, int i, pool_pocket p, unsigned kinds, int *blocked) {
	const double R = s->table.radius, half = (1.0 + s->def->sim.params.e_ball) / 2.0;
	const aim_xy C = at(s, s->cue), O = at(s, i), T = s->table.target[p];
	const aim_xy u = aim_unit(aim_sub(T, O));
	const aim_xy G = aim_add_scaled(O, u, -2.0 * R);
	if (!enters(s, u, p) || !on_table(s, G) || !clear_path(s, O, T, i, -1))
		return 0;
	if (kinds & (1u << POOL_AIM_STRAIGHT)) {
		aim_xy w = aim_unit(aim_sub(G, C));
		double cut = aim_dot(w, u);
		if (cut >= cos_deg(AIM_MAX_CUT_DEG) && clear_path(s, C, G, s->cue, i)) {
			shot_plan plan = {POOL_AIM_STRAIGHT, i, -1, p, POOL_RAIL_NONE, G, aim_norm(aim_sub(G, C)),
			                  aim_norm(aim_sub(T, O)), cut * half, cut, 1};
			if (add_plan(s, &plan, blocked) != 0)
				return -1;
		}
	}
	if (!(kinds & (1u << POOL_AIM_KICK)))
		return 0;
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_EAST; ++r) {
		aim_xy image = aim_mirror(&s->table, (pool_rail)r, G), B;
		if (!aim_bounce(&s->table, (pool_rail)r, C, image, &B))
			continue;
		aim_xy w = aim_unit(aim_sub(G, B));
		double cut = aim_dot(w, u);
		if (cut < cos_deg(AIM_MAX_CUT_DEG) || !clear_path(s, C, B, s->cue, -1) || !clear_path(s, B, G, s->cue, i))
			continue;
		shot_plan plan = {POOL_AIM_KICK, i, -1, p, (pool_rail)r, image,
		                  aim_norm(aim_sub(B, C)) + aim_norm(aim_sub(G, B)), aim_norm(aim_sub(T, O)),
		                  cut * half * AIM_CUSHION_KEEP, cut, 1};
		if (add_plan(s, &plan, blocked) != 0)
			return -1;
	}
	return 0;
}

/// Banks of ball i off each cushion into pocket p.
static int banks(aim_search *s, int i, pool_pocket p, int *blocked) {
	const double R = s->table.radius, half = (1.0 + s->def->sim.params.e_ball) / 2.0;
	const aim_xy C = at(s, s->cue), O = at(s, i), T = s->table.target[p];
	for (int r = POOL_RAIL_SOUTH; r <= POOL_RAIL_EAST; ++r) {
		if (rail_of_pocket((pool_rail)r, p))
			continue;
		aim_xy image = aim_mirror(&s->table, (pool_rail)r, T), B;
		if (!aim_bounce(&s->table, (pool_rail)r, O, image, &B))
			continue;
		aim_xy u = aim_unit(aim_sub(image, O)), G = aim_add_scaled(O, u, -2.0 * R);
		aim_xy w = aim_unit(aim_sub(G, C));
		double cut = aim_dot(w, u);
		if (!enters(s, aim_unit(aim_sub(T, B)), p) || !on_table(s, G) || cut < cos_deg(AIM_MAX_CUT_DEG) ||
		    !clear_path(s, C, G, s->cue, i) || !clear_path(s, O, B, i, -1) || !clear_path(s, B, T, i, -1))
			continue;
		shot_plan plan = {POOL_AIM_BANK, i, -1, p, (pool_rail)r, G, aim_norm(aim_sub(G, C)),
		                  aim_norm(aim_sub(B, O)) + aim_norm(aim_sub(T, B)), cut * half * AIM_CUSHION_KEEP, cut, 2};
		if (add_plan(s, &plan, blocked) != 0)
			return -1;
	}
	return 0;
}

/// Ball j driven into ball i, which goes into pocket p.
static int combination(aim_search *s, int i, int j, pool_pocket p, int *blocked) {
	const double R = s->table.radius, half = (1.0 + s->def->sim.params.e_ball) / 2.0;
	const aim_xy C = at(s, s->cue), A = at(s, j), O = at(s, i), T = s->table.target[p];
	const aim_xy u2 = aim_unit(aim_sub(T, O)), G2 = aim_add_scaled(O, u2, -2.0 * R);
	const aim_xy u1 = aim_unit(aim_sub(G2, A)), G1 = aim_add_scaled(A, u1, -2.0 * R);
	const aim_xy w = aim_unit(aim_sub(G1, C));
	const double cut2 = aim_dot(u1, u2), cut1 = aim_dot(w, u1), limit = cos_deg(AIM_MAX_CUT_TWO_DEG);
	if (!enters(s, u2, p) || cut1 < limit || cut2 < limit || !on_table(s, G1) || !on_table(s, G2) ||
	    !clear_path(s, O, T, i, -1) || !clear_path(s, A, G2, j, i) || !clear_path(s, C, G1, s->cue, j))
		return 0;
	shot_plan plan = {POOL_AIM_COMBINATION, i, j, p, POOL_RAIL_NONE, G1, aim_norm(aim_sub(G1, C)),
	                  aim_norm(aim_sub(G2, A)) + aim_norm(aim_sub(T, O)), cut1 * half * cut2 * half,
	                  fmin(cut1, cut2), 1};
	return add_plan(s, &plan, blocked);
}

/// Ball i glancing off ball j into pocket p: a stunned ball leaves a kiss along the tangent, so
/// it must touch j where the tangent points at the pocket, X with (T - X).(X - Oj) = 0 and
/// |X - Oj| = 2R: x = 4R^2 / D along Oj->T, y = +-sqrt(4R^2 - x^2) across it.
static int caroms(aim_search *s, int i, int j, pool_pocket p, int *blocked) {
	const double R = s->table.radius, half = (1.0 + s->def->sim.params.e_ball) / 2.0;
	const aim_xy C = at(s, s->cue), O = at(s, i), K = at(s, j), T = s->table.target[p];
	const double D = aim_norm(aim_sub(T, K));
	if (D <= 2.0 * R)
		return 0;
	const aim_xy e1 = aim_unit(aim_sub(T, K)), e2 = {-e1.y, e1.x};
	const double x = 4.0 * R * R / D, y = sqrt(fmax(4.0 * R * R - x * x, 0.0));
	for (int side = -1; side <= 1; side += 2) {
		aim_xy X = aim_add_scaled(aim_add_scaled(K, e1, x), e2, side * y);
		aim_xy n = aim_unit(aim_sub(X, K)), out = aim_unit(aim_sub(T, X)), u1 = aim_unit(aim_sub(X, O));
		aim_xy G1 = aim_add_scaled(O, u1, -2.0 * R), w = aim_unit(aim_sub(G1, C));
		double kiss = aim_dot(u1, out), cut1 = aim_dot(w, u1);
		if (aim_dot(u1, n) >= 0.0 || kiss < cos_deg(AIM_MAX_KISS_DEG) || cut1 < cos_deg(AIM_MAX_CUT_TWO_DEG) ||
		    !enters(s, out, p) || !on_table(s, X) || !on_table(s, G1) || !clear_path(s, C, G1, s->cue, i) ||
		    !clear_path(s, O, X, i, j) || !clear_path(s, X, T, i, j))
			continue;
		shot_plan plan = {POOL_AIM_CAROM, i, j, p, POOL_RAIL_NONE, G1, aim_norm(aim_sub(G1, C)),
		                  aim_norm(aim_sub(X, O)) + aim_norm(aim_sub(T, X)), cut1 * half * kiss, fmin(cut1, kiss), 2};
		if (add_plan(s, &plan, blocked) != 0)
			return -1;
	}
	return 0;
}

static int by_difficulty(const void *pa, const void *pb) {
	const aim_candidate *a = pa, *b = pb;
	if (a->difficulty != b->difficulty)
		return a->difficulty < b->difficulty ? -1 : 1;
	return 0;
}

int aim_candidates(aim_search *s) {
	const pool_aim_def *d = s->def;
	unsigned kinds = d->kinds ? d->kinds : (1u << POOL_AIM_KINDS) - 1;
	int blocked = 0;
	for (int i = 0; i < d->ball_count; ++i) {
		if (i == s->cue || (d->ball != POOL_AIM_NO_BALL && d->balls[i].id != d->ball))
			continue;
		for (int p = 0; p < 6; ++p) {
			if (d->pocket != POOL_POCKET_NONE && (int)d->pocket != p)
				continue;
			if (aim_legal_first(s, i)) { // the cue ball meets i first
				if (straight_and_kicks(s, i, (pool_pocket)p, kinds, &blocked) != 0)
					return -1;
				if ((kinds & (1u << POOL_AIM_BANK)) && banks(s, i, (pool_pocket)p, &blocked) != 0)
					return -1;
			}
			for (int j = 0; j < d->ball_count; ++j) {
				if (j == i || j == s->cue)
					continue;
				if ((kinds & (1u << POOL_AIM_COMBINATION)) && aim_legal_first(s, j) &&
				    combination(s, i, j, (pool_pocket)p, &blocked) != 0)
					return -1;
				if ((kinds & (1u << POOL_AIM_CAROM)) && aim_legal_first(s, i) &&
				    caroms(s, i, j, (pool_pocket)p, &blocked) != 0)
					return -1;
			}
		}
	}
	if (s->count > 1) // (no candidates: cands may be NULL, which qsort must not be given)
		qsort(s->cands, (size_t)s->count, sizeof *s->cands, by_difficulty);
	return blocked;
}
