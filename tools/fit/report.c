// pool-fit's outputs: the libpool-fit/1 document and the text summary.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fit.h"
#include "json_writer.h"
#include "text_buffer.h"

/// The fitted table parameters (the first shot's, with the free ones fitted).
static pool_params fitted_params(const fit_problem *pb, const fit_solution *s) {
	pool_params p = pb->base_params;
	fit_table_values(pb, s->x, &p);
	return p;
}

static void interval(pool_jw *w, const fit_param_info *info, const fit_estimate *e) {
	pool_jw_key(w, "ci95");
	pool_jw_array(w, true);
	pool_jw_number(w, fit_shown(info, e->ci_low));
	pool_jw_number(w, fit_shown(info, e->ci_high));
	pool_jw_end(w, ']');
}

char *fit_report_json(const fit_problem *pb, const fit_solution *s) {
	pool_jw w;
	pool_jw_init(&w, true);
	pool_jw_object(&w, false);
	pool_jw_key(&w, "format");
	pool_jw_string(&w, "libpool-fit/1");
	pool_jw_key(&w, "fit");
	pool_jw_array(&w, true);
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		if (pb->free_table[k])
			pool_jw_string(&w, fit_table_params[k].name);
	for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
		if (pb->free_shot[k])
			pool_jw_string(&w, fit_shot_params[k].name);
	pool_jw_end(&w, ']');

	pool_jw_key(&w, "parameters");
	pool_jw_array(&w, false);
	for (int j = 0; j < pb->p; ++j) {
		int shot, index;
		const fit_param_info *info = fit_param_of(pb, j, &shot, &index);
		const fit_estimate *e = &s->est[j];
		pool_jw_object(&w, true);
		pool_jw_key(&w, "name");
		pool_jw_string(&w, info->name);
		pool_jw_key(&w, "shot");
		if (shot < 0)
			pool_jw_string(&w, "all");
		else
			pool_jw_int(&w, shot);
		pool_jw_key(&w, "value");
		pool_jw_number(&w, fit_shown(info, e->value));
		pool_jw_key(&w, "se");
		pool_jw_number(&w, fit_shown(info, e->se));
		interval(&w, info, e);
		pool_jw_key(&w, "initial");
		pool_jw_number(&w, fit_shown(info, e->initial));
		pool_jw_key(&w, "unit");
		pool_jw_string(&w, info->unit);
		pool_jw_end(&w, '}');
	}
	pool_jw_end(&w, ']');

	pool_params params = fitted_params(pb, s);
	pool_jw_key(&w, "params");
	pool_jw_object(&w, false);
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k) {
		pool_jw_key(&w, fit_table_params[k].name);
		pool_jw_number(&w, *fit_table_field(&params, k));
	}
	pool_jw_end(&w, '}');

	pool_jw_key(&w, "shots");
	pool_jw_array(&w, false);
	for (int shot = 0; shot < pb->shot_count; ++shot) {
		const fit_shot *sh = &pb->shots[shot];
		double v[FIT_SHOT_PARAMS];
		fit_shot_values(pb, s->x, shot, v);
		pool_jw_object(&w, false);
		pool_jw_key(&w, "scenario");
		pool_jw_string(&w, sh->scenario_path);
		pool_jw_key(&w, "tracks");
		pool_jw_string(&w, sh->tracks_path);
		pool_jw_key(&w, "observations");
		pool_jw_int(&w, sh->obs_count);
		pool_jw_key(&w, "rms");
		pool_jw_number(&w, s->shot_rms[shot]);
		pool_jw_key(&w, "strike");
		pool_jw_object(&w, true);
		pool_jw_key(&w, "ball");
		pool_jw_int(&w, sh->ball);
		for (int k = FIT_SPEED; k <= FIT_B; ++k) {
			pool_jw_key(&w, fit_shot_params[k].name);
			pool_jw_number(&w, fit_shown(&fit_shot_params[k], v[k]));
		}
		pool_jw_end(&w, '}');
		pool_jw_key(&w, "t0");
		pool_jw_number(&w, v[FIT_T0]);
		pool_jw_end(&w, '}');
	}
	pool_jw_end(&w, ']');

	pool_jw_key(&w, "residual");
	pool_jw_object(&w, true);
	pool_jw_key(&w, "rms");
	pool_jw_number(&w, s->rms);
	pool_jw_key(&w, "sum_squares");
	pool_jw_number(&w, s->rss);
	pool_jw_key(&w, "coordinates");
	pool_jw_int(&w, (int64_t)pb->n_obs);
	pool_jw_key(&w, "dof");
	pool_jw_int(&w, s->dof);
	pool_jw_key(&w, "sigma");
	pool_jw_number(&w, s->sigma);
	pool_jw_key(&w, "sigma_given");
	pool_jw_bool(&w, s->sigma_given);
	pool_jw_key(&w, "track_noise");
	pool_jw_number(&w, s->track_noise);
	pool_jw_end(&w, '}');

	pool_jw_key(&w, "solver");
	pool_jw_object(&w, true);
	pool_jw_key(&w, "method");
	pool_jw_string(&w, "gsl_multifit_nlinear: trust region, Levenberg-Marquardt, More scaling, QR");
	pool_jw_key(&w, "starts");
	pool_jw_int(&w, s->starts);
	pool_jw_key(&w, "best_start");
	pool_jw_int(&w, s->best_start);
	pool_jw_key(&w, "iterations");
	pool_jw_int(&w, s->iterations);
	pool_jw_key(&w, "alternatives");
	pool_jw_int(&w, s->alternatives);
	pool_jw_key(&w, "intervals");
	pool_jw_string(&w, s->profiled ? "profile" : "wald");
	pool_jw_key(&w, "converged");
	pool_jw_bool(&w, s->converged);
	pool_jw_end(&w, '}');

	pool_jw_key(&w, "correlation");
	pool_jw_array(&w, false);
	for (int j = 0; j < pb->p; ++j) {
		pool_jw_array(&w, true);
		for (int k = 0; k < pb->p; ++k)
			pool_jw_number(&w, s->correlation[(size_t)j * (size_t)pb->p + (size_t)k]);
		pool_jw_end(&w, ']');
	}
	pool_jw_end(&w, ']');
	pool_jw_end(&w, '}');
	return pool_jw_finish(&w);
}


char *fit_report_text(const fit_problem *pb, const fit_solution *s) {
	pool_text_buffer b = {0};
	long observations = (long)(pb->n_obs / 2);
	pool_text_appendf(&b, "%s: %d shot%s, %ld observations, %d parameters: rms residual %.3g mm, sigma %.3g mm per "
	    "coordinate (%s; the tracks' own noise %.3g mm), %d iterations, %s, %.3f s\n", FIT_PROGRAM, pb->shot_count, pb->shot_count == 1 ? "" : "s",
	    observations, pb->p, 1e3 * s->rms, 1e3 * s->sigma, s->sigma_given ? "given" : "estimated", 1e3 * s->track_noise, s->iterations,
	    s->converged ? "converged" : "not converged", s->seconds);
	pool_text_appendf(&b, "  %-13s %5s %14s %12s %31s %14s\n", "parameter", "shot", "value", "se",
	    s->profiled ? "95 % interval (profile)" : "95 % interval", "start");
	for (int j = 0; j < pb->p; ++j) {
		int shot, index;
		const fit_param_info *info = fit_param_of(pb, j, &shot, &index);
		const fit_estimate *e = &s->est[j];
		char where[16];
		snprintf(where, sizeof where, shot < 0 ? "all" : "%d", shot);
		pool_text_appendf(&b, "  %-13s %5s %14.6g %12.3g   [%12.6g, %12.6g] %14.6g %s\n", info->name, where,
		    fit_shown(info, e->value), fit_shown(info, e->se), fit_shown(info, e->ci_low),
		    fit_shown(info, e->ci_high), fit_shown(info, e->initial), info->unit);
	}
	if (b.failed) {
		free(b.data);
		return NULL;
	}
	return b.data;
}
