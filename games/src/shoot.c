// One shot of a game in one call (pool_game_shoot): set up, strike, run, judge, final states.
#include "pool/game.h"

#include "rules.h"

pool_result pool_game_shoot(pool_sim *sim, const pool_sim_def *def, const pool_ball_state *balls, int count,
                            const pool_strike *strike, const pool_game_state *state, pool_game_result *result,
                            pool_ball_state *final, pool_error *error) {
	if (!sim || !def || !strike || !state || !result || (count > 0 && (!balls || !final)) || count < 0)
		return pool_game_fail(error, POOL_ERR_INVALID_ARGUMENT, "pool_game_shoot: missing argument");
	pool_result r = pool_sim_reset(sim, def, error);
	for (int i = 0; r == POOL_OK && i < count; ++i)
		r = pool_sim_add_ball(sim, &balls[i], error);
	if (r == POOL_OK)
		r = pool_sim_strike(sim, state->cue_ball, strike, error);
	if (r == POOL_OK && (r = pool_sim_run(sim)) != POOL_OK) // (what the run met: pool_sim_last_error)
		return pool_game_fail(error, r, "%s", pool_sim_last_error(sim)[0] ? pool_sim_last_error(sim) : pool_result_str(r));
	if (r != POOL_OK)
		return error && !error->message[0] ? pool_game_fail(error, r, "%s", pool_result_str(r)) : r;
	const pool_game_shot shot = pool_game_shot_of_sim(sim);
	pool_game_result judged;
	if ((r = pool_game_judge(state, &shot, &def->table, &judged, error)) != POOL_OK)
		return r;
	if (count > 0 && (r = pool_sim_state_at(sim, pool_sim_end_time(sim), final)) != POOL_OK)
		return pool_game_fail(error, r, "%s", pool_result_str(r));
	*result = judged;
	return POOL_OK;
}
