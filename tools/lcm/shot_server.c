// pool-shot-server: answers every shot_request_t on POOL_SHOT_REQUEST with a shot_t on POOL_SHOT
// carrying the same request_id. One simulation is reused for every request (pool_sim_reset via
// pool_scenario_setup), so a steady stream of shots does not allocate per request; after a shot
// that grew it past RETAIN_EVENTS events it is freed, so one huge shot does not pin its memory.
//
// Every request has a budget: at most --max-balls balls, at most --max-events events (capping the
// scenario's own options.max_events) and --max-shot-seconds of wall time. The shot is stepped in
// chunks of STEP_CHUNK events; between chunks the server checks the clock and the stop flag, so a
// request over budget is answered with an error, and SIGINT/SIGTERM abandon a running shot at
// once. An answer whose encoding would exceed --max-answer-bytes (LCM over UDP multicast loses
// messages larger than the receivers' socket buffers) is replaced by one carrying the final
// states and an error saying so.
#define _POSIX_C_SOURCE 200809L
#include <inttypes.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "cli.h"
#include "lcm_convert.h"
#include "lcm_service.h"
#include "scenario.h"

#define EXIT_BAD_INPUT 2
#define EXIT_INTERNAL 1

#define DEFAULT_MAX_SHOT_SECONDS 10.0
#define DEFAULT_MAX_EVENTS 1000000L
#define DEFAULT_MAX_BALLS 2000L
#define DEFAULT_MAX_ANSWER_BYTES 4194304L
/// Smallest accepted --max-answer-bytes: room for an error answer.
#define MIN_MAX_ANSWER_BYTES 512L
/// Events stepped between two looks at the clock and the stop flag (a step of a 2000-ball shot
/// takes well under a millisecond).
#define STEP_CHUNK 16
/// A simulation that held more events than this is freed after the shot instead of reused.
#define RETAIN_EVENTS 100000

static const char usage_text[] =
	"usage: pool-shot-server [--lcm-url URL] [--max-requests N] [--max-shot-seconds S]\n"
	"                        [--max-events N] [--max-balls N] [--max-answer-bytes N] [--help]\n"
	"\n"
	"Answers every pool_lcm.shot_request_t on POOL_SHOT_REQUEST (a libpool-scenario/1 document)\n"
	"with a pool_lcm.shot_t on POOL_SHOT carrying the same request_id: every event and the final\n"
	"state of every ball, or `error` naming the offending field of a bad scenario or the limit a\n"
	"request exceeded. Undecodable datagrams are logged on standard error and skipped. Stops on\n"
	"SIGINT or SIGTERM (abandoning a shot in progress) and reports how many requests it answered.\n"
	"\n"
	"  --lcm-url URL           LCM provider (default $LCM_DEFAULT_URL, else\n"
	"                          udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608)\n"
	"  --max-requests N        exit after answering N requests (0 = serve until a signal)\n"
	"  --max-shot-seconds S    wall time one request may take, parsing included (default 10)\n"
	"  --max-events N          events one shot may take; caps the scenario's options.max_events\n"
	"                          (default 1000000)\n"
	"  --max-balls N           balls one scenario may hold (default 2000)\n"
	"  --max-answer-bytes N    largest answer sent; a larger one is replaced by the final states\n"
	"                          and an error (default 4194304 = 4 MiB)\n"
	"  -h, --help              show this help\n";

/// The per-request budget (command-line options).
typedef struct server_limits {
	double max_shot_seconds;
	long max_events;
	long max_balls;
	long max_answer_bytes;
} server_limits;

/// What the handler needs between requests.
typedef struct server_state {
	lcm_t *lcm;
	server_limits limits;
	pool_sim *sim;        // reused for every request
	int64_t last_shot_id; // shot ids strictly increase even within one microsecond
	long answered;        // shot_t published (errors included)
	long errors;          // answers carrying an error (the three counts below included)
	long over_budget;     // requests over --max-shot-seconds, --max-events or --max-balls
	long oversized;       // answers over --max-answer-bytes, replaced by the final states
	long abandoned;       // shots given up because a stop signal arrived
	long undecodable;     // datagrams that were not a shot_request_t
	long publish_failures;
} server_state;

static double monotonic_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int64_t next_shot_id(server_state *s)
{
	int64_t now = pool_lcm_utime_now();
	s->last_shot_id = now > s->last_shot_id ? now : s->last_shot_id + 1;
	return s->last_shot_id;
}

static void publish_shot(server_state *s, const pool_lcm_shot_t *shot)
{
	if (pool_lcm_shot_t_publish(s->lcm, POOL_LCM_CHANNEL_SHOT, shot) != 0) {
		s->publish_failures++;
		fprintf(stderr, "pool-shot-server: could not publish the answer to request %lld\n",
		        (long long)shot->request_id);
	}
	s->answered++;
}

static void answer_error(server_state *s, int64_t shot_id, int64_t request_id, const char *message)
{
	pool_lcm_shot_t shot;
	s->errors++;
	if (pool_lcm_shot_fill_error(shot_id, request_id, pool_lcm_utime_now(), message, &shot) != 0) {
		fprintf(stderr, "pool-shot-server: out of memory answering request %lld\n",
		        (long long)request_id);
		return;
	}
	publish_shot(s, &shot);
	pool_lcm_shot_release(&shot);
}

/// How stepping a shot ended.
typedef enum run_outcome {
	RUN_DONE,        // the shot is over (rest, max_time or max_events)
	RUN_FAILED,      // libpool returned an error (message in err)
	RUN_OVER_TIME,   // --max-shot-seconds ran out (message in err)
	RUN_STOPPED,     // a stop signal arrived
} run_outcome;

// Steps the shot in chunks of STEP_CHUNK events, looking at the stop flag and the clock between
// chunks. started: monotonic time the request was taken up.
static run_outcome run_budgeted(server_state *s, double started, char *err, size_t err_size)
{
	for (;;) {
		for (int k = 0; k < STEP_CHUNK; ++k) {
			int status = pool_sim_step(s->sim);
			if (status < 0) {
				snprintf(err, err_size, "simulation failed at t = %.17g s: %s",
				         pool_sim_time(s->sim), pool_result_str((pool_result)status));
				return RUN_FAILED;
			}
			if (status == 0) {
				return RUN_DONE;
			}
		}
		if (pool_lcm_stop_requested()) {
			return RUN_STOPPED;
		}
		if (monotonic_s() - started > s->limits.max_shot_seconds) {
			int count = 0;
			pool_sim_events(s->sim, &count);
			snprintf(err, err_size,
			         "shot exceeded the server's budget of %g s (--max-shot-seconds): stopped "
			         "after %d events at t = %.6g s",
			         s->limits.max_shot_seconds, count, pool_sim_time(s->sim));
			return RUN_OVER_TIME;
		}
	}
}

// Publishes the shot, or, when its encoding would exceed --max-answer-bytes, an answer carrying
// the final states (when they fit) and an error giving the size.
static void answer_shot(server_state *s, int64_t shot_id, int64_t request_id)
{
	pool_lcm_shot_t shot;
	int64_t events_size = pool_lcm_shot_events_encoded_size(s->sim);
	if (events_size < 0 ||
	    pool_lcm_shot_fill_final(s->sim, shot_id, request_id, pool_lcm_utime_now(), &shot) != 0) {
		answer_error(s, shot_id, request_id, "out of memory converting the shot");
		return;
	}
	int64_t size = (int64_t)pool_lcm_shot_t_encoded_size(&shot) + events_size;
	if (size <= s->limits.max_answer_bytes) {
		pool_lcm_shot_release(&shot);
		if (pool_lcm_shot_fill(s->sim, shot_id, request_id, shot.utime, &shot) != 0) {
			answer_error(s, shot_id, request_id, "out of memory converting the shot");
			return;
		}
		publish_shot(s, &shot);
		pool_lcm_shot_release(&shot);
		return;
	}
	int count = 0;
	pool_sim_events(s->sim, &count);
	char message[400];
	snprintf(message, sizeof message,
	         "the answer of %" PRId64 " bytes (%d events) exceeds the server's limit of %ld bytes "
	         "(--max-answer-bytes); final states only",
	         size, count, s->limits.max_answer_bytes);
	if (pool_lcm_shot_set_error(&shot, message) != 0) {
		pool_lcm_shot_release(&shot);
		answer_error(s, shot_id, request_id, "out of memory converting the shot");
		return;
	}
	if (pool_lcm_shot_t_encoded_size(&shot) > s->limits.max_answer_bytes) {
		// Even the final states do not fit: the error alone.
		snprintf(message, sizeof message,
		         "the answer of %" PRId64 " bytes (%d events) exceeds the server's limit of %ld "
		         "bytes (--max-answer-bytes); the %d final states do not fit either",
		         size, count, s->limits.max_answer_bytes, shot.num_balls);
		pool_lcm_shot_release(&shot);
		s->oversized++;
		answer_error(s, shot_id, request_id, message);
		return;
	}
	fprintf(stderr, "pool-shot-server: request %lld: %s\n", (long long)request_id, message);
	s->oversized++;
	s->errors++;
	publish_shot(s, &shot);
	pool_lcm_shot_release(&shot);
}

// Frees the simulation after a shot that made it large, so its memory goes back to the system.
static void trim_sim(server_state *s)
{
	int count = 0;
	if (s->sim != NULL) {
		pool_sim_events(s->sim, &count);
	}
	if (count > RETAIN_EVENTS) {
		pool_sim_destroy(s->sim);
		s->sim = NULL;
	}
}

static void answer_request(server_state *s, const pool_lcm_shot_request_t *request)
{
	double started = monotonic_s();
	int64_t shot_id = next_shot_id(s);
	char err[512];
	pool_scenario scenario;
	const char *json = request->scenario_json;
	if (pool_scenario_parse(json, strlen(json), &scenario, err, sizeof err) != 0) {
		answer_error(s, shot_id, request->request_id, err);
		return;
	}
	if (scenario.ball_count > s->limits.max_balls) {
		snprintf(err, sizeof err, "balls: %d balls, more than the server's limit of %ld "
		         "(--max-balls)", scenario.ball_count, s->limits.max_balls);
		pool_scenario_free(&scenario);
		s->over_budget++;
		answer_error(s, shot_id, request->request_id, err);
		return;
	}
	// The scenario may ask for fewer events than the server allows, never more.
	bool capped = scenario.def.max_events > s->limits.max_events;
	if (capped) {
		scenario.def.max_events = (int)s->limits.max_events;
	}
	pool_error perr = {{0}};
	pool_result r = pool_scenario_setup(&scenario, &s->sim, &perr);
	pool_scenario_free(&scenario);
	if (r != POOL_OK) {
		answer_error(s, shot_id, request->request_id,
		             perr.message[0] ? perr.message : pool_result_str(r));
		return;
	}
	run_outcome outcome = run_budgeted(s, started, err, sizeof err);
	if (outcome == RUN_DONE && capped && pool_sim_stop_reason(s->sim) == POOL_STOP_MAX_EVENTS) {
		snprintf(err, sizeof err,
		         "shot exceeded the server's budget of %ld events (--max-events) at t = %.6g s",
		         s->limits.max_events, pool_sim_time(s->sim));
		outcome = RUN_OVER_TIME; // over budget, like the time limit
	}
	switch (outcome) {
	case RUN_DONE:
		answer_shot(s, shot_id, request->request_id);
		break;
	case RUN_FAILED:
		answer_error(s, shot_id, request->request_id, err);
		break;
	case RUN_OVER_TIME:
		fprintf(stderr, "pool-shot-server: request %lld: %s\n", (long long)request->request_id,
		        err);
		s->over_budget++;
		answer_error(s, shot_id, request->request_id, err);
		break;
	case RUN_STOPPED:
		s->abandoned++;
		answer_error(s, shot_id, request->request_id,
		             "shot abandoned: the server is stopping (SIGINT/SIGTERM)");
		break;
	}
	trim_sim(s);
}

// Raw handler rather than lcm-gen's typed one: a datagram that does not decode must be counted
// and logged, and its framing checked before lcm-gen's decoder trusts it.
static void on_request(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
	(void)channel;
	server_state *s = user;
	pool_lcm_shot_request_t request;
	char err[256];
	if (pool_lcm_request_decode(rbuf->data, rbuf->data_size, &request, err, sizeof err) != 0) {
		s->undecodable++;
		fprintf(stderr, "pool-shot-server: %s (skipped)\n", err);
		return;
	}
	answer_request(s, &request);
	pool_lcm_shot_request_t_decode_cleanup(&request);
}

int main(int argc, char **argv)
{
	const char *url = NULL;
	long max_requests = 0;
	server_limits limits = {DEFAULT_MAX_SHOT_SECONDS, DEFAULT_MAX_EVENTS, DEFAULT_MAX_BALLS,
	                        DEFAULT_MAX_ANSWER_BYTES};
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			fputs(usage_text, stdout);
			return 0;
		} else if (pool_lcm_url_option(argc, argv, &i, &url)) {
			continue;
		} else if (strcmp(a, "--max-requests") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_count(argv[++i], &max_requests)) {
				fprintf(stderr, "pool-shot-server: --max-requests: '%s' is not a count >= 0\n",
				        argv[i]);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-shot-seconds") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_double(argv[++i], &limits.max_shot_seconds) ||
			    !(limits.max_shot_seconds > 0.0)) {
				fprintf(stderr, "pool-shot-server: --max-shot-seconds: '%s' is not a time > 0 "
				                "in seconds\n", argv[i]);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-events") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_count(argv[++i], &limits.max_events) || limits.max_events < 1 ||
			    limits.max_events > INT_MAX) {
				fprintf(stderr, "pool-shot-server: --max-events: '%s' is not a count in 1..%d\n",
				        argv[i], INT_MAX);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-balls") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_count(argv[++i], &limits.max_balls) || limits.max_balls < 1) {
				fprintf(stderr, "pool-shot-server: --max-balls: '%s' is not a count >= 1\n",
				        argv[i]);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-answer-bytes") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_count(argv[++i], &limits.max_answer_bytes) ||
			    limits.max_answer_bytes < MIN_MAX_ANSWER_BYTES ||
			    limits.max_answer_bytes > INT_MAX) {
				fprintf(stderr, "pool-shot-server: --max-answer-bytes: '%s' is not a size in "
				                "%ld..%d bytes\n", argv[i], MIN_MAX_ANSWER_BYTES, INT_MAX);
				return EXIT_BAD_INPUT;
			}
		} else {
			fprintf(stderr, "pool-shot-server: unknown or incomplete option '%s'\n"
			                "Try 'pool-shot-server --help'.\n", a);
			return EXIT_BAD_INPUT;
		}
	}

	pool_lcm_catch_stop_signals();

	server_state s;
	memset(&s, 0, sizeof s);
	s.limits = limits;
	char err[256];
	s.lcm = pool_lcm_open(url, err, sizeof err);
	if (s.lcm == NULL) {
		fprintf(stderr, "pool-shot-server: %s\n", err);
		return EXIT_BAD_INPUT;
	}
	lcm_subscription_t *sub = lcm_subscribe(s.lcm, POOL_LCM_CHANNEL_SHOT_REQUEST, on_request, &s);
	if (sub == NULL) {
		fprintf(stderr, "pool-shot-server: cannot subscribe to %s\n", POOL_LCM_CHANNEL_SHOT_REQUEST);
		lcm_destroy(s.lcm);
		return EXIT_INTERNAL;
	}
	// Bursts of requests wait in liblcm's queue (default 30) instead of being dropped.
	lcm_subscription_set_queue_capacity(sub, 100000);
	fprintf(stderr, "pool-shot-server: ready on %s, channel %s (budget per request: %g s, %ld "
	        "events, %ld balls, %ld-byte answers)\n", pool_lcm_resolve_url(url),
	        POOL_LCM_CHANNEL_SHOT_REQUEST, limits.max_shot_seconds, limits.max_events,
	        limits.max_balls, limits.max_answer_bytes);

	int status = 0;
	while (!pool_lcm_stop_requested() && (max_requests == 0 || s.answered < max_requests)) {
		// A timeout so a signal that arrives between the check and poll stops us within 200 ms.
		int ready = pool_lcm_wait(s.lcm, 200);
		if (ready < 0) {
			perror("pool-shot-server: poll");
			status = EXIT_INTERNAL;
			break;
		}
		if (ready > 0 && lcm_handle(s.lcm) != 0) {
			fprintf(stderr, "pool-shot-server: lcm_handle failed\n");
			status = EXIT_INTERNAL;
			break;
		}
	}

	fprintf(stderr,
	        "pool-shot-server: answered %ld requests (%ld with an error), skipped %ld undecodable "
	        "datagrams, %ld publish failures; %ld over budget, %ld answers over "
	        "--max-answer-bytes, %ld shots abandoned on stop\n",
	        s.answered, s.errors, s.undecodable, s.publish_failures, s.over_budget, s.oversized,
	        s.abandoned);
	lcm_unsubscribe(s.lcm, sub);
	lcm_destroy(s.lcm);
	pool_sim_destroy(s.sim);
	return status;
}
