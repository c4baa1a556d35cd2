// The picture of a fit: for each shot, the table with the observed positions (dots) and the
// fitted tracks (lines) of every observed ball, in the balls' colours, and the starting guess's
// tracks dashed, so a user sees at once where the model follows the camera and where not.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fit.h"
#include "svg_table.h"

#define FIT_SVG_LINE 18.0      // px per legend line
#define FIT_SVG_DT 0.005       // s between points of a drawn track
#define FIT_SVG_MAX_POINTS 4000 // per ball and track

/// The tracks of shot s simulated under x, drawn as one polyline per observed ball.
static void tracks(pool_svg *g, const fit_problem *pb, int s, const double *x, fit_worker *w, bool dashed,
                   const bool *observed) {
	double v[FIT_SHOT_PARAMS];
	uint64_t signature;
	double *rows = malloc(2 * (size_t)pb->shots[s].obs_count * sizeof *rows);
	if (!rows || fit_shot_residuals(pb, s, x, w, rows, &signature) != POOL_OK) {
		free(rows);
		return;
	}
	free(rows);
	fit_shot_values(pb, x, s, v);
	const pool_scenario *sc = &pb->shots[s].scenario;
	double end = pool_sim_end_time(w->sim);
	double dt = fmax(FIT_SVG_DT, end / FIT_SVG_MAX_POINTS);
	for (int b = 0; b < sc->ball_count; ++b) {
		if (!observed[b])
			continue;
		int id = sc->balls[b].id;
		pool_svg_put(g, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%s\"%s stroke-opacity=\"0.9\" points=\"",
		             id == 0 ? "#ffffff" : pool_svg_ball_colour(id), dashed ? "1.5" : "1.2",
		             dashed ? " stroke-dasharray=\"6 4\"" : "");
		for (double t = 0.0;; t += dt) {
			if (t > end)
				t = end;
			if (pool_sim_state_at(w->sim, t, w->states) != POOL_OK)
				break;
			pool_svg_put(g, "%.1f,%.1f ", pool_svg_x(w->states[b].pos.x), pool_svg_y(g, w->states[b].pos.y));
			if (t == end || w->states[b].motion == POOL_MOTION_POCKETED || w->states[b].motion == POOL_MOTION_OFF_TABLE)
				break;
		}
		pool_svg_put(g, "\"/>\n");
	}
}

char *fit_svg(const fit_problem *pb, const fit_solution *s) {
	fit_problem one = *pb;
	one.threads = 1;
	fit_worker *w = NULL;
	double *start = malloc((size_t)pb->p * sizeof *start);
	if (!start || fit_workers_create(&one, 1, &w) != 0) {
		free(start);
		return NULL;
	}
	fit_start_vector(pb, start);
	const pool_table_def *t0 = &pb->shots[0].scenario.def.table;
	double width = pool_svg_table_width(t0), height = 0.0;
	for (int k = 0; k < pb->shot_count; ++k)
		height += pool_svg_table_height(&pb->shots[k].scenario.def.table) + FIT_SVG_LINE * 2;
	pool_svg g = {0};
	pool_svg_begin(&g, width, height + FIT_SVG_LINE);
	double top = 0.0;
	for (int k = 0; k < pb->shot_count; ++k) {
		const fit_shot *sh = &pb->shots[k];
		const pool_scenario *sc = &sh->scenario;
		bool *observed = calloc((size_t)sc->ball_count, sizeof *observed);
		if (!observed)
			break;
		for (long i = 0; i < sh->obs_count; ++i)
			observed[sh->obs[i].ball] = true;
		pool_svg_table(&g, &sc->def.table, top);
		double R = sc->def.params.ball_radius;
		for (int b = 0; b < sc->ball_count; ++b) // where the balls start
			pool_svg_put(&g, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\" fill-opacity=\"0.45\" "
			             "stroke=\"black\" stroke-width=\"0.5\"/>\n", pool_svg_x(sc->balls[b].pos.x),
			             pool_svg_y(&g, sc->balls[b].pos.y), R * POOL_SVG_SCALE, pool_svg_ball_colour(sc->balls[b].id));
		tracks(&g, pb, k, start, w, true, observed);
		tracks(&g, pb, k, s->x, w, false, observed);
		for (long i = 0; i < sh->obs_count; ++i) { // the observations over the fitted tracks
			const fit_observation *o = &sh->obs[i];
			pool_svg_put(&g, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.2\" fill=\"%s\" fill-opacity=\"0.6\" stroke=\"black\" "
			             "stroke-width=\"0.4\"/>\n", pool_svg_x(o->x), pool_svg_y(&g, o->y),
			             pool_svg_ball_colour(sc->balls[o->ball].id));
		}
		free(observed);
		top += pool_svg_table_height(&sc->def.table);
		pool_svg_put(&g, "<text x=\"10\" y=\"%.1f\">shot %d: ", top + FIT_SVG_LINE, k);
		pool_svg_put_escaped(&g, sh->tracks_path);
		pool_svg_put(&g, ", %ld observations (dots), fitted tracks (lines, rms %.2f mm), starting guess "
		             "(dashed)</text>\n", sh->obs_count, 1e3 * s->shot_rms[k]);
		top += 2 * FIT_SVG_LINE;
	}
	pool_svg_put(&g, "<text x=\"10\" y=\"%.1f\">pool-fit: %d parameters, rms residual %.2f mm over %d shot%s</text>\n",
	             top + FIT_SVG_LINE * 0.5, pb->p, 1e3 * s->rms, pb->shot_count, pb->shot_count == 1 ? "" : "s");
	fit_workers_free(w, 1);
	free(start);
	return pool_svg_end(&g);
}
