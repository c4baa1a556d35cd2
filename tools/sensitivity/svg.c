// The study's picture, like the 2012 work's Fig. 3.9-3.11: the table seen from above (rails,
// cloth, pocket mouths as pool-plot draws them), the layout's balls where they start, and for
// each model set the cloud of the tracked balls' final positions, its mean (a cross) and its
// 95 % ellipse. Written directly as SVG text, so the C tool needs no plotting library.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "svg_table.h"

#define SVG_LEGEND_LINE 18.0 // px per legend line
#define SVG_POINT_RADIUS 1.6 // px

// A colour per model set and tracked ball (warm shades for the first set, cool for the second),
// cycling after four balls.
#define SVG_SHADES 4
static const char *const set_colours[SENS_MAX_SETS][SVG_SHADES] = {
	{"#ffd23f", "#ff9f1c", "#fff3b0", "#e76f51"},
	{"#4cc9f0", "#c77dff", "#b8f2e6", "#4361ee"}};

static const char *colour_of(int set, int k) { return set_colours[set][k % SVG_SHADES]; }

static void cloud(pool_svg *g, const sens_study *s, int set) {
	const sens_run *r = &s->runs[set];
	int t = s->tracked_count;
	for (int k = 0; k < t; ++k) {
		pool_svg_put(g, "<g fill=\"%s\" fill-opacity=\"0.55\">\n", colour_of(set, k));
		for (long i = 0; i < r->n; ++i) {
			int8_t state = r->state[i * t + k];
			if (r->stop[i] < 0 || state == POOL_MOTION_POCKETED || state == POOL_MOTION_OFF_TABLE)
				continue;
			pool_svg_put(g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.1f\"/>\n", pool_svg_x(r->pos[(i * t + k) * 2]),
			    pool_svg_y(g, r->pos[(i * t + k) * 2 + 1]), SVG_POINT_RADIUS);
		}
		pool_svg_put(g, "</g>\n");
	}
	for (int k = 0; k < t; ++k) {
		const sens_cloud *c = &s->clouds[set * t + k];
		const char *colour = colour_of(set, k);
		if (!c->has_mean)
			continue;
		double x = pool_svg_x(c->mean[0]), y = pool_svg_y(g, c->mean[1]), arm = 8.0;
		if (c->has_cov) // SVG's y points down: a counter-clockwise angle turns clockwise there
			pool_svg_put(g, "<ellipse cx=\"%.2f\" cy=\"%.2f\" rx=\"%.2f\" ry=\"%.2f\" transform=\"rotate(%.3f %.2f %.2f)\" "
			    "fill=\"none\" stroke=\"%s\" stroke-width=\"2.5\"/>\n", x, y, c->ellipse_major * POOL_SVG_SCALE,
			    c->ellipse_minor * POOL_SVG_SCALE, -c->ellipse_angle_deg, x, y, colour);
		pool_svg_put(g, "<path d=\"M%.2f %.2fL%.2f %.2fM%.2f %.2fL%.2f %.2f\" stroke=\"%s\" stroke-width=\"2.5\"/>\n",
		    x - arm, y - arm, x + arm, y + arm, x - arm, y + arm, x + arm, y - arm, colour);
	}
}

char *sens_svg(const sens_study *s) {
	const pool_table_def *t = &s->layout->def.table;
	pool_svg g = {.width = t->width};
	double w = pool_svg_table_width(t), h_table = pool_svg_table_height(t);
	int lines = 1 + s->set_count * s->tracked_count;
	double h = h_table + SVG_LEGEND_LINE * (lines + 1);
	pool_svg_begin(&g, w, h);
	pool_svg_table(&g, t, 0.0);
	double R = s->layout->def.params.ball_radius;
	for (int k = 0; k < s->layout->ball_count; ++k) { // where the balls start
		const pool_ball_state *b = &s->layout->balls[k];
		pool_svg_put(&g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"white\" fill-opacity=\"%s\" stroke=\"white\"/>\n",
		    pool_svg_x(b->pos.x), pool_svg_y(&g, b->pos.y), R * POOL_SVG_SCALE, b->id == s->nominal.ball ? "0.9" : "0.35");
	}
	for (int set = 0; set < s->set_count; ++set)
		cloud(&g, s, set);
	double y = h_table + SVG_LEGEND_LINE;
	const double *sd = s->noise.cue_sd;
	pool_svg_put(&g, "<text x=\"10\" y=\"%.1f\">", y);
	pool_svg_put_escaped(&g, s->scenario_path);
	pool_svg_put(&g, ": %ld samples, seed %lu; sd speed %.4g m/s, phi %.4g deg, theta %.4g deg, a %.4g m, "
	    "b %.4g m, positions %.4g m</text>\n", s->samples.n, s->seed, sd[SENS_SPEED], sd[SENS_PHI],
	    sd[SENS_THETA], sd[SENS_A], sd[SENS_B], s->noise.position_sd);
	for (int set = 0; set < s->set_count; ++set)
		for (int k = 0; k < s->tracked_count; ++k) {
			const sens_cloud *c = &s->clouds[set * s->tracked_count + k];
			y += SVG_LEGEND_LINE;
			pool_svg_put(&g, "<rect x=\"10\" y=\"%.1f\" width=\"12\" height=\"12\" fill=\"%s\" stroke=\"black\"/>", y - 11,
			    colour_of(set, k));
			pool_svg_put(&g, "<text x=\"28\" y=\"%.1f\">", y);
			pool_svg_put_escaped(&g, s->sets[set].name);
			pool_svg_put(&g, ", ball %d: %ld on the table", (int)c->id, c->on_table);
			if (c->has_mean)
				pool_svg_put(&g, ", mean (%.3f, %.3f) m", c->mean[0], c->mean[1]);
			if (c->has_cov)
				pool_svg_put(&g, ", 95%% ellipse %.3f x %.3f m", c->ellipse_major, c->ellipse_minor);
			pool_svg_put(&g, ", pocketed %.3f [%.3f, %.3f]", c->pocketed.p, c->pocketed.low, c->pocketed.high);
			if (set == 1 && isfinite(sens_mean_distance(s, k)))
				pool_svg_put(&g, ", means %.4f m apart", sens_mean_distance(s, k));
			pool_svg_put(&g, "</text>\n");
		}
	return pool_svg_end(&g);
}
