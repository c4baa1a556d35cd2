// The table seen from above as SVG text (svg_table.h).
#include "svg_table.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

void pool_svg_put(pool_svg *g, const char *format, ...) {
	va_list args;
	va_start(args, format);
	pool_text_vappendf(&g->b, format, args);
	va_end(args);
}

void pool_svg_put_escaped(pool_svg *g, const char *text) {
	for (const char *p = text; *p; ++p) {
		switch (*p) {
		case '<': pool_svg_put(g, "&lt;"); break;
		case '>': pool_svg_put(g, "&gt;"); break;
		case '&': pool_svg_put(g, "&amp;"); break;
		case '"': pool_svg_put(g, "&quot;"); break;
		case '\'': pool_svg_put(g, "&apos;"); break;
		default: pool_text_append(&g->b, p, 1);
		}
	}
}

double pool_svg_x(double x) { return (x + POOL_SVG_RAIL + POOL_SVG_MARGIN) * POOL_SVG_SCALE; }

double pool_svg_y(const pool_svg *g, double y) {
	return g->top + (g->width - y + POOL_SVG_RAIL + POOL_SVG_MARGIN) * POOL_SVG_SCALE;
}

double pool_svg_table_width(const pool_table_def *t) {
	return (t->length + 2 * (POOL_SVG_RAIL + POOL_SVG_MARGIN)) * POOL_SVG_SCALE;
}

double pool_svg_table_height(const pool_table_def *t) {
	return (t->width + 2 * (POOL_SVG_RAIL + POOL_SVG_MARGIN)) * POOL_SVG_SCALE;
}

void pool_svg_begin(pool_svg *g, double w, double h) {
	pool_svg_put(g, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
	pool_svg_put(g, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f %.0f\" "
	             "font-family=\"sans-serif\" font-size=\"13\">\n", w, h, w, h);
	pool_svg_put(g, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
}

void pool_svg_table(pool_svg *g, const pool_table_def *t, double top) {
	g->width = t->width;
	g->top = top;
	double L = t->length, W = t->width, rw = POOL_SVG_RAIL;
	pool_svg_put(g, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#5b3a1e\"/>\n",
	             pool_svg_x(-rw), pool_svg_y(g, W + rw), (L + 2 * rw) * POOL_SVG_SCALE, (W + 2 * rw) * POOL_SVG_SCALE);
	pool_svg_put(g, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"#1d7a46\"/>\n", pool_svg_x(0),
	             pool_svg_y(g, W), L * POOL_SVG_SCALE, W * POOL_SVG_SCALE);
	// Pocket mouths (docs/physics.md): a corner mouth opens the last corner_mouth/sqrt(2) of each of
	// its rail lines, a side mouth the side_mouth-wide interval centred at x = L/2.
	double c = t->corner_mouth / sqrt(2.0), s = t->side_mouth;
	const char *mouth = "stroke=\"black\" stroke-width=\"4\"";
	for (int k = 0; k < 4; ++k) {
		double cx = k & 1 ? L : 0.0, cy = k & 2 ? W : 0.0;
		double sx = cx == 0.0 ? 1.0 : -1.0, sy = cy == 0.0 ? 1.0 : -1.0;
		pool_svg_put(g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"black\"/>\n", pool_svg_x(cx - sx * c * 0.25),
		             pool_svg_y(g, cy - sy * c * 0.25), c * 0.75 * POOL_SVG_SCALE);
		pool_svg_put(g, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", pool_svg_x(cx),
		             pool_svg_y(g, cy), pool_svg_x(cx + sx * c), pool_svg_y(g, cy), mouth);
		pool_svg_put(g, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", pool_svg_x(cx),
		             pool_svg_y(g, cy), pool_svg_x(cx), pool_svg_y(g, cy + sy * c), mouth);
	}
	for (int k = 0; k < 2; ++k) {
		double y = k ? W : 0.0, sy = k ? 1.0 : -1.0;
		pool_svg_put(g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"black\"/>\n", pool_svg_x(L / 2),
		             pool_svg_y(g, y + sy * s * 0.3), s / 2 * POOL_SVG_SCALE);
		pool_svg_put(g, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", pool_svg_x(L / 2 - s / 2),
		             pool_svg_y(g, y), pool_svg_x(L / 2 + s / 2), pool_svg_y(g, y), mouth);
	}
}

const char *pool_svg_ball_colour(int id) {
	static const char *const balls[] = {"#ffffff", "#f2c500", "#1f4fd1", "#d62020", "#6a2c91",
	                                    "#f07c00", "#138a36", "#7a1f1f", "#111111"};
	static const char *const others[] = {"#17becf", "#bcbd22", "#8c564b", "#e377c2", "#7f7f7f"};
	if (id >= 0 && id <= 8)
		return balls[id];
	if (id >= 9 && id <= 15)
		return balls[id - 8];
	return others[((id % 5) + 5) % 5];
}

char *pool_svg_end(pool_svg *g) {
	pool_svg_put(g, "</svg>\n");
	if (g->b.failed) {
		free(g->b.data);
		g->b.data = NULL;
		return NULL;
	}
	return g->b.data;
}
