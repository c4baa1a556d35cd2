// The ranked shots as JSON (docs/interfaces.md "Shot planning") and as text.
#include <math.h>
#include <stdlib.h>

#include "aim_tool.h"
#include "json_writer.h"

#define DEG (3.14159265358979323846 / 180.0)

char *aim_report_json(const pool_aim_shot *shots, int count, int32_t cue_ball) {
	pool_jw w;
	pool_jw_init(&w, true);
	pool_jw_array(&w, false);
	for (int k = 0; k < count; ++k) {
		const pool_aim_shot *s = &shots[k];
		pool_jw_object(&w, false);
		pool_jw_key(&w, "rank");
		pool_jw_int(&w, k + 1);
		pool_jw_key(&w, "strike");
		pool_jw_object(&w, true);
		pool_jw_key(&w, "ball");
		pool_jw_int(&w, cue_ball);
		pool_jw_key(&w, "speed");
		pool_jw_number(&w, s->strike.speed);
		pool_jw_key(&w, "phi");
		pool_jw_number(&w, s->strike.phi / DEG);
		pool_jw_key(&w, "theta");
		pool_jw_number(&w, s->strike.theta / DEG);
		pool_jw_key(&w, "a");
		pool_jw_number(&w, s->strike.a);
		pool_jw_key(&w, "b");
		pool_jw_number(&w, s->strike.b);
		pool_jw_end(&w, '}');
		pool_jw_key(&w, "ball");
		pool_jw_int(&w, s->ball);
		pool_jw_key(&w, "pocket");
		pool_jw_string(&w, pool_pocket_name(s->pocket));
		pool_jw_key(&w, "kind");
		pool_jw_string(&w, pool_aim_kind_name(s->kind));
		pool_jw_key(&w, "via");
		if (s->via == POOL_AIM_NO_BALL)
			pool_jw_null(&w);
		else
			pool_jw_int(&w, s->via);
		pool_jw_key(&w, "rail");
		if (s->rail == POOL_RAIL_NONE)
			pool_jw_null(&w);
		else
			pool_jw_string(&w, pool_rail_name(s->rail));
		pool_jw_key(&w, "p_success");
		pool_jw_number(&w, s->p_success);
		pool_jw_key(&w, "ci95");
		pool_jw_array(&w, true);
		pool_jw_number(&w, s->ci_low);
		pool_jw_number(&w, s->ci_high);
		pool_jw_end(&w, ']');
		pool_jw_key(&w, "samples");
		pool_jw_int(&w, s->samples);
		pool_jw_key(&w, "cue_ball_final");
		pool_jw_array(&w, true);
		pool_jw_number(&w, s->cue_final.x);
		pool_jw_number(&w, s->cue_final.y);
		pool_jw_end(&w, ']');
		if (s->position >= 0) {
			pool_jw_key(&w, "position");
			pool_jw_int(&w, s->position);
		}
		pool_jw_end(&w, '}');
	}
	pool_jw_end(&w, ']');
	return pool_jw_finish(&w);
}

char *aim_report_text(const pool_aim_shot *shots, int count, const pool_aim_stats *st) {
	pool_text_buffer b = {0};
	pool_text_appendf(&b, "pool-aim: %d candidates (%d blocked by the cue stick), %d refined, %d pot without noise; "
	                  "%lld shots simulated in %.3f s%s\n", st->candidates, st->blocked, st->refined, st->potting,
	                  st->simulations, st->seconds, st->budget_reached ? " (time budget reached)" : "");
	for (int k = 0; k < count; ++k) {
		const pool_aim_shot *s = &shots[k];
		pool_text_appendf(&b, "  %d. %-11s ball %d into %-2s  p %.3f [%.3f, %.3f] of %d   speed %.2f m/s phi %.2f deg "
		                  "theta %.1f deg a %.1f mm b %.1f mm\n", k + 1, pool_aim_kind_name(s->kind), (int)s->ball,
		                  pool_pocket_name(s->pocket), s->p_success, s->ci_low, s->ci_high, s->samples, s->strike.speed,
		                  s->strike.phi / DEG, s->strike.theta / DEG, 1e3 * s->strike.a, 1e3 * s->strike.b);
	}
	if (b.failed) {
		free(b.data);
		return NULL;
	}
	return b.data;
}
