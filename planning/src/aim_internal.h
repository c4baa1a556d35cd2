// The pieces of a shot search (pool/aim.h): the table's geometry for aiming (geometry.c), the
// candidates (candidates.c), a candidate simulated and judged (simulate.c), refined (refine.c)
// and ranked under noise (rank.c), the cue ball's next shots (position.c), all on worker threads
// (workers.c). aim.c runs them in turn.
#ifndef POOL_AIM_INTERNAL_H
#define POOL_AIM_INTERNAL_H

#include <stdatomic.h>

#include "pool/aim.h"

#define AIM_PI 3.14159265358979323846
#define AIM_DEG (AIM_PI / 180.0)

// ---- geometry ---------------------------------------------------------------------------------

/// A point or direction on the table (m).
typedef struct aim_xy {
	double x, y;
} aim_xy;

/// The table as aiming sees it: where a ball's centre can go, the pockets' aiming points and
/// the cushions a ball can be banked off.
typedef struct aim_table {
	double length, width;  ///< m, the nose lines' rectangle
	double radius;         ///< m, ball radius
	double contact;        ///< m, a ball on the cloth touches a nose with its centre this far from it
	aim_xy target[6];      ///< per pocket: the point a ball's path is aimed through (the mouth's middle)
	aim_xy axis[6];        ///< per pocket: unit, pointing out of the table through the mouth
	double accept[6];      ///< per pocket: cos of the widest angle of approach to the axis tried
	double span_lo[4][2], span_hi[4][2]; ///< per rail: the stretches of cushion a ball may bounce
	                                     ///< off (coordinate along the rail), between the pockets
	int spans[4];          ///< per rail: how many stretches (2 on the long rails, 1 on the short)
} aim_table;

void aim_table_init(aim_table *t, const pool_sim_def *def);

aim_xy aim_sub(aim_xy a, aim_xy b);
aim_xy aim_add_scaled(aim_xy a, aim_xy d, double s);
double aim_dot(aim_xy a, aim_xy b);
double aim_cross(aim_xy a, aim_xy b);
double aim_norm(aim_xy a);
aim_xy aim_unit(aim_xy a);

/// The image of p across the rail's contact line (where a ball's centre is when it touches it).
aim_xy aim_mirror(const aim_table *t, pool_rail rail, aim_xy p);

/// Where the straight path from a to b (b a mirror image) crosses the rail's contact line; false
/// when it does not, or not on a stretch of cushion (a pocket's mouth, within a ball of it).
bool aim_bounce(const aim_table *t, pool_rail rail, aim_xy a, aim_xy b, aim_xy *at);

/// Whether a ball of this radius moving from a to b touches none of the balls (count of them)
/// but those skipped (indices) and those pocketed or off the table.
bool aim_clear(const pool_ball_state *balls, int count, double radius, aim_xy a, aim_xy b, int skip1, int skip2);

// ---- a search ---------------------------------------------------------------------------------

/// One shot being considered: how it was meant, its strike, and what became of it.
typedef struct aim_candidate {
	pool_aim_kind kind;
	int ball, via;          ///< layout indices of the ball potted and the second ball (-1 none)
	pool_pocket pocket;
	pool_rail rail;
	int approach;           ///< which collision of the potted ball starts its way to the pocket (1 or 2)
	pool_strike strike;     ///< the first guess, then the refined strike
	double difficulty;      ///< geometric: lower is easier; the order candidates are refined in
	int state;              ///< AIM_* below
	aim_xy cue_final;       ///< without noise
	int position;
	long successes, samples;   ///< while ranking
	long report_successes, report_samples; ///< the fresh samples reported
} aim_candidate;

enum {
	AIM_PENDING = 0,  ///< not refined yet
	AIM_POTS = 1,     ///< refined: pots without noise
	AIM_MISSES = -1,  ///< refinement found no strike that pots
	AIM_BLOCKED = -2, ///< the cue stick cannot reach the ball (a ball or the rail in its way)
	AIM_SKIPPED = -3, ///< the time budget ran out before it was refined
	AIM_DUPLICATE = -4, ///< pots, but another candidate's refinement found the same strike
};

/// A worker thread's simulation.
typedef struct aim_worker {
	pool_sim *sim;
	pool_ball_state *states; ///< room for every ball
	long long simulations;
} aim_worker;

typedef struct aim_search {
	const pool_aim_def *def;
	aim_table table;
	int cue;                 ///< layout index of the cue ball
	aim_candidate *cands;
	int count, capacity;
	aim_worker *workers;
	int threads;
	double started;          ///< s, monotonic clock
	double refine_deadline;  ///< s, monotonic; INFINITY without a budget
	double deadline;
	atomic_bool out_of_time;
	atomic_int failure;      ///< a pool_result the library failed with, or 0
} aim_search;

/// s on a monotonic clock.
double aim_now(void);

/// Whether ball index i of the layout is the rules' legal first ball (any ball without rules).
bool aim_legal_first(const aim_search *s, int i);

/// Fills s->cands with every geometric candidate in the def's kinds, balls and pockets, each with
/// its first-guess strike, sorted by difficulty. Returns 0, or -1 when out of memory.
int aim_candidates(aim_search *s);

/// The elevation the cue needs to clear the rail and every ball for a strike at phi (radians,
/// at least theta_min), or a negative value when no elevation up to AIM_MAX_ELEVATION does.
double aim_cue_elevation(const aim_search *s, double phi, double a, double b, double theta_min);

/// Simulates the strike of candidate c (strike given) on the worker's simulation. Returns the
/// library's result (a refused strike is POOL_ERR_BAD_STRIKE).
pool_result aim_simulate(aim_search *s, aim_worker *w, const aim_candidate *c, const pool_strike *strike);

/// After aim_simulate: did the shot do what c means (the ball in its pocket, legally under the
/// rules, or without a scratch)?
bool aim_success(const aim_search *s, const aim_worker *w, const aim_candidate *c);

/// After aim_simulate: the signed distance (m) by which the potted ball's path passes the
/// pocket's aiming point, *short when it stops before getting there. False when the shot did not
/// start as c means (another ball hit first, no approaching collision).
bool aim_miss(const aim_search *s, const aim_worker *w, const aim_candidate *c, double *miss, bool *short_);

/// Refines candidate c: a root of the miss in phi (and more speed where it falls short), then
/// checked without noise. Sets c->state, c->strike, c->cue_final.
void aim_refine(aim_search *s, aim_worker *w, aim_candidate *c);

/// The cue ball's next shots from where it ends: balls with a clear straight pot (cut under
/// 60 degrees, both paths clear), legal under the rules.
int aim_position_score(const aim_search *s, const aim_candidate *c, const aim_worker *w);

/// Ranks the potting candidates under noise (more samples only where the top is undecided) and
/// estimates the best def->top of them afresh; fills order[] with their indices, best first.
/// Returns how many, or -1 when out of memory.
int aim_rank(aim_search *s, int *order);

/// The 95 % Wilson score interval of k successes in n, with continuity correction.
void aim_wilson(long k, long n, double *lo, double *hi);

/// Runs fn(s, worker, i) for i in [0, count) on s->threads threads (on fewer, down to the calling
/// thread alone, when threads cannot start).
typedef void (*aim_task)(aim_search *s, aim_worker *w, long i, void *ctx);
void aim_parallel(aim_search *s, long count, aim_task fn, void *ctx);

int aim_workers_create(aim_search *s);
void aim_workers_free(aim_search *s);

#endif
