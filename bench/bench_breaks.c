// pool-bench-breaks: what the laws do to a break. Runs N jittered 8-ball breaks (15 balls with
// 0.1 mm gaps, the cue ball on the head spot, 8 m/s, 2 degrees of elevation, the aim jittered
// uniformly within +-0.5 degree; the same N breaks for every model set) and prints, per model
// set, the break statistics the issue compares with pooltool and with measured breaks: how far
// the rack balls end from where they started (median), how many move more than 0.3 m, reach a
// cushion, are pocketed, where the cue ball ends, and what a break costs. --json writes every
// break's figures for tools/pool-break-plot.
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pool/pool.h>

#include "bench_util.h"
#include "cli.h"
#include "json_writer.h"
#include "models_json.h"

#define PROGRAM "pool-bench-breaks"
#define BREAKS_MAX 1000000
#define SETS_MAX 8
#define MOVED_FAR 0.3 // m: a rack ball that ends further than this from its place "moved"

enum { RACK = 16 }; // the cue ball (id 0) and 15 object balls

static const char usage_text[] =
	"usage: pool-bench-breaks [--breaks N] [--seed S] [--speed V] [--models SET[,SET...]]\n"
	"                         [--json FILE]\n"
	"\n"
	"Runs N jittered 8-ball breaks (15 balls with 0.1 mm gaps, 2 degrees of elevation, the aim\n"
	"jittered uniformly within +-0.5 degree) under each model set and prints the break statistics:\n"
	"the median distance a rack ball ends from where it started, the rack balls per break that\n"
	"move more than 0.3 m, reach a cushion, are pocketed, the cue ball's final distance, events\n"
	"and time per break (median and minimum) and the machine.\n"
	"\n"
	"  --breaks N        breaks per model set (default 200)\n"
	"  --seed S          seed of the aim jitter (default 1); the same breaks for every set\n"
	"  --speed V         cue speed in m/s (default 8)\n"
	"  --models LIST     comma-separated model sets (a set, or model names joined with '+',\n"
	"                    as pool-batch --models), default thesis,default\n"
	"  --json FILE       also write every break's figures (libpool-breaks/1) for pool-break-plot\n"
	"  -h, --help        show this help\n";

typedef struct options {
	long breaks, seed;
	double speed;
	const char *models, *json;
	bool help;
} options;

static int option(void *context, const char *a, const char *v) {
	options *o = context;
	if (strcmp(a, "--breaks") == 0) {
		if (!pool_cli_parse_count(v, &o->breaks) || o->breaks < 1 || o->breaks > BREAKS_MAX)
			return pool_cli_usage_error(PROGRAM, "--breaks: '%s' is not a count from 1 to %d", pool_cli_arg(v),
			                            BREAKS_MAX);
	} else if (strcmp(a, "--seed") == 0) {
		if (!pool_cli_parse_count(v, &o->seed))
			return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number >= 0", pool_cli_arg(v));
	} else if (strcmp(a, "--speed") == 0) {
		if (!pool_cli_parse_double(v, &o->speed) || !(o->speed > 0.0) || o->speed > 50.0)
			return pool_cli_usage_error(PROGRAM, "--speed: '%s' is not a speed in (0, 50] m/s", pool_cli_arg(v));
	} else if (strcmp(a, "--models") == 0) {
		o->models = v;
	} else if (strcmp(a, "--json") == 0) {
		o->json = v;
	}
	return 0;
}

// splitmix64: the jitter of break i is a function of (seed, i) only.
static double jitter(uint64_t seed, long i) {
	uint64_t z = seed * 0x9E3779B97F4A7C15ull + (uint64_t)i * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	z ^= z >> 31;
	return (double)(z >> 11) * (1.0 / 9007199254740992.0) * 2.0 - 1.0;
}

// One break's figures.
typedef struct break_figures {
	double displacement[RACK - 1]; // m, each rack ball's final distance from its place
	int moved, cushioned, pocketed, events;
	bool scratched;
	double cue_distance, seconds;
} break_figures;

static int run_break(pool_sim *sim, const pool_sim_def *def, const pool_ball_state *rack, int n, double speed,
                     double aim_deg, break_figures *out) {
	memset(out, 0, sizeof *out);
	pool_error err;
	const double t0 = pool_bench_now_s();
	if (pool_sim_reset(sim, def, &err) != POOL_OK)
		return fprintf(stderr, "%s: %s\n", PROGRAM, err.message), -1;
	for (int i = 0; i < n; ++i)
		if (pool_sim_add_ball(sim, &rack[i], &err) != POOL_OK)
			return fprintf(stderr, "%s: %s\n", PROGRAM, err.message), -1;
	pool_strike s = pool_break_strike(speed);
	s.phi += aim_deg * 3.14159265358979323846 / 180.0;
	s.theta = 2.0 * 3.14159265358979323846 / 180.0;
	if (pool_sim_strike(sim, 0, &s, &err) != POOL_OK)
		return fprintf(stderr, "%s: %s\n", PROGRAM, err.message), -1;
	const pool_result r = pool_sim_run(sim);
	out->seconds = pool_bench_now_s() - t0;
	if (r != POOL_OK)
		return fprintf(stderr, "%s: the break failed: %s\n", PROGRAM,
		               pool_sim_last_error(sim)[0] ? pool_sim_last_error(sim) : pool_result_str(r)),
		       -1;
	int count;
	const pool_event *ev = pool_sim_events(sim, &count);
	out->events = count;
	bool cushion[RACK] = {false};
	for (int e = 0; e < count; ++e)
		if (ev[e].type == POOL_EVENT_BALL_CUSHION) {
			const pool_ball_state *after = pool_sim_event_states(sim, &ev[e]);
			if (after[0].id > 0 && after[0].id < RACK)
				cushion[after[0].id] = true;
		}
	const pool_ball_state *fin = pool_sim_balls(sim); // by insertion index: the rack's order
	for (int i = 0; i < n; ++i) {
		const double dx = fin[i].pos.x - rack[i].pos.x, dy = fin[i].pos.y - rack[i].pos.y, d = sqrt(dx * dx + dy * dy);
		const bool down = fin[i].motion == POOL_MOTION_POCKETED || fin[i].motion == POOL_MOTION_OFF_TABLE;
		if (rack[i].id == 0) {
			out->cue_distance = d;
			out->scratched = down;
			continue;
		}
		out->displacement[rack[i].id - 1] = d;
		out->moved += d > MOVED_FAR;
		out->cushioned += cushion[rack[i].id];
		out->pocketed += fin[i].motion == POOL_MOTION_POCKETED;
	}
	return 0;
}

static int compare_doubles(const void *a, const void *b) {
	const double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static double median_of(double *v, size_t n) {
	qsort(v, n, sizeof *v, compare_doubles);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int main(int argc, char **argv) {
	options o = {200, 1, 8.0, "thesis,default", NULL, false};
	static const char *const flags[] = {NULL};
	static const char *const with_value[] = {"--breaks", "--seed", "--speed", "--models", "--json", NULL};
	const char *stray = NULL;
	int status = pool_cli_walk(PROGRAM, argc, argv, "argument", flags, with_value, option, &o, &stray, &o.help);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	if (stray)
		return pool_cli_usage_error(PROGRAM, "unexpected argument '%s'", pool_cli_arg(stray));

	// The model sets.
	char names[SETS_MAX][64];
	pool_models models[SETS_MAX];
	int sets = 0;
	char list[512];
	if (strlen(o.models) >= sizeof list)
		return pool_cli_usage_error(PROGRAM, "%s", "--models: too long");
	snprintf(list, sizeof list, "%s", o.models);
	for (char *part = strtok(list, ","); part; part = strtok(NULL, ",")) {
		char err[512];
		if (sets == SETS_MAX)
			return pool_cli_usage_error(PROGRAM, "--models: at most %d sets", SETS_MAX);
		models[sets] = pool_default_models();
		if (pool_models_parse_spec(&models[sets], part, err, sizeof err))
			return pool_cli_usage_error(PROGRAM, "--models: %s", err);
		snprintf(names[sets], sizeof names[sets], "%.63s", part);
		++sets;
	}
	if (sets == 0)
		return pool_cli_usage_error(PROGRAM, "%s", "--models: no model set");

	pool_sim_def def = pool_default_sim_def();
	pool_ball_state rack[RACK];
	const int n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 1e-4, rack, RACK);
	pool_sim *sim = NULL;
	pool_error err;
	if (n != RACK || pool_sim_create(&def, &sim, &err) != POOL_OK)
		return fprintf(stderr, "%s: cannot set the break up\n", PROGRAM), 1;
	break_figures *fig = malloc(sizeof *fig * (size_t)o.breaks * (size_t)sets);
	double *scratch = malloc(sizeof *scratch * (size_t)o.breaks * (RACK - 1));
	if (!fig || !scratch)
		return fprintf(stderr, "%s: out of memory\n", PROGRAM), 1;

	char cpu[256];
	printf("machine: %s, %ld cores online; %ld breaks per model set: 8-ball rack, 0.1 mm gaps, %.3g m/s, "
	       "2 deg elevation, aim +-0.5 deg (seed %ld)\n",
	       pool_bench_cpu_model(cpu, sizeof cpu), pool_bench_cpus_online(), o.breaks, o.speed, o.seed);
	printf("%-18s %11s %9s %9s %9s %10s %10s %8s %9s %11s %9s\n", "models", "median disp", "moved>0.3", "cushion",
	       "pocketed", "breaks>=1", "cue dist", "scratch", "events", "time med", "time min");
	for (int k = 0; k < sets; ++k) {
		def.models = models[k];
		double sum_moved = 0.0, sum_cushion = 0.0, sum_pocketed = 0.0, any = 0.0, scratches = 0.0;
		for (long i = 0; i < o.breaks; ++i) {
			break_figures *f = &fig[(size_t)k * (size_t)o.breaks + (size_t)i];
			if (run_break(sim, &def, rack, n, o.speed, 0.5 * jitter((uint64_t)o.seed, i), f))
				return 1;
			sum_moved += f->moved;
			sum_cushion += f->cushioned;
			sum_pocketed += f->pocketed;
			any += f->pocketed > 0;
			scratches += f->scratched;
		}
		const break_figures *F = &fig[(size_t)k * (size_t)o.breaks];
		for (long i = 0; i < o.breaks; ++i)
			memcpy(&scratch[(size_t)i * (RACK - 1)], F[i].displacement, sizeof F[i].displacement);
		const double disp = median_of(scratch, (size_t)o.breaks * (RACK - 1));
		for (long i = 0; i < o.breaks; ++i)
			scratch[i] = F[i].cue_distance;
		const double cue = median_of(scratch, (size_t)o.breaks);
		for (long i = 0; i < o.breaks; ++i)
			scratch[i] = F[i].events;
		const double events = median_of(scratch, (size_t)o.breaks);
		for (long i = 0; i < o.breaks; ++i)
			scratch[i] = F[i].seconds;
		const pool_bench_summary t = pool_bench_summarise(scratch, (size_t)o.breaks);
		const double N = (double)o.breaks;
		printf("%-18s %9.3f m %9.2f %9.2f %9.2f %9.0f %% %8.3f m %6.1f %% %9.0f %8.1f us %6.1f us\n", names[k], disp,
		       sum_moved / N, sum_cushion / N, sum_pocketed / N, 100.0 * any / N, cue, 100.0 * scratches / N, events,
		       1e6 * t.median, 1e6 * t.min);
	}
	pool_sim_destroy(sim);

	int rc = 0;
	if (o.json) {
		pool_jw w;
		pool_jw_init(&w, true);
		pool_jw_object(&w, false);
		pool_jw_key(&w, "format");
		pool_jw_string(&w, "libpool-breaks/1");
		pool_jw_key(&w, "machine");
		pool_jw_string(&w, cpu);
		pool_jw_key(&w, "breaks");
		pool_jw_int(&w, (int)o.breaks);
		pool_jw_key(&w, "seed");
		pool_jw_int(&w, (int)o.seed);
		pool_jw_key(&w, "speed");
		pool_jw_number(&w, o.speed);
		pool_jw_key(&w, "sets");
		pool_jw_array(&w, false);
		for (int k = 0; k < sets; ++k) {
			const break_figures *F = &fig[(size_t)k * (size_t)o.breaks];
			pool_jw_object(&w, false);
			pool_jw_key(&w, "name");
			pool_jw_string(&w, names[k]);
			pool_jw_models(&w, &models[k]);
			static const char *const keys[] = {"moved", "cushion", "pocketed", "cue_distance", "scratch", "events"};
			for (int q = 0; q < 6; ++q) {
				pool_jw_key(&w, keys[q]);
				pool_jw_array(&w, true);
				for (long i = 0; i < o.breaks; ++i) {
					const double v[6] = {F[i].moved, F[i].cushioned, F[i].pocketed, F[i].cue_distance, F[i].scratched,
					                     F[i].events};
					pool_jw_number(&w, v[q]);
				}
				pool_jw_end(&w, ']');
			}
			pool_jw_key(&w, "displacement");
			pool_jw_array(&w, true);
			for (long i = 0; i < o.breaks; ++i)
				for (int b = 0; b < RACK - 1; ++b)
					pool_jw_number(&w, F[i].displacement[b]);
			pool_jw_end(&w, ']');
			pool_jw_end(&w, '}');
		}
		pool_jw_end(&w, ']');
		pool_jw_end(&w, '}');
		char *text = pool_jw_finish(&w);
		FILE *out = text ? fopen(o.json, "w") : NULL;
		if (!out || fputs(text, out) < 0 || fputc('\n', out) < 0) {
			fprintf(stderr, "%s: --json: cannot write %s\n", PROGRAM, o.json);
			rc = 1;
		}
		if (out && fclose(out) != 0)
			rc = 1;
		free(text);
	}
	free(fig);
	free(scratch);
	return rc;
}
