// The libpool-result/1 writer (docs/interfaces.md): events with the after-states of their balls,
// every ball at the end, statistics, and optionally the trajectories sampled for plots.
#include "game_json.h"
#include "json_writer.h"
#include "models_json.h"
#include "pool/scenario.h"
#include "result_setup.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

// Sampling beyond this many grid instants would make files nobody can plot; dt is widened.
#define POOL_RESULT_MAX_SAMPLES 20000

static void write_state(pool_jw *w, const pool_ball_state *b) {
	pool_jw_object(w, true);
	pool_jw_key(w, "id");
	pool_jw_int(w, b->id);
	pool_jw_key(w, "pos");
	pool_jw_vec3(w, b->pos);
	pool_jw_key(w, "vel");
	pool_jw_vec3(w, b->vel);
	pool_jw_key(w, "omega");
	pool_jw_vec3(w, b->omega);
	pool_jw_key(w, "state");
	pool_jw_string(w, pool_motion_name(b->motion));
	pool_jw_end(w, '}');
}

// The parameters of the closed forms (docs/physics.md), by their scenario names.
static void write_params(pool_jw *w, const pool_params *p) {
	const struct {
		const char *name;
		double value;
	} fields[] = {
		{"g", p->g},
		{"mu_slide", p->mu_slide},
		{"mu_roll", p->mu_roll},
		{"mu_spin", p->mu_spin},
		{"mu_ball", p->mu_ball},
		{"e_ball", p->e_ball},
		{"mu_cushion", p->mu_cushion},
		{"e_cushion", p->e_cushion},
		{"mu_table", p->mu_table},
		{"e_table", p->e_table},
		{"ball_radius", p->ball_radius},
		{"ball_mass", p->ball_mass},
		{"cue_mass", p->cue_mass},
		{"throw_a", p->throw_a},
		{"throw_b", p->throw_b},
		{"throw_c", p->throw_c},
		{"cue_end_mass", p->cue_end_mass},
		{"e_cushion_mathavan", p->e_cushion_mathavan},
		{"mu_cushion_mathavan", p->mu_cushion_mathavan},
	};
	pool_jw_key(w, "params");
	pool_jw_object(w, true);
	for (size_t i = 0; i < sizeof fields / sizeof fields[0]; ++i) {
		pool_jw_key(w, fields[i].name);
		pool_jw_number(w, fields[i].value);
	}
	pool_jw_end(w, '}');
}

static void write_events(pool_jw *w, const pool_sim *sim, const pool_event *events, int count) {
	pool_jw_key(w, "events");
	pool_jw_array(w, false);
	for (int i = 0; i < count; ++i) {
		const pool_event *ev = &events[i];
		const pool_ball_state *after = pool_sim_event_states(sim, ev);
		pool_jw_object(w, false);
		pool_jw_key(w, "t");
		pool_jw_number(w, ev->time);
		pool_jw_key(w, "type");
		pool_jw_string(w, pool_event_type_name(ev->type));
		pool_jw_key(w, "balls");
		pool_jw_array(w, true);
		for (int k = 0; k < ev->ball_count; ++k)
			pool_jw_int(w, after[k].id);
		pool_jw_end(w, ']');
		if (ev->rail != POOL_RAIL_NONE && pool_rail_name(ev->rail)) {
			pool_jw_key(w, "rail");
			pool_jw_string(w, pool_rail_name(ev->rail));
		}
		if (ev->part != POOL_PART_NONE && pool_cushion_part_name(ev->part)) {
			pool_jw_key(w, "part");
			pool_jw_string(w, pool_cushion_part_name(ev->part));
		}
		if (ev->pocket != POOL_POCKET_NONE && pool_pocket_name(ev->pocket)) {
			pool_jw_key(w, "pocket");
			pool_jw_string(w, pool_pocket_name(ev->pocket));
		}
		pool_jw_key(w, "after");
		pool_jw_array(w, false);
		for (int k = 0; k < ev->ball_count; ++k)
			write_state(w, &after[k]);
		pool_jw_end(w, ']');
		pool_jw_end(w, '}');
	}
	pool_jw_end(w, ']');
}

static void write_stats(pool_jw *w, const pool_sim *sim, const pool_event *events, int count,
                        const pool_ball_state *final_states, int ball_count, double end) {
	pool_jw_key(w, "stats");
	pool_jw_object(w, false);
	pool_jw_key(w, "events");
	pool_jw_int(w, count);
	pool_jw_key(w, "sim_time");
	pool_jw_number(w, pool_sim_time(sim));
	pool_jw_key(w, "end_time"); // time of "final": sim_time, or max_time when cut there
	pool_jw_number(w, end);
	pool_jw_key(w, "stop_reason");
	pool_jw_string(w, pool_stop_reason_name(pool_sim_stop_reason(sim)));
	pool_jw_key(w, "balls");
	pool_jw_int(w, ball_count);
	// Counts per event type, in the enumeration's order so the output is deterministic.
	int per_type[POOL_EVENT_LINK_END + 1] = {0};
	for (int i = 0; i < count; ++i)
		if ((int)events[i].type >= 0 && events[i].type <= POOL_EVENT_LINK_END)
			per_type[events[i].type]++;
	pool_jw_key(w, "event_counts");
	pool_jw_object(w, true);
	for (int t = 0; t <= POOL_EVENT_LINK_END; ++t) {
		if (per_type[t] == 0)
			continue;
		pool_jw_key(w, pool_event_type_name((pool_event_type)t));
		pool_jw_int(w, per_type[t]);
	}
	pool_jw_end(w, '}');
	pool_jw_key(w, "pocketed");
	pool_jw_array(w, true);
	for (int i = 0; i < ball_count; ++i)
		if (final_states && final_states[i].motion == POOL_MOTION_POCKETED)
			pool_jw_int(w, final_states[i].id);
	pool_jw_end(w, ']');
	pool_jw_key(w, "off_table");
	pool_jw_array(w, true);
	for (int i = 0; i < ball_count; ++i)
		if (final_states && final_states[i].motion == POOL_MOTION_OFF_TABLE)
			pool_jw_int(w, final_states[i].id);
	pool_jw_end(w, ']');
	pool_jw_end(w, '}');
}

static int compare_double(const void *a, const void *b) {
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

static bool gone(pool_motion m) { return m == POOL_MOTION_POCKETED || m == POOL_MOTION_OFF_TABLE; }

// Sampled trajectories: a grid every dt plus every event time (so polylines are exact at the
// corners), per ball, dropping the inside of runs where the ball does not move, and ending at
// the sample where the ball leaves play.
static bool write_samples(pool_jw *w, const pool_sim *sim, const pool_event *events, int count,
                          double dt, double end) {
	int balls = pool_sim_ball_count(sim);
	double steps = floor(end / dt);
	if (steps > POOL_RESULT_MAX_SAMPLES) {
		dt = end / POOL_RESULT_MAX_SAMPLES;
		steps = POOL_RESULT_MAX_SAMPLES;
	}
	size_t grid = (size_t)steps + 1;
	size_t capacity = grid + (size_t)count + 1;
	double *times = malloc(capacity * sizeof *times);
	if (!times)
		return false;
	size_t n = 0;
	// With a whole number of samples per second (dt = 0.01...), k / rate is the correctly
	// rounded k dt (1.63, not 1.6300000000000001).
	double rate = 1.0 / dt;
	bool whole_rate = rate == floor(rate) && rate < 1e15;
	for (size_t k = 0; k < grid; ++k) {
		double t = whole_rate ? (double)k / rate : (double)k * dt;
		if (t <= end)
			times[n++] = t;
	}
	for (int i = 0; i < count; ++i)
		if (events[i].time >= 0.0 && events[i].time <= end)
			times[n++] = events[i].time;
	times[n++] = end;
	qsort(times, n, sizeof *times, compare_double);
	size_t unique = 0;
	for (size_t i = 0; i < n; ++i)
		if (unique == 0 || times[i] != times[unique - 1])
			times[unique++] = times[i];
	n = unique;

	pool_ball_state *states = malloc(n * (size_t)balls * sizeof *states);
	if (!states) {
		free(times);
		return false;
	}
	for (size_t k = 0; k < n; ++k) {
		if (pool_sim_state_at(sim, times[k], states + k * (size_t)balls) != POOL_OK) {
			free(states);
			free(times);
			return false;
		}
	}

	pool_jw_key(w, "samples");
	pool_jw_object(w, false);
	pool_jw_key(w, "dt");
	pool_jw_number(w, dt);
	pool_jw_key(w, "balls");
	pool_jw_array(w, false);
	for (int b = 0; b < balls; ++b) {
		// Pick the samples to keep, then write times and positions from the same list.
		size_t last = n - 1;
		for (size_t k = 0; k < n; ++k)
			if (gone(states[k * (size_t)balls + (size_t)b].motion)) {
				last = k;
				break;
			}
		pool_jw_object(w, false);
		pool_jw_key(w, "id");
		pool_jw_int(w, states[b].id);
		for (int pass = 0; pass < 2; ++pass) {
			pool_jw_key(w, pass == 0 ? "t" : "pos");
			pool_jw_array(w, pass == 0);
			for (size_t k = 0; k <= last; ++k) {
				const pool_ball_state *s = &states[k * (size_t)balls + (size_t)b];
				if (k > 0 && k < last) {
					const pool_ball_state *prev = s - balls, *next = s + balls;
					bool same_prev = prev->motion == s->motion && memcmp(&prev->pos, &s->pos, sizeof s->pos) == 0;
					bool same_next = next->motion == s->motion && memcmp(&next->pos, &s->pos, sizeof s->pos) == 0;
					if (same_prev && same_next)
						continue;
				}
				if (pass == 0)
					pool_jw_number(w, times[k]);
				else
					pool_jw_vec3(w, s->pos);
			}
			pool_jw_end(w, ']');
		}
		pool_jw_end(w, '}');
	}
	pool_jw_end(w, ']');
	pool_jw_end(w, '}');
	free(states);
	free(times);
	return true;
}

// The shot's setup as the result writes it: "table" (its pocket model and, with "jaws", its
// geometry, cut angles in degrees), "ball_radius", "params" and "models".
void pool_jw_sim_setup(pool_jw *w, const pool_sim_def *def) {
	const pool_table_def *t = &def->table;
	pool_jw_key(w, "table");
	pool_jw_object(w, true);
	pool_jw_key(w, "length");
	pool_jw_number(w, t->length);
	pool_jw_key(w, "width");
	pool_jw_number(w, t->width);
	pool_jw_key(w, "cushion_height");
	pool_jw_number(w, t->cushion_height);
	pool_jw_key(w, "corner_mouth");
	pool_jw_number(w, t->corner_mouth);
	pool_jw_key(w, "side_mouth");
	pool_jw_number(w, t->side_mouth);
	pool_jw_key(w, "pockets");
	pool_jw_string(w, pool_pockets_model_name(t->pockets));
	if (t->pockets == POOL_POCKETS_JAWS) {
		// The nose curve's geometry, as the scenario names it (angles in degrees).
		const struct {
			const char *name;
			double value;
		} jaws[] = {
			{"corner_cut_angle", t->corner_cut_angle * 180.0 / 3.14159265358979323846},
			{"side_cut_angle", t->side_cut_angle * 180.0 / 3.14159265358979323846},
			{"corner_jaw_radius", t->corner_jaw_radius}, {"side_jaw_radius", t->side_jaw_radius},
			{"corner_shelf", t->corner_shelf}, {"side_shelf", t->side_shelf},
			{"corner_hole_radius", t->corner_hole_radius}, {"side_hole_radius", t->side_hole_radius},
		};
		for (size_t k = 0; k < sizeof jaws / sizeof jaws[0]; ++k) {
			pool_jw_key(w, jaws[k].name);
			pool_jw_number(w, jaws[k].value);
		}
	}
	pool_jw_end(w, '}');
	pool_jw_key(w, "ball_radius");
	pool_jw_number(w, def->params.ball_radius);
	write_params(w, &def->params);
	// Always: a result says which laws made it, whatever a reader's defaults are.
	pool_jw_models(w, &def->models);
}

char *pool_result_json(const pool_sim *sim, const pool_result_options *options) {
	pool_result_options defaults = {0};
	if (!options)
		options = &defaults;
	pool_jw w;
	pool_jw_init(&w, options->pretty);
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	int balls = pool_sim_ball_count(sim);
	// "final" is every ball at rest, or at max_time when the shot was cut there (docs/interfaces.md).
	double end = pool_sim_end_time(sim);
	pool_ball_state *final_states = calloc(balls > 0 ? (size_t)balls : 1, sizeof *final_states);
	if (!final_states)
		return NULL;
	if (balls > 0 && pool_sim_state_at(sim, end, final_states) != POOL_OK) {
		free(final_states);
		return NULL;
	}

	pool_jw_object(&w, false);
	pool_jw_key(&w, "format");
	pool_jw_string(&w, "libpool-result/1");
	if (options->def)
		pool_jw_sim_setup(&w, options->def);
	// Every ball at t = 0: with the events' after-states, the start of each closed-form segment
	// (docs/interfaces.md), from which a reader (pool-view) evaluates any instant exactly.
	if (balls > 0 && pool_sim_state_at(sim, 0.0, final_states) != POOL_OK) {
		pool_jw_discard(&w);
		free(final_states);
		return NULL;
	}
	pool_jw_key(&w, "initial");
	pool_jw_array(&w, false);
	for (int i = 0; i < balls; ++i)
		write_state(&w, &final_states[i]);
	pool_jw_end(&w, ']');
	write_events(&w, sim, events, count);
	if (balls > 0 && pool_sim_state_at(sim, end, final_states) != POOL_OK) {
		pool_jw_discard(&w);
		free(final_states);
		return NULL;
	}
	pool_jw_key(&w, "final");
	pool_jw_array(&w, false);
	for (int i = 0; i < balls; ++i)
		write_state(&w, &final_states[i]);
	pool_jw_end(&w, ']');
	write_stats(&w, sim, events, count, final_states, balls, end);
	bool ok = true;
	if (options->game && options->def) {
		pool_game_shot shot = pool_game_shot_of_sim(sim);
		pool_game_result judged;
		ok = pool_game_judge(options->game, &shot, &options->def->table, &judged, NULL) == POOL_OK;
		if (ok) {
			pool_jw_key(&w, "game");
			pool_jw_game_result(&w, options->game->rules, &judged);
		}
	}
	if (ok && options->sample_dt > 0.0 && isfinite(options->sample_dt) && balls > 0)
		ok = write_samples(&w, sim, events, count, options->sample_dt, end);
	pool_jw_end(&w, '}');
	free(final_states);
	if (!ok) {
		pool_jw_discard(&w);
		return NULL;
	}
	return pool_jw_finish(&w);
}

void pool_scenario_text_free(char *text) { free(text); }
