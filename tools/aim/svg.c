// The ranked shots drawn on the table: the position's balls, and for each shot (best first) the
// cue ball's path (dashed) and the potted ball's (solid) as simulated without noise, in the
// shot's colour, numbered, with a legend line giving kind, ball, pocket and p_success.
#include <math.h>
#include <stdlib.h>

#include "aim_tool.h"
#include "svg_table.h"

#define AIM_SVG_LINE 18.0
#define AIM_SVG_DT 0.01   // s between drawn points
#define AIM_SVG_SHOTS 5   // drawn at most
static const char *const shot_colours[AIM_SVG_SHOTS] = {"#ffd23f", "#4cc9f0", "#ff6b6b", "#c77dff", "#80ed99"};

/// A ball's path from the start of the shot until it rests or drops.
static void path(pool_svg *g, pool_sim *sim, pool_ball_state *states, int index, const char *colour, bool dashed) {
	double end = pool_sim_end_time(sim);
	pool_svg_put(g, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%s\"%s points=\"", colour, dashed ? "2" : "3",
	             dashed ? " stroke-dasharray=\"7 5\"" : "");
	for (double t = 0.0;; t += AIM_SVG_DT) {
		if (t > end)
			t = end;
		if (pool_sim_state_at(sim, t, states) != POOL_OK)
			break;
		pool_svg_put(g, "%.1f,%.1f ", pool_svg_x(states[index].pos.x), pool_svg_y(g, states[index].pos.y));
		pool_motion m = states[index].motion;
		if (t == end || m == POOL_MOTION_POCKETED || m == POOL_MOTION_OFF_TABLE)
			break;
	}
	pool_svg_put(g, "\"/>\n");
}

char *aim_svg(const pool_aim_def *def, const pool_aim_shot *shots, int count) {
	const pool_table_def *t = &def->sim.table;
	const double R = def->sim.params.ball_radius;
	int drawn = count < AIM_SVG_SHOTS ? count : AIM_SVG_SHOTS;
	pool_svg g = {0};
	double h_table = pool_svg_table_height(t);
	pool_svg_begin(&g, pool_svg_table_width(t), h_table + AIM_SVG_LINE * (drawn + 1.5));
	pool_svg_table(&g, t, 0.0);
	pool_sim *sim = NULL;
	pool_ball_state *states = calloc((size_t)def->ball_count, sizeof *states);
	int cue = 0;
	for (int k = 0; k < def->ball_count; ++k)
		if (def->balls[k].id == def->cue_ball)
			cue = k;
	for (int k = drawn - 1; states && k >= 0; --k) { // the best drawn last, on top
		pool_error e;
		pool_result r = sim ? pool_sim_reset(sim, &def->sim, &e) : pool_sim_create(&def->sim, &sim, &e);
		for (int b = 0; r == POOL_OK && b < def->ball_count; ++b)
			r = pool_sim_add_ball(sim, &def->balls[b], &e);
		if (r == POOL_OK)
			r = pool_sim_strike(sim, def->cue_ball, &shots[k].strike, &e);
		if (r == POOL_OK)
			r = pool_sim_run(sim);
		if (r != POOL_OK)
			continue;
		for (int b = 0; b < def->ball_count; ++b)
			if (b == cue || def->balls[b].id == shots[k].ball || def->balls[b].id == shots[k].via)
				path(&g, sim, states, b, shot_colours[k], b == cue);
	}
	for (int b = 0; b < def->ball_count; ++b) { // the balls where they stand, with their ids
		const pool_ball_state *ball = &def->balls[b];
		double x = pool_svg_x(ball->pos.x), y = pool_svg_y(&g, ball->pos.y);
		pool_svg_put(&g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\" stroke=\"black\" stroke-width=\"1\"/>\n",
		             x, y, R * POOL_SVG_SCALE, pool_svg_ball_colour(ball->id));
		if (b != cue)
			pool_svg_put(&g, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\" font-size=\"11\" fill=\"%s\">%d</text>\n",
			             x, y + 4.0, ball->id == 2 || ball->id == 4 || ball->id == 7 || ball->id == 8 ? "white" : "black", (int)ball->id);
	}
	for (int k = 0; k < drawn; ++k) {
		const pool_aim_shot *s = &shots[k];
		double y = h_table + AIM_SVG_LINE * (k + 1);
		pool_svg_put(&g, "<rect x=\"10\" y=\"%.1f\" width=\"24\" height=\"5\" fill=\"%s\"/>", y - 7, shot_colours[k]);
		pool_svg_put(&g, "<text x=\"42\" y=\"%.1f\">%d. %s: ball %d into %s, p_success %.3f [%.3f, %.3f] of %d; speed "
		             "%.2f m/s, phi %.2f deg, b %.1f mm</text>\n", y, k + 1, pool_aim_kind_name(s->kind), (int)s->ball,
		             pool_pocket_name(s->pocket), s->p_success, s->ci_low, s->ci_high, s->samples, s->strike.speed,
		             s->strike.phi * 180.0 / 3.14159265358979323846, 1e3 * s->strike.b);
	}
	if (drawn == 0)
		pool_svg_put(&g, "<text x=\"10\" y=\"%.1f\">no shot found</text>\n", h_table + AIM_SVG_LINE);
	pool_sim_destroy(sim);
	free(states);
	return pool_svg_end(&g);
}
