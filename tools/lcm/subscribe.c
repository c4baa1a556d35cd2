// pool-lcm-subscribe: an example LCM client that prints every event (POOL_EVENT) and every shot
// (POOL_SHOT) as it arrives, one line each. Also a handy way to watch pool-shot-server.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "cli.h"
#include "lcm_convert.h"
#include "lcm_service.h"

static const char usage_text[] =
	"usage: pool-lcm-subscribe [--lcm-url URL] [--count N] [--timeout S] [--states] [--help]\n"
	"\n"
	"Prints each pool_lcm.event_t on POOL_EVENT and each pool_lcm.shot_t on POOL_SHOT as it\n"
	"arrives, one line each:\n"
	"  event shot=ID seq=N t=T TYPE balls=ID,ID [rail=R] [pocket=P]\n"
	"  shot shot=ID request=ID events=N balls=N sim_time=T stop=REASON [error=\"...\"]\n"
	"\n"
	"  --lcm-url URL  LCM provider (default $LCM_DEFAULT_URL, else\n"
	"                 udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608)\n"
	"  --count N      exit after N shots (0 = run until interrupted)\n"
	"  --timeout S    exit with status 1 when no message arrived for S seconds\n"
	"  --states       also print playback frames on POOL_STATE (state t=T balls=N)\n"
	"  -h, --help     show this help\n";

static long shots_seen = 0;

static void on_event(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_event_t *msg,
                     void *user)
{
	(void)rbuf, (void)channel, (void)user;
	printf("event shot=%lld seq=%d t=%.17g %s balls=", (long long)msg->shot_id, msg->seq, msg->t,
	       msg->type);
	for (int i = 0; i < msg->num_balls; ++i) {
		printf("%s%d", i ? "," : "", msg->balls[i].id);
	}
	if (msg->rail[0]) {
		printf(" rail=%s", msg->rail);
	}
	if (msg->pocket[0]) {
		printf(" pocket=%s", msg->pocket);
	}
	printf("\n");
	fflush(stdout);
}

static void on_shot(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_shot_t *msg,
                    void *user)
{
	(void)rbuf, (void)channel, (void)user;
	printf("shot shot=%lld request=%lld events=%d balls=%d sim_time=%.17g stop=%s",
	       (long long)msg->shot_id, (long long)msg->request_id, msg->num_events, msg->num_balls,
	       msg->sim_time, msg->stop_reason[0] ? msg->stop_reason : "-");
	if (msg->error[0]) {
		printf(" error=\"%s\"", msg->error);
	}
	printf("\n");
	fflush(stdout);
	shots_seen++;
}

static void on_state(const lcm_recv_buf_t *rbuf, const char *channel,
                     const pool_lcm_table_state_t *msg, void *user)
{
	(void)rbuf, (void)channel, (void)user;
	printf("state shot=%lld t=%.6f balls=%d\n", (long long)msg->shot_id, msg->t, msg->num_balls);
	fflush(stdout);
}

int main(int argc, char **argv)
{
	const char *url = NULL;
	long count = 0;
	double timeout = 0.0;
	int states = 0;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		char *end = NULL;
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			fputs(usage_text, stdout);
			return 0;
		} else if (pool_lcm_url_option(argc, argv, &i, &url)) {
			continue;
		} else if (strcmp(a, "--count") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_count(argv[++i], &count)) {
				fprintf(stderr, "pool-lcm-subscribe: --count: '%s' is not a count >= 0\n", argv[i]);
				return 2;
			}
		} else if (strcmp(a, "--timeout") == 0 && i + 1 < argc) {
			timeout = strtod(argv[++i], &end);
			if (end == argv[i] || *end || !isfinite(timeout) || timeout < 0) {
				fprintf(stderr, "pool-lcm-subscribe: --timeout: '%s' is not seconds >= 0\n", argv[i]);
				return 2;
			}
		} else if (strcmp(a, "--states") == 0) {
			states = 1;
		} else {
			fprintf(stderr, "pool-lcm-subscribe: unknown or incomplete option '%s'\n"
			                "Try 'pool-lcm-subscribe --help'.\n", a);
			return 2;
		}
	}
	pool_lcm_catch_stop_signals();

	char err[256];
	lcm_t *lcm = pool_lcm_open(url, err, sizeof err);
	if (lcm == NULL) {
		fprintf(stderr, "pool-lcm-subscribe: %s\n", err);
		return 2;
	}
	pool_lcm_event_t_subscription_t *se = pool_lcm_event_t_subscribe(lcm, POOL_LCM_CHANNEL_EVENT,
	                                                                 on_event, NULL);
	pool_lcm_shot_t_subscription_t *ss = pool_lcm_shot_t_subscribe(lcm, POOL_LCM_CHANNEL_SHOT,
	                                                               on_shot, NULL);
	pool_lcm_table_state_t_subscription_t *st = NULL;
	if (states) {
		st = pool_lcm_table_state_t_subscribe(lcm, POOL_LCM_CHANNEL_STATE, on_state, NULL);
	}
	// liblcm keeps at most 30 received messages per subscription until lcm_handle takes them and
	// drops the rest silently; pool-sim publishes a shot's events in one burst, and --playback
	// frames come at up to 1000 Hz: room for bursts on every subscription.
	pool_lcm_event_t_subscription_set_queue_capacity(se, 10000);
	pool_lcm_shot_t_subscription_set_queue_capacity(ss, 10000);
	if (st != NULL) {
		pool_lcm_table_state_t_subscription_set_queue_capacity(st, 10000);
	}
	// Once this line is out, everything published reaches us (scripts and tests wait for it).
	fprintf(stderr, "pool-lcm-subscribe: subscribed on %s\n", pool_lcm_resolve_url(url));

	int status = 0;
	struct timespec last;
	clock_gettime(CLOCK_MONOTONIC, &last);
	while (!pool_lcm_stop_requested() && (count == 0 || shots_seen < count)) {
		int ready = pool_lcm_wait(lcm, 100);
		struct timespec now;
		clock_gettime(CLOCK_MONOTONIC, &now);
		if (ready < 0) {
			perror("pool-lcm-subscribe: poll");
			status = 1;
			break;
		}
		if (ready > 0) {
			lcm_handle(lcm);
			last = now;
		} else if (timeout > 0.0 &&
		           (double)(now.tv_sec - last.tv_sec) + 1e-9 * (double)(now.tv_nsec - last.tv_nsec) >
		               timeout) {
			fprintf(stderr, "pool-lcm-subscribe: nothing received for %g s\n", timeout);
			status = 1;
			break;
		}
	}
	pool_lcm_event_t_unsubscribe(lcm, se);
	pool_lcm_shot_t_unsubscribe(lcm, ss);
	if (st != NULL) {
		pool_lcm_table_state_t_unsubscribe(lcm, st);
	}
	lcm_destroy(lcm);
	return status;
}
