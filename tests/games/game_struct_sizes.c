// Prints sizeof and offsetof of the games library's structures that libpool.game mirrors, as
// JSON (the format of tests/python/struct_sizes.c); test_game_python.py compares it with ctypes.
#include <stdio.h>

#include <pool/game.h>
#include <pool/noise.h>

#include "../python/struct_json.h"

int main(void) {
	printf("{");
	begin("pool_game_state", sizeof(pool_game_state));
	FIELD(pool_game_state, rules, 0); FIELD(pool_game_state, player, 0);
	FIELD(pool_game_state, break_shot, 0); FIELD(pool_game_state, cue_ball, 0);
	FIELD(pool_game_state, opponent_cue_ball, 0); FIELD(pool_game_state, group, 0);
	FIELD(pool_game_state, called_ball, 0); FIELD(pool_game_state, called_pocket, 0);
	FIELD(pool_game_state, safety, 0); FIELD(pool_game_state, push_out, 0);
	FIELD(pool_game_state, push_out_available, 0); FIELD(pool_game_state, ball_in_hand, 0);
	FIELD(pool_game_state, behind_head_string, 0); FIELD(pool_game_state, fouls, 0);
	FIELD(pool_game_state, opponent_fouls, 0); FIELD(pool_game_state, points, 0);
	FIELD(pool_game_state, opponent_points, 0); FIELD(pool_game_state, target_points, 1);
	begin("pool_game_shot", sizeof(pool_game_shot));
	FIELD(pool_game_shot, events, 0); FIELD(pool_game_shot, event_count, 0);
	FIELD(pool_game_shot, event_states, 0); FIELD(pool_game_shot, balls, 0);
	FIELD(pool_game_shot, ball_count, 1);
	begin("pool_game_result", sizeof(pool_game_result));
	FIELD(pool_game_result, legal, 0); FIELD(pool_game_result, fouls, 0);
	FIELD(pool_game_result, outcome, 0); FIELD(pool_game_result, reason, 0);
	FIELD(pool_game_result, ball_in_hand, 0); FIELD(pool_game_result, behind_head_string, 0);
	FIELD(pool_game_result, rerack_option, 0); FIELD(pool_game_result, pass_option, 0);
	FIELD(pool_game_result, points, 0); FIELD(pool_game_result, first_hit, 0);
	FIELD(pool_game_result, rails_after_contact, 0); FIELD(pool_game_result, cue_cushions, 0);
	FIELD(pool_game_result, pocketed_count, 0); FIELD(pool_game_result, pocketed, 0);
	FIELD(pool_game_result, pocketed_in, 0); FIELD(pool_game_result, off_table_count, 0);
	FIELD(pool_game_result, off_table, 0); FIELD(pool_game_result, spot_count, 0);
	FIELD(pool_game_result, spot, 0); FIELD(pool_game_result, next, 1);
	begin("pool_noise", sizeof(pool_noise));
	FIELD(pool_noise, speed, 0); FIELD(pool_noise, phi, 0); FIELD(pool_noise, theta, 0);
	FIELD(pool_noise, a, 0); FIELD(pool_noise, b, 1);
	printf("}\n");
	return 0;
}
