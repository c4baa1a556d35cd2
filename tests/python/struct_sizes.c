// Prints sizeof and offsetof of every public structure the Python binding mirrors, as JSON:
// {"pool_vec3": {"size": 24, "fields": {"x": 0, ...}}, ...}. test_binding.py compares it with
// ctypes, so a change to a header that the mirror misses (or the reverse) fails the tests.
#include <stdio.h>

#include <pool/pool.h>

#include "struct_json.h"

int main(void) {
	printf("{");
	begin("pool_vec3", sizeof(pool_vec3));
	FIELD(pool_vec3, x, 0); FIELD(pool_vec3, y, 0); FIELD(pool_vec3, z, 1);
	begin("pool_table_def", sizeof(pool_table_def));
	FIELD(pool_table_def, length, 0); FIELD(pool_table_def, width, 0);
	FIELD(pool_table_def, cushion_height, 0); FIELD(pool_table_def, corner_mouth, 0);
	FIELD(pool_table_def, side_mouth, 0); FIELD(pool_table_def, pockets, 0);
	FIELD(pool_table_def, corner_cut_angle, 0); FIELD(pool_table_def, side_cut_angle, 0);
	FIELD(pool_table_def, corner_jaw_radius, 0); FIELD(pool_table_def, side_jaw_radius, 0);
	FIELD(pool_table_def, corner_shelf, 0); FIELD(pool_table_def, side_shelf, 0);
	FIELD(pool_table_def, corner_hole_radius, 0); FIELD(pool_table_def, side_hole_radius, 1);
	begin("pool_params", sizeof(pool_params));
	FIELD(pool_params, g, 0); FIELD(pool_params, mu_slide, 0); FIELD(pool_params, mu_roll, 0);
	FIELD(pool_params, mu_spin, 0); FIELD(pool_params, mu_ball, 0); FIELD(pool_params, e_ball, 0);
	FIELD(pool_params, mu_cushion, 0); FIELD(pool_params, e_cushion, 0);
	FIELD(pool_params, mu_table, 0); FIELD(pool_params, e_table, 0);
	FIELD(pool_params, ball_radius, 0); FIELD(pool_params, ball_mass, 0);
	FIELD(pool_params, cue_mass, 0); FIELD(pool_params, throw_a, 0); FIELD(pool_params, throw_b, 0);
	FIELD(pool_params, throw_c, 0); FIELD(pool_params, cue_end_mass, 0);
	FIELD(pool_params, e_cushion_mathavan, 0); FIELD(pool_params, mu_cushion_mathavan, 1);
	begin("pool_ball_state", sizeof(pool_ball_state));
	FIELD(pool_ball_state, id, 0); FIELD(pool_ball_state, motion, 0); FIELD(pool_ball_state, pos, 0);
	FIELD(pool_ball_state, vel, 0); FIELD(pool_ball_state, omega, 1);
	begin("pool_strike", sizeof(pool_strike));
	FIELD(pool_strike, speed, 0); FIELD(pool_strike, phi, 0); FIELD(pool_strike, theta, 0);
	FIELD(pool_strike, a, 0); FIELD(pool_strike, b, 1);
	begin("pool_event", sizeof(pool_event));
	FIELD(pool_event, time, 0); FIELD(pool_event, type, 0); FIELD(pool_event, rail, 0);
	FIELD(pool_event, pocket, 0); FIELD(pool_event, ball_count, 0); FIELD(pool_event, first_state, 0);
	FIELD(pool_event, part, 1);
	begin("pool_allocator", sizeof(pool_allocator));
	FIELD(pool_allocator, alloc, 0); FIELD(pool_allocator, free, 0); FIELD(pool_allocator, context, 1);
	begin("pool_models", sizeof(pool_models));
	FIELD(pool_models, cushion, 0); FIELD(pool_models, ball_ball_friction, 0); FIELD(pool_models, squirt, 1);
	begin("pool_sim_def", sizeof(pool_sim_def));
	FIELD(pool_sim_def, table, 0); FIELD(pool_sim_def, params, 0); FIELD(pool_sim_def, airborne, 0);
	FIELD(pool_sim_def, max_time, 0); FIELD(pool_sim_def, max_events, 0);
	FIELD(pool_sim_def, allocator, 0); FIELD(pool_sim_def, models, 1);
	begin("pool_error", sizeof(pool_error));
	FIELD(pool_error, message, 1);
	// Enumerations travel as C int in the mirror: check that is their size.
	printf(", \"enum_sizes\": {\"pool_motion\": %zu, \"pool_event_type\": %zu, \"pool_rail\": %zu, "
	       "\"pool_pocket\": %zu, \"pool_result\": %zu, \"pool_stop_reason\": %zu, "
	       "\"pool_rack_kind\": %zu, \"pool_cushion_model\": %zu, \"pool_ball_friction_model\": %zu, "
	       "\"pool_squirt_model\": %zu, \"pool_pockets_model\": %zu, \"pool_cushion_part\": %zu}",
	       sizeof(pool_motion), sizeof(pool_event_type), sizeof(pool_rail), sizeof(pool_pocket),
	       sizeof(pool_result), sizeof(pool_stop_reason), sizeof(pool_rack_kind),
	       sizeof(pool_cushion_model), sizeof(pool_ball_friction_model), sizeof(pool_squirt_model),
	       sizeof(pool_pockets_model), sizeof(pool_cushion_part));
	printf("}\n");
	return 0;
}
