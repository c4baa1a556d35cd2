// Position play: where the cue ball ends without noise, and how many balls it then has a clear
// straight pot on (a cut under 60 degrees, the cue ball's and the ball's paths clear, a pocket
// that takes the ball's approach), counting only balls the rules let it hit next.
#include <math.h>

#include "aim_internal.h"

// The thinnest cut a next shot counts with: a comfortable pot, not merely a possible one.
#define AIM_POSITION_CUT_DEG 60.0

/// Whether ball index i may be the next shot's first ball once the shot is over (the rules'
/// state after it is approximated: 9-ball's lowest ball left, any ball otherwise).
static bool next_legal(const aim_search *s, const pool_ball_state *after, int i) {
	const pool_aim_def *d = s->def;
	if (!d->game || d->game->rules != POOL_GAME_9BALL)
		return true;
	int32_t lowest = INT32_MAX;
	for (int k = 0; k < d->ball_count; ++k)
		if (k != s->cue && after[k].motion != POOL_MOTION_POCKETED && after[k].motion != POOL_MOTION_OFF_TABLE &&
		    after[k].id < lowest)
			lowest = after[k].id;
	return after[i].id == lowest;
}

int aim_position_score(const aim_search *s, const aim_candidate *c, const aim_worker *w) {
	const pool_aim_def *d = s->def;
	const pool_ball_state *after = pool_sim_balls(w->sim);
	const double R = s->table.radius, limit = cos(AIM_POSITION_CUT_DEG * AIM_DEG);
	const aim_xy C = c->cue_final;
	int score = 0;
	for (int i = 0; i < d->ball_count; ++i) {
		const pool_motion m = after[i].motion;
		if (i == s->cue || m == POOL_MOTION_POCKETED || m == POOL_MOTION_OFF_TABLE || !next_legal(s, after, i))
			continue;
		const aim_xy O = {after[i].pos.x, after[i].pos.y};
		for (int p = 0; p < 6; ++p) {
			const aim_xy T = s->table.target[p], u = aim_unit(aim_sub(T, O)), G = aim_add_scaled(O, u, -2.0 * R);
			if (aim_dot(u, s->table.axis[p]) < s->table.accept[p] || aim_dot(aim_unit(aim_sub(G, C)), u) < limit)
				continue;
			if (aim_clear(after, d->ball_count, R, C, G, s->cue, i) && aim_clear(after, d->ball_count, R, O, T, i, -1)) {
				++score;
				break;
			}
		}
	}
	return score;
}
