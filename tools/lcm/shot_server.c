// pool-shot-server: answers every shot_request_t on POOL_SHOT_REQUEST with a shot_t on POOL_SHOT
// carrying the same request_id. One simulation is reused for every request (pool_sim_reset via
// pool_scenario_setup), so a steady stream of shots does not allocate per request.
#define _POSIX_C_SOURCE 200809L
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "cli.h"
#include "lcm_convert.h"
#include "lcm_service.h"
#include "scenario.h"

#define EXIT_BAD_INPUT 2
#define EXIT_INTERNAL 1

static const char usage_text[] =
	"usage: pool-shot-server [--lcm-url URL] [--max-requests N] [--help]\n"
	"\n"
	"Answers every pool_lcm.shot_request_t on POOL_SHOT_REQUEST (a libpool-scenario/1 document)\n"
	"with a pool_lcm.shot_t on POOL_SHOT carrying the same request_id: every event and the final\n"
	"state of every ball, or `error` naming the offending field of a bad scenario. Undecodable\n"
	"datagrams are logged on standard error and skipped. Stops on SIGINT or SIGTERM and reports\n"
	"how many requests it answered.\n"
	"\n"
	"  --lcm-url URL       LCM provider (default $LCM_DEFAULT_URL, else\n"
	"                      udpm://239.255.76.67:7667?ttl=0)\n"
	"  --max-requests N    exit after answering N requests (0 = serve until a signal)\n"
	"  -h, --help          show this help\n";

/// What the handler needs between requests.
typedef struct server_state {
	lcm_t *lcm;
	pool_sim *sim;        // reused for every request
	int64_t last_shot_id; // shot ids strictly increase even within one microsecond
	long answered;        // shot_t published (errors included)
	long errors;          // answers carrying an error
	long undecodable;     // datagrams that were not a shot_request_t
	long publish_failures;
} server_state;

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

static void answer_request(server_state *s, const pool_lcm_shot_request_t *request)
{
	int64_t shot_id = next_shot_id(s);
	char err[512];
	pool_scenario scenario;
	const char *json = request->scenario_json;
	if (pool_scenario_parse(json, strlen(json), &scenario, err, sizeof err) != 0) {
		answer_error(s, shot_id, request->request_id, err);
		return;
	}
	pool_error perr = {{0}};
	pool_result r = pool_scenario_setup(&scenario, &s->sim, &perr);
	if (r == POOL_OK) {
		r = pool_sim_run(s->sim);
		if (r != POOL_OK) {
			snprintf(perr.message, sizeof perr.message, "simulation failed at t = %.17g s: %s",
			         pool_sim_time(s->sim), pool_result_str(r));
		}
	}
	pool_scenario_free(&scenario);
	if (r != POOL_OK) {
		answer_error(s, shot_id, request->request_id,
		             perr.message[0] ? perr.message : pool_result_str(r));
		return;
	}
	pool_lcm_shot_t shot;
	if (pool_lcm_shot_fill(s->sim, shot_id, request->request_id, pool_lcm_utime_now(), &shot) != 0) {
		answer_error(s, shot_id, request->request_id, "out of memory converting the shot");
		return;
	}
	publish_shot(s, &shot);
	pool_lcm_shot_release(&shot);
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
		} else {
			fprintf(stderr, "pool-shot-server: unknown or incomplete option '%s'\n"
			                "Try 'pool-shot-server --help'.\n", a);
			return EXIT_BAD_INPUT;
		}
	}

	pool_lcm_catch_stop_signals();

	server_state s;
	memset(&s, 0, sizeof s);
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
	fprintf(stderr, "pool-shot-server: ready on %s, channel %s\n", pool_lcm_resolve_url(url),
	        POOL_LCM_CHANNEL_SHOT_REQUEST);

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
	        "datagrams, %ld publish failures\n",
	        s.answered, s.errors, s.undecodable, s.publish_failures);
	lcm_unsubscribe(s.lcm, sub);
	lcm_destroy(s.lcm);
	pool_sim_destroy(s.sim);
	return status;
}
