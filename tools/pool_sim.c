// pool-sim: simulates one shot from a libpool-scenario/1 file and prints its libpool-result/1.
// Exit status: 0 success, 2 bad input or usage (message on stderr), 1 internal failure.
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "read_input.h"
#include "pool/scenario.h"
#include "view_page.h"
#ifdef POOL_HAVE_LCM
#include "sim_publish.h"
#endif

#define PROGRAM "pool-sim"

/// Command-line options. New options (e.g. an LCM URL, a playback rate) add a field here, a
/// case in parse_options and, if they watch the shot, an event hook.
typedef struct sim_options {
	const char *scenario_path; ///< "-" = standard input
	const char *output_path;   ///< NULL = standard output
	const char *view_path;     ///< NULL = no page; else the pool-view page of the result
	double sample_dt;          ///< s; > 0 adds sampled trajectories
	bool pretty;               ///< indented JSON
	bool summary;              ///< human-readable summary on standard error
	bool help;                 ///< print usage and exit 0
	bool lcm;                  ///< publish the shot on LCM (--lcm-url or --playback given)
	const char *lcm_url;       ///< NULL = $LCM_DEFAULT_URL, else POOL_LCM_DEFAULT_URL
	double playback_hz;        ///< > 0: real-time frames on POOL_STATE at this rate
	size_t max_input;          ///< bytes; a longer scenario input is refused
} sim_options;

/// Called after every event appended to the simulation (the strike included), in order.
typedef void (*sim_event_hook)(const pool_sim *sim, const pool_event *event, void *user);

static const char usage_text[] =
	"usage: pool-sim SCENARIO.json [-o RESULT.json] [--view PAGE.html] [--sample DT] [--pretty]\n"
	"                [--summary] [--max-input BYTES]\n"
	"\n"
	"Simulates one shot described by a libpool-scenario/1 file (\"-\" reads standard input)\n"
	"and prints its libpool-result/1 JSON.\n"
	"\n"
	"  -o, --output FILE  write the result to FILE instead of standard output (atomically:\n"
	"                     no file is left behind on failure)\n"
	"  --view PAGE.html   also write the shot as an animated page (pool-view), opened in\n"
	"                     any browser\n"
	"  --sample DT        add \"samples\": every ball's position every DT seconds and at\n"
	"                     every event (for plots and animations)\n"
	"  --pretty           indent the JSON\n"
	"  --summary          print events by type, pocketed balls and times on standard error\n"
	"  --max-input BYTES  refuse a scenario input longer than BYTES (suffix k, M or G for\n"
	"                     KiB, MiB, GiB; default 64M), from a file, a pipe or standard input\n"
	"  --lcm-url URL      publish each event on POOL_EVENT as it is produced and the shot on\n"
	"                     POOL_SHOT (default URL $LCM_DEFAULT_URL, else\n"
	"                     udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608)\n"
	"  --playback HZ      with LCM, run in real time and publish every ball on POOL_STATE HZ\n"
	"                     times per simulated second (HZ at most 1000)\n"
	"  -h, --help         show this help\n"
	"\n"
	"Exit status: 0 success, 2 bad input or usage (message names the field), 1 internal error.\n";

static int parse_options(int argc, char **argv, sim_options *o) {
	memset(o, 0, sizeof *o);
	o->max_input = POOL_INPUT_DEFAULT_MAX;
	bool only_files = false;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		if (only_files || a[0] != '-' || strcmp(a, "-") == 0) {
			if (o->scenario_path)
				return pool_cli_usage_error(PROGRAM, "unexpected argument '%s' (one scenario per run)",
				                            pool_cli_arg(a));
			o->scenario_path = a;
		} else if (strcmp(a, "--") == 0) {
			only_files = true;
		} else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			o->help = true;
		} else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
			if (i + 1 >= argc)
				return pool_cli_usage_error(PROGRAM, "option %s needs a file name", a);
			o->output_path = argv[++i];
		} else if (strcmp(a, "--view") == 0) {
			if (i + 1 >= argc)
				return pool_cli_usage_error(PROGRAM, "option %s needs a file name", a);
			o->view_path = argv[++i];
		} else if (strcmp(a, "--sample") == 0) {
			if (i + 1 >= argc)
				return pool_cli_usage_error(PROGRAM, "option %s needs a time step in seconds", a);
			const char *value = argv[++i];
			if (!pool_cli_parse_double(value, &o->sample_dt) || o->sample_dt <= 0.0)
				return pool_cli_usage_error(PROGRAM, "--sample: '%s' is not a positive time step in seconds",
				                            pool_cli_arg(value));
		} else if (strcmp(a, "--max-input") == 0) {
			if (i + 1 >= argc)
				return pool_cli_usage_error(PROGRAM, "option %s needs a size in bytes", a);
			const char *value = argv[++i];
			if (!pool_parse_byte_count(value, &o->max_input))
				return pool_cli_usage_error(PROGRAM, "--max-input: '%s' is not a size in bytes > 0 "
				                            "(e.g. 1000000, 512k, 64M, 1G)", pool_cli_arg(value));
		} else if (strcmp(a, "--pretty") == 0) {
			o->pretty = true;
		} else if (strcmp(a, "--summary") == 0) {
			o->summary = true;
		} else if (strcmp(a, "--lcm-url") == 0 || strcmp(a, "--playback") == 0) {
#ifndef POOL_HAVE_LCM
			return pool_cli_usage_error(PROGRAM, "option %s needs a pool-sim built with LCM", a);
#endif
			if (i + 1 >= argc)
				return pool_cli_usage_error(PROGRAM, "option %s needs a value", a);
			o->lcm = true;
			if (strcmp(a, "--lcm-url") == 0) {
				o->lcm_url = argv[++i];
				continue;
			}
			const char *value = argv[++i];
			if (!pool_cli_parse_double(value, &o->playback_hz) || o->playback_hz <= 0.0)
				return pool_cli_usage_error(PROGRAM, "--playback: '%s' is not a positive rate in Hz",
				                            pool_cli_arg(value));
#ifdef POOL_HAVE_LCM
			if (o->playback_hz > POOL_LCM_PLAYBACK_MAX_HZ)
				return pool_cli_usage_error(PROGRAM, "--playback: %s Hz is above the limit of %g Hz",
				                            pool_cli_arg(value),
				                            POOL_LCM_PLAYBACK_MAX_HZ);
#endif
		} else {
			return pool_cli_usage_error(PROGRAM, "unknown option '%s'", pool_cli_arg(a));
		}
	}
	if (!o->help && !o->scenario_path)
		return pool_cli_usage_error(PROGRAM, "%s", "missing SCENARIO.json");
	return 0;
}

/// Runs the shot event by event so a caller can watch (stream, pace) each event as it appears.
static pool_result run_shot(pool_sim *sim, sim_event_hook hook, void *user) {
	int seen = 0;
	for (;;) {
		int count = 0;
		const pool_event *events = pool_sim_events(sim, &count);
		for (; hook && seen < count; ++seen)
			hook(sim, &events[seen], user);
		int status = pool_sim_step(sim);
		if (status < 0)
			return (pool_result)status;
		if (status == 0)
			break;
	}
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	for (; hook && seen < count; ++seen)
		hook(sim, &events[seen], user);
	return POOL_OK;
}

static void print_summary(const pool_sim *sim, double cpu_seconds) {
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	int per_type[POOL_EVENT_LINK_END + 1] = {0};
	for (int i = 0; i < count; ++i)
		if ((int)events[i].type >= 0 && events[i].type <= POOL_EVENT_LINK_END)
			per_type[events[i].type]++;
	fprintf(stderr, "pool-sim: %d events, %.3f s simulated, stop: %s, cpu %.3f ms\n", count,
	        pool_sim_time(sim), pool_stop_reason_name(pool_sim_stop_reason(sim)),
	        cpu_seconds * 1e3);
	fprintf(stderr, "  events by type:");
	for (int t = 0; t <= POOL_EVENT_LINK_END; ++t)
		if (per_type[t])
			fprintf(stderr, " %s %d", pool_event_type_name((pool_event_type)t), per_type[t]);
	fprintf(stderr, "\n  pocketed:");
	int pocketed = 0;
	for (int i = 0; i < count; ++i) {
		if (events[i].type != POOL_EVENT_POCKET && events[i].type != POOL_EVENT_OFF_TABLE)
			continue;
		const pool_ball_state *after = pool_sim_event_states(sim, &events[i]);
		const char *where = events[i].type == POOL_EVENT_POCKET ? pool_pocket_name(events[i].pocket)
		                                                        : "off table";
		fprintf(stderr, " ball %d (%s, t=%.3f s)", (int)after[0].id, where ? where : "?",
		        events[i].time);
		pocketed++;
	}
	fprintf(stderr, "%s\n", pocketed ? "" : " none");
}

int main(int argc, char **argv) {
	sim_options o;
	int status = parse_options(argc, argv, &o);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}

	pool_scenario scenario;
	char err[512];
	if (pool_scenario_load_file_limit(o.scenario_path, o.max_input, &scenario, err, sizeof err) != 0) {
		fprintf(stderr, "pool-sim: %s\n", err);
		return POOL_EXIT_BAD_INPUT;
	}

	pool_sim *sim = NULL;
	pool_error perr = {{0}};
	pool_result r = pool_scenario_setup(&scenario, &sim, &perr);
	if (r != POOL_OK) {
		// The parser already ran these checks, so this is a rule it does not know about yet.
		fprintf(stderr, "pool-sim: %s\n", perr.message[0] ? perr.message : pool_result_str(r));
		pool_sim_destroy(sim);
		pool_scenario_free(&scenario);
		return pool_cli_result_status(r);
	}

	sim_event_hook hook = NULL;
	void *hook_user = NULL;
#ifdef POOL_HAVE_LCM
	pool_lcm_sim_publisher *publisher = NULL;
	if (o.lcm) {
		publisher = pool_lcm_sim_publisher_create(o.lcm_url, o.playback_hz, err, sizeof err);
		if (!publisher) {
			fprintf(stderr, "pool-sim: %s\n", err);
			pool_sim_destroy(sim);
			pool_scenario_free(&scenario);
			return POOL_EXIT_BAD_INPUT;
		}
		hook = pool_lcm_sim_publisher_event;
		hook_user = publisher;
		pool_lcm_sim_publisher_set_shot(publisher, &scenario.def, scenario.has_game ? &scenario.game : NULL);
	}
#endif
	clock_t start = clock();
	r = run_shot(sim, hook, hook_user);
#ifdef POOL_HAVE_LCM
	if (publisher) {
		bool published = r != POOL_OK ||
		                 pool_lcm_sim_publisher_finish(publisher, sim, err, sizeof err) == 0;
		pool_lcm_sim_publisher_destroy(publisher);
		if (!published) {
			fprintf(stderr, "pool-sim: %s\n", err);
			pool_sim_destroy(sim);
			pool_scenario_free(&scenario);
			return POOL_EXIT_INTERNAL;
		}
	}
#endif
	double cpu = (double)(clock() - start) / CLOCKS_PER_SEC;
	if (r != POOL_OK) {
		fprintf(stderr, "pool-sim: simulation failed at t = %.17g s: %s\n", pool_sim_time(sim),
		        pool_sim_last_error(sim)[0] ? pool_sim_last_error(sim) : pool_result_str(r));
		pool_sim_destroy(sim);
		pool_scenario_free(&scenario);
		return POOL_EXIT_INTERNAL;
	}
	if (o.summary)
		print_summary(sim, cpu);

	pool_result_options ro = {.sample_dt = o.sample_dt, .pretty = o.pretty, .def = &scenario.def,
	                          .game = scenario.has_game ? &scenario.game : NULL};
	char *json = pool_result_json(sim, &ro);
	if (!json) {
		fprintf(stderr, "pool-sim: could not write the result (out of memory or sampling failed)\n");
		status = POOL_EXIT_INTERNAL;
	} else {
		status = pool_cli_write_output(PROGRAM, o.output_path, json);
	}
	if (status == 0 && o.view_path) {
		char *page = pool_view_page(json);
		if (!page) {
			fprintf(stderr, "pool-sim: could not write the page (out of memory)\n");
			status = POOL_EXIT_INTERNAL;
		} else {
			status = pool_cli_write_output(PROGRAM, o.view_path, page);
		}
		free(page);
	}
	free(json);
	pool_sim_destroy(sim);
	pool_scenario_free(&scenario);
	return status;
}
