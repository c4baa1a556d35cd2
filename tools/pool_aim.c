// pool-aim: the best shots of a position, ranked by their chance of success under the noise of
// a real stroke (libpool planning, pool/aim.h). Prints the JSON list of docs/interfaces.md
// "Shot planning", best first; --svg draws them on the table. docs/commands.md "pool-aim".
// Exit status: 0 success (also when no shot is found: an empty list), 2 bad input or usage (the
// message names the option or field), 1 internal failure.
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aim/aim_tool.h"
#include "cli.h"
#include "read_input.h"

#define PROGRAM "pool-aim"
#define AIM_MAX_TOP 1000
#define AIM_MAX_SAMPLES 1000000L

typedef struct aim_options {
	const char *path;
	bool have_ball, have_cue;
	int32_t ball, cue;
	const char *pocket, *noise, *kinds;
	long samples, top, threads;
	unsigned long seed;
	double budget;
	bool position, distinct, summary, help;
	const char *output, *svg;
	size_t max_input;
} aim_options;

static const char usage_text[] =
	"usage: pool-aim SCENARIO.json [--ball ID] [--pocket NAME] [--noise fastfiz|none|SPEC] [-n SAMPLES]\n"
	"                [--top K] [--kinds LIST] [--cue ID] [--seed S] [--time-budget S] [--threads N]\n"
	"                [--position] [--distinct] [--svg FILE] [--summary] [-o FILE] [--max-input BYTES]\n"
	"\n"
	"Searches the shots that pot a ball of the scenario's position (its strike, if any, is ignored)\n"
	"and prints the best, best first, as a JSON list: the strike (degrees), the ball and pocket, the\n"
	"kind, p_success (the share of noisy repetitions that pot that ball in that pocket legally under\n"
	"the scenario's \"game\" rules, or without a scratch without them), its 95 % interval and\n"
	"samples, and where the cue ball ends.\n"
	"\n"
	"  --ball ID          pot this ball (default: any)\n"
	"  --pocket NAME      in this pocket: sw, se, nw, ne, s, n (default: any)\n"
	"  --noise SPEC       the stroke's noise: fastfiz (default), none, or NAME=SD pairs (speed m/s,\n"
	"                     phi and theta degrees, a and b m), e.g. speed=0.05,phi=0.2\n"
	"  -n, --samples N    noisy repetitions behind each reported p_success (default 400)\n"
	"  --top K            shots printed (default 5)\n"
	"  --kinds LIST       straight, bank, kick, combination, carom, comma-separated (default all)\n"
	"  --cue ID           the cue ball (default: the scenario's struck ball, the game's cue ball, 0)\n"
	"  --seed S           seed of the noise (default 1)\n"
	"  --time-budget S    stop searching after S seconds (default: none; with none the output\n"
	"                     depends only on the input, not on the threads or the machine)\n"
	"  --threads N        worker threads (default: the online CPUs)\n"
	"  --position         score where the cue ball ends: balls with a clear straight pot next\n"
	"  --distinct         one shot per ball, pocket, kind, second ball and cushion (its best speed\n"
	"                     and spin): K different shots\n"
	"  --svg FILE         draw the position and the shots found on the table\n"
	"  --summary          the search's figures and a table of the shots on standard error\n"
	"  -o, --output FILE  write the list to FILE (atomically) instead of standard output\n"
	"  --max-input BYTES  refuse a scenario longer than BYTES (default 64M)\n"
	"  -h, --help         show this help\n";

static int parse_id(const char *option, const char *v, int32_t *out) {
	char *end = NULL;
	long long id = strtoll(v, &end, 10);
	if (!v[0] || *end || id < INT32_MIN || id > INT32_MAX)
		return pool_cli_usage_error(PROGRAM, "%s: '%s' is not a ball id", option, pool_cli_arg(v));
	*out = (int32_t)id;
	return 0;
}

static int option(void *context, const char *a, const char *v) {
	aim_options *o = context;
	long n = 0;
	if (strcmp(a, "--position") == 0) {
		o->position = true;
	} else if (strcmp(a, "--distinct") == 0) {
		o->distinct = true;
	} else if (strcmp(a, "--summary") == 0) {
		o->summary = true;
	} else if (strcmp(a, "--ball") == 0) {
		o->have_ball = true;
		return parse_id(a, v, &o->ball);
	} else if (strcmp(a, "--cue") == 0) {
		o->have_cue = true;
		return parse_id(a, v, &o->cue);
	} else if (strcmp(a, "--pocket") == 0) {
		o->pocket = v;
	} else if (strcmp(a, "--noise") == 0) {
		o->noise = v;
	} else if (strcmp(a, "--kinds") == 0) {
		o->kinds = v;
	} else if (strcmp(a, "-n") == 0 || strcmp(a, "--samples") == 0) {
		if (!pool_cli_parse_count(v, &o->samples) || o->samples < 1 || o->samples > AIM_MAX_SAMPLES)
			return pool_cli_usage_error(PROGRAM, "%s: '%s' is not a number of samples from 1 to %ld", a, pool_cli_arg(v),
			                            AIM_MAX_SAMPLES);
	} else if (strcmp(a, "--top") == 0) {
		if (!pool_cli_parse_count(v, &o->top) || o->top < 1 || o->top > AIM_MAX_TOP)
			return pool_cli_usage_error(PROGRAM, "--top: '%s' is not a number of shots from 1 to %d", pool_cli_arg(v),
			                            AIM_MAX_TOP);
	} else if (strcmp(a, "--seed") == 0) {
		if (!pool_cli_parse_count(v, &n) || n < 1)
			return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number from 1", pool_cli_arg(v));
		o->seed = (unsigned long)n;
	} else if (strcmp(a, "--time-budget") == 0) {
		if (!pool_cli_parse_double(v, &o->budget) || o->budget <= 0.0 || o->budget > 1e6)
			return pool_cli_usage_error(PROGRAM, "--time-budget: '%s' is not a time in seconds (above 0)",
			                            pool_cli_arg(v));
	} else if (strcmp(a, "--threads") == 0) {
		if (!pool_cli_parse_count(v, &o->threads) || o->threads < 1 || o->threads > 1024)
			return pool_cli_usage_error(PROGRAM, "--threads: '%s' is not a number of threads from 1 to 1024",
			                            pool_cli_arg(v));
	} else if (strcmp(a, "--svg") == 0) {
		o->svg = v;
	} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
		o->output = v;
	} else if (strcmp(a, "--max-input") == 0) {
		return pool_cli_max_input(PROGRAM, v, &o->max_input);
	}
	return 0;
}

int main(int argc, char **argv) {
	aim_options o = {.seed = 1, .max_input = POOL_INPUT_DEFAULT_MAX};
	static const char *const flags[] = {"--position", "--distinct", "--summary", NULL};
	static const char *const with_value[] = {"--ball", "--cue",    "--pocket",  "--noise", "--kinds",       "-n",
	                                         "--samples", "--top", "--seed",    "--time-budget", "--threads",
	                                         "--svg",  "-o",       "--output",  "--max-input", NULL};
	int status = pool_cli_walk(PROGRAM, argc, argv, "scenario", flags, with_value, option, &o, &o.path, &o.help);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	if (!o.path)
		return pool_cli_usage_error(PROGRAM, "%s", "missing SCENARIO.json");
	char err[512], *text = NULL;
	size_t length = 0;
	if (pool_read_input(o.path, o.max_input, &text, &length, err, sizeof err) != 0) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return POOL_EXIT_BAD_INPUT;
	}
	aim_position position;
	status = aim_position_parse(text, length, &position, err, sizeof err);
	free(text);
	if (status) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return POOL_EXIT_BAD_INPUT;
	}
	pool_aim_def def = aim_position_def(&position);
	if (o.have_ball)
		def.ball = o.ball;
	if (o.have_cue)
		def.cue_ball = o.cue;
	if ((o.pocket && aim_parse_pocket(o.pocket, &def.pocket, err, sizeof err)) ||
	    (o.noise && aim_parse_noise(o.noise, &def.noise, err, sizeof err)) ||
	    (o.kinds && aim_parse_kinds(o.kinds, &def.kinds, err, sizeof err))) {
		aim_position_free(&position);
		return pool_cli_usage_error(PROGRAM, "--%s", err);
	}
	if (o.samples)
		def.samples = (int)o.samples;
	if (o.top)
		def.top = (int)o.top;
	def.seed = o.seed;
	def.time_budget = o.budget;
	def.threads = (int)o.threads;
	def.position = o.position;
	def.distinct = o.distinct;
	pool_aim_shot *shots = calloc((size_t)def.top, sizeof *shots);
	int count = 0;
	pool_aim_stats stats;
	pool_error e;
	pool_result r = shots ? pool_aim_search(&def, shots, def.top, &count, &stats, &e) : POOL_ERR_OUT_OF_MEMORY;
	if (r != POOL_OK) {
		fprintf(stderr, "%s: %s\n", PROGRAM, shots ? e.message : "out of memory");
		status = pool_cli_result_status(r);
	} else {
		char *json = aim_report_json(shots, count, def.cue_ball);
		status = json ? pool_cli_write_output(PROGRAM, o.output, json) : POOL_EXIT_INTERNAL;
		free(json);
		if (!status && o.svg) {
			char *svg = aim_svg(&def, shots, count);
			status = svg ? pool_cli_write_output(PROGRAM, o.svg, svg) : POOL_EXIT_INTERNAL;
			free(svg);
		}
		if (!status && o.summary) {
			char *summary = aim_report_text(shots, count, &stats);
			if (summary)
				fputs(summary, stderr);
			free(summary);
		}
		if (status == POOL_EXIT_INTERNAL)
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
	}
	free(shots);
	aim_position_free(&position);
	return status;
}
