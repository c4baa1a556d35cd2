// The study's picture, like the 2012 work's Fig. 3.9-3.11: the table seen from above (rails,
// cloth, pocket mouths as pool-plot draws them), the layout's balls where they start, and for
// each model set the cloud of the tracked balls' final positions, its mean (a cross) and its
// 95 % ellipse. Written directly as SVG text, so the C tool needs no plotting library.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"
#include "text_buffer.h"

#define SVG_SCALE 400.0   // px per metre
#define SVG_RAIL 0.10     // m, drawn only (pool-plot's RAIL_WIDTH); the physics uses the noses
#define SVG_MARGIN 0.02   // m around the rails
#define SVG_LEGEND_LINE 18.0 // px per legend line
#define SVG_POINT_RADIUS 1.6 // px

// A colour per model set and tracked ball (warm shades for the first set, cool for the second),
// cycling after four balls.
#define SVG_SHADES 4
static const char *const set_colours[SENS_MAX_SETS][SVG_SHADES] = {
	{"#ffd23f", "#ff9f1c", "#fff3b0", "#e76f51"},
	{"#4cc9f0", "#c77dff", "#b8f2e6", "#4361ee"}};

static const char *colour_of(int set, int k) { return set_colours[set][k % SVG_SHADES]; }

typedef struct svg {
	pool_text_buffer b;
	double width; ///< table width (m), to flip y
} svg;

static void put(svg *g, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void put(svg *g, const char *format, ...) {
	char line[1024];
	va_list args;
	va_start(args, format);
	int n = vsnprintf(line, sizeof line, format, args);
	va_end(args);
	if (n > 0)
		pool_text_append(&g->b, line, (size_t)n < sizeof line ? (size_t)n : sizeof line - 1);
}

static double px(double x) { return (x + SVG_RAIL + SVG_MARGIN) * SVG_SCALE; }
static double py(const svg *g, double y) { return (g->width - y + SVG_RAIL + SVG_MARGIN) * SVG_SCALE; }

/// Text with XML's five special characters escaped.
static void put_escaped(svg *g, const char *text) {
	for (const char *p = text; *p; ++p) {
		switch (*p) {
		case '<': put(g, "&lt;"); break;
		case '>': put(g, "&gt;"); break;
		case '&': put(g, "&amp;"); break;
		case '"': put(g, "&quot;"); break;
		case '\'': put(g, "&apos;"); break;
		default: pool_text_append(&g->b, p, 1);
		}
	}
}

static void table(svg *g, const pool_table_def *t) {
	double L = t->length, W = t->width, rw = SVG_RAIL;
	put(g, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#5b3a1e\"/>\n", px(-rw),
	    py(g, W + rw), (L + 2 * rw) * SVG_SCALE, (W + 2 * rw) * SVG_SCALE);
	put(g, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#1d7a46\"/>\n", px(0),
	    py(g, W), L * SVG_SCALE, W * SVG_SCALE);
	// Pocket mouths (docs/physics.md): a corner mouth opens the last corner_mouth/sqrt(2) of each of
	// its rail lines, a side mouth the side_mouth-wide interval centred at x = L/2.
	double c = t->corner_mouth / sqrt(2.0), s = t->side_mouth;
	const char *mouth = "stroke=\"black\" stroke-width=\"4\"";
	for (int k = 0; k < 4; ++k) {
		double cx = k & 1 ? L : 0.0, cy = k & 2 ? W : 0.0;
		double sx = cx == 0.0 ? 1.0 : -1.0, sy = cy == 0.0 ? 1.0 : -1.0;
		put(g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"black\"/>\n", px(cx - sx * c * 0.25),
		    py(g, cy - sy * c * 0.25), c * 0.75 * SVG_SCALE);
		put(g, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", px(cx), py(g, cy),
		    px(cx + sx * c), py(g, cy), mouth);
		put(g, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", px(cx), py(g, cy), px(cx),
		    py(g, cy + sy * c), mouth);
	}
	for (int k = 0; k < 2; ++k) {
		double y = k ? W : 0.0, sy = k ? 1.0 : -1.0;
		put(g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"black\"/>\n", px(L / 2),
		    py(g, y + sy * s * 0.3), s / 2 * SVG_SCALE);
		put(g, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", px(L / 2 - s / 2), py(g, y),
		    px(L / 2 + s / 2), py(g, y), mouth);
	}
}

static void cloud(svg *g, const sens_study *s, int set) {
	const sens_run *r = &s->runs[set];
	int t = s->tracked_count;
	for (int k = 0; k < t; ++k) {
		put(g, "<g fill=\"%s\" fill-opacity=\"0.55\">\n", colour_of(set, k));
		for (long i = 0; i < r->n; ++i) {
			int8_t state = r->state[i * t + k];
			if (r->stop[i] < 0 || state == POOL_MOTION_POCKETED || state == POOL_MOTION_OFF_TABLE)
				continue;
			put(g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.1f\"/>\n", px(r->pos[(i * t + k) * 2]),
			    py(g, r->pos[(i * t + k) * 2 + 1]), SVG_POINT_RADIUS);
		}
		put(g, "</g>\n");
	}
	for (int k = 0; k < t; ++k) {
		const sens_cloud *c = &s->clouds[set * t + k];
		const char *colour = colour_of(set, k);
		if (!c->has_mean)
			continue;
		double x = px(c->mean[0]), y = py(g, c->mean[1]), arm = 8.0;
		if (c->has_cov) // SVG's y points down: a counter-clockwise angle turns clockwise there
			put(g, "<ellipse cx=\"%.2f\" cy=\"%.2f\" rx=\"%.2f\" ry=\"%.2f\" transform=\"rotate(%.3f %.2f %.2f)\" "
			    "fill=\"none\" stroke=\"%s\" stroke-width=\"2.5\"/>\n", x, y, c->ellipse_major * SVG_SCALE,
			    c->ellipse_minor * SVG_SCALE, -c->ellipse_angle_deg, x, y, colour);
		put(g, "<path d=\"M%.2f %.2fL%.2f %.2fM%.2f %.2fL%.2f %.2f\" stroke=\"%s\" stroke-width=\"2.5\"/>\n",
		    x - arm, y - arm, x + arm, y + arm, x - arm, y + arm, x + arm, y - arm, colour);
	}
}

char *sens_svg(const sens_study *s) {
	const pool_table_def *t = &s->layout->def.table;
	svg g = {.width = t->width};
	double w = (t->length + 2 * (SVG_RAIL + SVG_MARGIN)) * SVG_SCALE;
	double h_table = (t->width + 2 * (SVG_RAIL + SVG_MARGIN)) * SVG_SCALE;
	int lines = 1 + s->set_count * s->tracked_count;
	double h = h_table + SVG_LEGEND_LINE * (lines + 1);
	put(&g, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
	put(&g, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
	    "font-family=\"sans-serif\" font-size=\"13\">\n", w, h, w, h);
	put(&g, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
	table(&g, t);
	double R = s->layout->def.params.ball_radius;
	for (int k = 0; k < s->layout->ball_count; ++k) { // where the balls start
		const pool_ball_state *b = &s->layout->balls[k];
		put(&g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"white\" fill-opacity=\"%s\" stroke=\"white\"/>\n",
		    px(b->pos.x), py(&g, b->pos.y), R * SVG_SCALE, b->id == s->nominal.ball ? "0.9" : "0.35");
	}
	for (int set = 0; set < s->set_count; ++set)
		cloud(&g, s, set);
	double y = h_table + SVG_LEGEND_LINE;
	const double *sd = s->noise.cue_sd;
	put(&g, "<text x=\"10\" y=\"%.1f\">", y);
	put_escaped(&g, s->scenario_path);
	put(&g, ": %ld samples, seed %lu; sd speed %.4g m/s, phi %.4g deg, theta %.4g deg, a %.4g m, "
	    "b %.4g m, positions %.4g m</text>\n", s->samples.n, s->seed, sd[SENS_SPEED], sd[SENS_PHI],
	    sd[SENS_THETA], sd[SENS_A], sd[SENS_B], s->noise.position_sd);
	for (int set = 0; set < s->set_count; ++set)
		for (int k = 0; k < s->tracked_count; ++k) {
			const sens_cloud *c = &s->clouds[set * s->tracked_count + k];
			y += SVG_LEGEND_LINE;
			put(&g, "<rect x=\"10\" y=\"%.1f\" width=\"12\" height=\"12\" fill=\"%s\" stroke=\"black\"/>", y - 11,
			    colour_of(set, k));
			put(&g, "<text x=\"28\" y=\"%.1f\">", y);
			put_escaped(&g, s->sets[set].name);
			put(&g, ", ball %d: %ld on the table", (int)c->id, c->on_table);
			if (c->has_mean)
				put(&g, ", mean (%.3f, %.3f) m", c->mean[0], c->mean[1]);
			if (c->has_cov)
				put(&g, ", 95%% ellipse %.3f x %.3f m", c->ellipse_major, c->ellipse_minor);
			put(&g, ", pocketed %.3f [%.3f, %.3f]", c->pocketed.p, c->pocketed.low, c->pocketed.high);
			if (set == 1 && isfinite(sens_mean_distance(s, k)))
				put(&g, ", means %.4f m apart", sens_mean_distance(s, k));
			put(&g, "</text>\n");
		}
	put(&g, "</svg>\n");
	if (g.b.failed) {
		free(g.b.data);
		return NULL;
	}
	return g.b.data;
}
