// The study's text, JSON and CSV outputs. Numbers in JSON and CSV are written with the fewest
// digits that read back to the same double (json_writer.h), so a seed gives byte-identical files.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "json_writer.h"
#include "models_json.h"
#include "study.h"
#include "text_buffer.h"

static const char *const pocket_names[SENS_POCKET_COUNT] = {"sw", "se", "nw", "ne", "s", "n"};

static const sens_cloud *cloud_of(const sens_study *s, int set, int k) {
	return &s->clouds[set * s->tracked_count + k];
}

double sens_mean_distance(const sens_study *s, int k) {
	if (s->set_count < 2)
		return NAN;
	const sens_cloud *a = cloud_of(s, 0, k), *b = cloud_of(s, 1, k);
	if (!a->has_mean || !b->has_mean)
		return NAN;
	return hypot(b->mean[0] - a->mean[0], b->mean[1] - a->mean[1]);
}

// ---- text -------------------------------------------------------------------------------------

static void put(pool_text_buffer *b, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void put(pool_text_buffer *b, const char *format, ...) {
	char line[1024];
	va_list args;
	va_start(args, format);
	int n = vsnprintf(line, sizeof line, format, args);
	va_end(args);
	if (n > 0)
		pool_text_append(b, line, (size_t)n < sizeof line ? (size_t)n : sizeof line - 1);
}

static void put_proportion(pool_text_buffer *b, const char *what, const sens_proportion *p) {
	put(b, "%s %.4f [%.4f, %.4f] (%ld of %ld)", what, p->p, p->low, p->high, p->count, p->n);
}

char *sens_report_text(const sens_study *s) {
	pool_text_buffer b = {0};
	const double *sd = s->noise.cue_sd;
	put(&b, "%s: %ld samples of %s, seed %lu (%s)\n", SENS_PROGRAM, s->samples.n, s->scenario_path,
	    s->seed, sens_rng_name());
	put(&b, "  strike: ball %d, speed %.6g m/s, phi %.6g deg, theta %.6g deg, a %.6g m, b %.6g m\n",
	    (int)s->nominal.ball, s->nominal.speed, s->nominal.phi, s->nominal.theta, s->nominal.a,
	    s->nominal.b);
	put(&b, "  sd: speed %.6g m/s, phi %.6g deg, theta %.6g deg, a %.6g m, b %.6g m, positions %.6g m "
	    "(%d balls)\n", sd[SENS_SPEED], sd[SENS_PHI], sd[SENS_THETA], sd[SENS_A], sd[SENS_B],
	    s->noise.position_sd, s->noise.position_count);
	for (int set = 0; set < s->set_count; ++set) {
		const sens_run *r = &s->runs[set];
		put(&b, "models %s: %ld simulated, %ld refused by the library", s->sets[set].name,
		    r->n - r->refused - r->failed, r->refused);
		if (r->failed)
			put(&b, ", %ld failed", r->failed);
		for (long i = 0; i < r->n; ++i)
			if (r->error[i]) {
				put(&b, " (first: sample %ld: %.300s)", i, r->error[i]);
				break;
			}
		put(&b, "\n");
		for (int k = 0; k < s->tracked_count; ++k) {
			const sens_cloud *c = cloud_of(s, set, k);
			put(&b, "  ball %d: %ld on the table", (int)c->id, c->on_table);
			if (c->has_mean)
				put(&b, ", mean (%.6g, %.6g) m", c->mean[0], c->mean[1]);
			if (c->has_cov)
				put(&b, ", sd (%.4g, %.4g) m, cov_xy %.4g m^2, 95%% ellipse %.4g x %.4g m at %.2f deg",
				    sqrt(c->cov[0]), sqrt(c->cov[2]), c->cov[1], c->ellipse_major, c->ellipse_minor,
				    c->ellipse_angle_deg);
			put(&b, "\n    ");
			put_proportion(&b, "pocketed", &c->pocketed);
			for (int p = 0; p < SENS_POCKET_COUNT; ++p)
				if (c->pockets[p].count > 0) {
					put(&b, "; ");
					put_proportion(&b, pocket_names[p], &c->pockets[p]);
				}
			if (c->off_table.count > 0) {
				put(&b, "; ");
				put_proportion(&b, "off the table", &c->off_table);
			}
			put(&b, " (Wilson %.0f%%)\n", 100.0 * SENS_CONFIDENCE);
		}
		if (s->layout->has_game) {
			const sens_game_stats g = sens_game_stats_compute(r);
			put(&b, "  game %s: ", pool_game_rules_name(s->layout->game.rules));
			put_proportion(&b, "legal", &g.legal);
			put(&b, "; ");
			put_proportion(&b, "legal pot", &g.legal_pot);
			for (int o = 0; o < 4; ++o)
				if (g.outcomes[o].count > 0) {
					put(&b, "; ");
					put_proportion(&b, pool_game_outcome_name((pool_game_outcome)o), &g.outcomes[o]);
				}
			put(&b, "\n");
		}
	}
	if (s->set_count == 2)
		for (int k = 0; k < s->tracked_count; ++k)
			put(&b, "distance between the means (%s to %s), ball %d: %.6g m\n", s->sets[0].name,
			    s->sets[1].name, (int)cloud_of(s, 0, k)->id, sens_mean_distance(s, k));
	if (b.failed) {
		free(b.data);
		return NULL;
	}
	return b.data ? b.data : calloc(1, 1);
}

// ---- JSON -------------------------------------------------------------------------------------

/// null (the writer writes a non-finite number as null).
static void jw_null(pool_jw *w) { pool_jw_number(w, NAN); }

static void jw_proportion(pool_jw *w, const char *key, const sens_proportion *p) {
	pool_jw_key(w, key);
	pool_jw_object(w, true);
	pool_jw_key(w, "count");
	pool_jw_int(w, p->count);
	pool_jw_key(w, "p");
	pool_jw_number(w, p->p);
	pool_jw_key(w, "low");
	pool_jw_number(w, p->low);
	pool_jw_key(w, "high");
	pool_jw_number(w, p->high);
	pool_jw_end(w, '}');
}

char *sens_report_json(const sens_study *s) {
	pool_jw w;
	pool_jw_init(&w, true);
	pool_jw_object(&w, false);
	pool_jw_key(&w, "format");
	pool_jw_string(&w, "libpool-sensitivity/1");
	pool_jw_key(&w, "scenario");
	pool_jw_string(&w, s->scenario_path);
	pool_jw_key(&w, "samples");
	pool_jw_int(&w, s->samples.n);
	pool_jw_key(&w, "seed");
	pool_jw_int(&w, (int64_t)s->seed);
	pool_jw_key(&w, "rng");
	pool_jw_string(&w, sens_rng_name());
	pool_jw_key(&w, "confidence");
	pool_jw_number(&w, SENS_CONFIDENCE);
	pool_jw_key(&w, "strike");
	pool_jw_object(&w, true);
	pool_jw_key(&w, "ball");
	pool_jw_int(&w, s->nominal.ball);
	double nominal[SENS_CUE_COUNT] = {s->nominal.speed, s->nominal.phi, s->nominal.theta, s->nominal.a,
	                                  s->nominal.b};
	for (int p = 0; p < SENS_CUE_COUNT; ++p) {
		pool_jw_key(&w, sens_cue_names[p]);
		pool_jw_number(&w, nominal[p]);
	}
	pool_jw_end(&w, '}');
	pool_jw_key(&w, "sd");
	pool_jw_object(&w, true);
	for (int p = 0; p < SENS_CUE_COUNT; ++p) {
		pool_jw_key(&w, sens_cue_names[p]);
		pool_jw_number(&w, s->noise.cue_sd[p]);
	}
	pool_jw_key(&w, "position");
	pool_jw_number(&w, s->noise.position_sd);
	pool_jw_end(&w, '}');
	pool_jw_key(&w, "position_balls");
	pool_jw_array(&w, true);
	for (int k = 0; k < s->noise.position_count; ++k)
		pool_jw_int(&w, s->layout->balls[s->noise.position_index[k]].id);
	pool_jw_end(&w, ']');
	pool_jw_key(&w, "model_sets");
	pool_jw_array(&w, false);
	for (int set = 0; set < s->set_count; ++set) {
		const sens_run *r = &s->runs[set];
		pool_jw_object(&w, false);
		pool_jw_key(&w, "name");
		pool_jw_string(&w, s->sets[set].name);
		pool_jw_models(&w, &s->sets[set].def.models); // the laws the name stands for
		pool_jw_key(&w, "simulated");
		pool_jw_int(&w, r->n - r->refused - r->failed);
		pool_jw_key(&w, "refused");
		pool_jw_int(&w, r->refused);
		pool_jw_key(&w, "failed");
		pool_jw_int(&w, r->failed);
		if (s->layout->has_game) {
			const sens_game_stats g = sens_game_stats_compute(r);
			pool_jw_key(&w, "game");
			pool_jw_object(&w, false);
			pool_jw_key(&w, "rules");
			pool_jw_string(&w, pool_game_rules_name(s->layout->game.rules));
			jw_proportion(&w, "legal", &g.legal);
			jw_proportion(&w, "legal_pot", &g.legal_pot);
			pool_jw_key(&w, "outcomes");
			pool_jw_object(&w, false);
			for (int o = 0; o < 4; ++o)
				jw_proportion(&w, pool_game_outcome_name((pool_game_outcome)o), &g.outcomes[o]);
			pool_jw_end(&w, '}');
			pool_jw_end(&w, '}');
		}
		pool_jw_key(&w, "balls");
		pool_jw_array(&w, false);
		for (int k = 0; k < s->tracked_count; ++k) {
			const sens_cloud *c = cloud_of(s, set, k);
			pool_jw_object(&w, false);
			pool_jw_key(&w, "id");
			pool_jw_int(&w, c->id);
			pool_jw_key(&w, "on_table");
			pool_jw_int(&w, c->on_table);
			pool_jw_key(&w, "mean");
			if (c->has_mean) {
				pool_jw_array(&w, true);
				pool_jw_number(&w, c->mean[0]);
				pool_jw_number(&w, c->mean[1]);
				pool_jw_end(&w, ']');
			} else {
				jw_null(&w);
			}
			pool_jw_key(&w, "covariance");
			if (c->has_cov) {
				pool_jw_array(&w, true);
				pool_jw_number(&w, c->cov[0]);
				pool_jw_number(&w, c->cov[1]);
				pool_jw_number(&w, c->cov[2]);
				pool_jw_end(&w, ']');
				pool_jw_key(&w, "ellipse");
				pool_jw_object(&w, true);
				pool_jw_key(&w, "major");
				pool_jw_number(&w, c->ellipse_major);
				pool_jw_key(&w, "minor");
				pool_jw_number(&w, c->ellipse_minor);
				pool_jw_key(&w, "angle_deg");
				pool_jw_number(&w, c->ellipse_angle_deg);
				pool_jw_end(&w, '}');
			} else {
				jw_null(&w);
				pool_jw_key(&w, "ellipse");
				jw_null(&w);
			}
			jw_proportion(&w, "pocketed", &c->pocketed);
			jw_proportion(&w, "off_table", &c->off_table);
			pool_jw_key(&w, "pockets");
			pool_jw_object(&w, false);
			for (int p = 0; p < SENS_POCKET_COUNT; ++p)
				jw_proportion(&w, pocket_names[p], &c->pockets[p]);
			pool_jw_end(&w, '}');
			pool_jw_end(&w, '}');
		}
		pool_jw_end(&w, ']');
		pool_jw_end(&w, '}');
	}
	pool_jw_end(&w, ']');
	if (s->set_count == 2) {
		pool_jw_key(&w, "mean_distance");
		pool_jw_array(&w, false);
		for (int k = 0; k < s->tracked_count; ++k) {
			pool_jw_object(&w, true);
			pool_jw_key(&w, "id");
			pool_jw_int(&w, cloud_of(s, 0, k)->id);
			pool_jw_key(&w, "distance");
			pool_jw_number(&w, sens_mean_distance(s, k)); // null when either cloud is empty
			pool_jw_end(&w, '}');
		}
		pool_jw_end(&w, ']');
	}
	pool_jw_end(&w, '}');
	return pool_jw_finish(&w);
}

// ---- CSV --------------------------------------------------------------------------------------

static void csv_num(pool_text_buffer *b, bool has, double x) {
	pool_text_append(b, ",", 1);
	if (!has || !isfinite(x))
		return;
	char text[32];
	pool_jw_format_double(x, text);
	pool_text_append(b, text, strlen(text));
}

static void csv_proportion(pool_text_buffer *b, const sens_proportion *p) {
	csv_num(b, true, p->p);
	csv_num(b, true, p->low);
	csv_num(b, true, p->high);
}

/// A CSV field in double quotes (quotes doubled, line breaks as spaces), as pool-batch writes.
static void csv_quoted(pool_text_buffer *b, const char *text) {
	pool_text_append(b, "\"", 1);
	for (const char *p = text; *p; ++p) {
		if (*p == '"')
			pool_text_append(b, "\"\"", 2);
		else if (*p == '\n' || *p == '\r')
			pool_text_append(b, " ", 1);
		else
			pool_text_append(b, p, 1);
	}
	pool_text_append(b, "\"", 1);
}

char *sens_report_csv(const sens_study *s) {
	pool_text_buffer b = {0};
	put(&b, "models,ball,simulated,refused,on_table,mean_x,mean_y,cov_xx,cov_xy,cov_yy,ellipse_major,"
	        "ellipse_minor,ellipse_angle_deg,p_pocketed,p_pocketed_low,p_pocketed_high,p_off_table,"
	        "p_off_table_low,p_off_table_high");
	for (int p = 0; p < SENS_POCKET_COUNT; ++p)
		put(&b, ",p_%s,p_%s_low,p_%s_high", pocket_names[p], pocket_names[p], pocket_names[p]);
	put(&b, ",mean_distance");
	if (s->layout->has_game) {
		put(&b, ",p_legal,p_legal_low,p_legal_high,p_legal_pot,p_legal_pot_low,p_legal_pot_high");
		for (int o = 0; o < 4; ++o) {
			const char *name = pool_game_outcome_name((pool_game_outcome)o);
			put(&b, ",p_%s,p_%s_low,p_%s_high", name, name, name);
		}
	}
	put(&b, "\n");
	for (int set = 0; set < s->set_count; ++set)
		for (int k = 0; k < s->tracked_count; ++k) {
			const sens_cloud *c = cloud_of(s, set, k);
			const sens_run *r = &s->runs[set];
			csv_quoted(&b, s->sets[set].name);
			put(&b, ",%d,%ld,%ld,%ld", (int)c->id, c->samples, r->refused, c->on_table);
			csv_num(&b, c->has_mean, c->mean[0]);
			csv_num(&b, c->has_mean, c->mean[1]);
			for (int j = 0; j < 3; ++j)
				csv_num(&b, c->has_cov, c->cov[j]);
			csv_num(&b, c->has_cov, c->ellipse_major);
			csv_num(&b, c->has_cov, c->ellipse_minor);
			csv_num(&b, c->has_cov, c->ellipse_angle_deg);
			csv_proportion(&b, &c->pocketed);
			csv_proportion(&b, &c->off_table);
			for (int p = 0; p < SENS_POCKET_COUNT; ++p)
				csv_proportion(&b, &c->pockets[p]);
			csv_num(&b, set > 0, sens_mean_distance(s, k)); // from the first set's mean
			if (s->layout->has_game) {
				const sens_game_stats g = sens_game_stats_compute(r);
				csv_proportion(&b, &g.legal);
				csv_proportion(&b, &g.legal_pot);
				for (int o = 0; o < 4; ++o)
					csv_proportion(&b, &g.outcomes[o]);
			}
			put(&b, "\n");
		}
	if (b.failed) {
		free(b.data);
		return NULL;
	}
	return b.data;
}

char *sens_samples_csv(const sens_study *s) {
	pool_text_buffer b = {0};
	const pool_scenario *layout = s->layout;
	put(&b, "sample,models,ball,speed,phi,theta,a,b");
	for (int k = 0; k < s->noise.position_count; ++k) {
		int id = (int)layout->balls[s->noise.position_index[k]].id;
		put(&b, ",ball_%d_x0,ball_%d_y0", id, id);
	}
	put(&b, ",stop_reason");
	for (int k = 0; k < s->tracked_count; ++k) {
		int id = (int)layout->balls[s->tracked[k]].id;
		put(&b, ",ball_%d_x,ball_%d_y,ball_%d_state,ball_%d_pocket", id, id, id, id);
	}
	if (s->layout->has_game)
		put(&b, ",legal,outcome");
	put(&b, ",error\n");
	int m = s->samples.position_count, t = s->tracked_count;
	for (int set = 0; set < s->set_count; ++set) {
		const sens_run *r = &s->runs[set];
		for (long i = 0; i < s->samples.n && !b.failed; ++i) {
			const pool_batch_strike *st = &s->samples.strikes[i];
			put(&b, "%ld,", i);
			csv_quoted(&b, s->sets[set].name);
			put(&b, ",%d", (int)st->ball);
			double v[SENS_CUE_COUNT] = {st->speed, st->phi, st->theta, st->a, st->b};
			for (int p = 0; p < SENS_CUE_COUNT; ++p)
				csv_num(&b, true, v[p]);
			for (int k = 0; k < m; ++k) {
				csv_num(&b, true, s->samples.positions[(i * m + k) * 2]);
				csv_num(&b, true, s->samples.positions[(i * m + k) * 2 + 1]);
			}
			int8_t stop = r->stop[i];
			put(&b, ",%s", stop == -1 ? "error" : stop == -2 ? "failed"
			                                   : pool_stop_reason_name((pool_stop_reason)stop));
			for (int k = 0; k < t; ++k) {
				bool ok = stop >= 0;
				csv_num(&b, ok, r->pos[(i * t + k) * 2]);
				csv_num(&b, ok, r->pos[(i * t + k) * 2 + 1]);
				int8_t p = r->pocket[i * t + k];
				put(&b, ",%s,%s", ok ? pool_motion_name((pool_motion)r->state[i * t + k]) : "",
				    p >= 0 && p < SENS_POCKET_COUNT ? pocket_names[p] : "");
			}
			if (s->layout->has_game) {
				const int8_t legal = r->legal[i], outcome = r->outcome[i];
				put(&b, ",%s,%s", legal < 0 ? "" : legal ? "true" : "false",
				    outcome < 0 ? "" : pool_game_outcome_name((pool_game_outcome)outcome));
			}
			put(&b, ",");
			if (r->error[i])
				csv_quoted(&b, r->error[i]);
			put(&b, "\n");
		}
	}
	if (b.failed) {
		free(b.data);
		return NULL;
	}
	return b.data;
}
