// pool-aim-server: the shot planner on LCM. Answers every aim_request_t on POOL_AIM_REQUEST ("the
// best K shots for this table") with an aim_reply_t on POOL_AIM carrying the same request_id: the
// shots libpool planning finds (what pool-aim prints for the same position and options). A robot
// asks between shots and gets an answer within the time it allows.
//
// Requests are answered one after the other, each search using every core (--threads). A request's
// time budget counts from the moment liblcm received it (lcm_recv_buf_t.recv_utime), so time spent
// waiting behind another request is part of it: one whose budget is gone when it comes up is
// answered with an error (after its checks: a bad request hears what is wrong with it), and the
// search gets what is left. Requests beyond --max-balls or
// --max-samples, bad scenarios and bad options are answered with an error naming the field; a
// datagram that is not an aim_request_t is logged and skipped. SIGINT/SIGTERM stop the server
// after the request in hand.
#define _POSIX_C_SOURCE 200809L
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>

#include <lcm/lcm.h>

#include "aim/aim_tool.h"
#include "cli.h"
#include "lcm_service.h"
#include "pool_lcm_aim_reply_t.h"
#include "pool_lcm_aim_request_t.h"

#define PROGRAM "pool-aim-server"
#define REQUEST_CHANNEL "POOL_AIM_REQUEST"
#define REPLY_CHANNEL "POOL_AIM"
#define DEFAULT_TIME_BUDGET 1.0
#define DEFAULT_MAX_TIME_BUDGET 10.0
#define DEFAULT_MAX_BALLS 64L
#define DEFAULT_MAX_SAMPLES 10000L
#define MAX_TOP 100
// liblcm keeps this many requests waiting while one is searched (its default, 30, drops the rest
// without a word).
#define QUEUE_CAPACITY 1000

static const char usage_text[] =
	"usage: pool-aim-server [--lcm-url URL] [--time-budget S] [--max-time-budget S] [--max-balls N]\n"
	"                       [--max-samples N] [--threads N] [--max-requests N]\n"
	"\n"
	"Answers every aim_request_t on POOL_AIM_REQUEST with the best shots of its position, an\n"
	"aim_reply_t on POOL_AIM with the same request_id (docs/lcm.md \"The shot planner\").\n"
	"\n"
	"  --lcm-url URL         LCM URL (default: $LCM_DEFAULT_URL or the project's udpm URL)\n"
	"  --time-budget S       the budget of a request that gives none (default 1 s)\n"
	"  --max-time-budget S   the most any request gets, counted from its arrival (default 10 s)\n"
	"  --max-balls N         refuse positions of more balls (default 64)\n"
	"  --max-samples N       refuse requests of more samples per shot (default 10000)\n"
	"  --threads N           threads of each search (default: the online CPUs)\n"
	"  --max-requests N      exit after answering N requests (default: run until SIGINT/SIGTERM)\n"
	"  -h, --help            show this help\n";

typedef struct server {
	lcm_t *lcm;
	double default_budget, max_budget;
	long max_balls, max_samples, threads, max_requests, answered;
} server;

static double now_us(void) {
	struct timeval tv;
	gettimeofday(&tv, NULL);
	return (double)tv.tv_sec * 1e6 + (double)tv.tv_usec;
}

static void reply(server *sv, pool_lcm_aim_reply_t *msg) {
	msg->utime = (int64_t)now_us();
	if (pool_lcm_aim_reply_t_publish(sv->lcm, REPLY_CHANNEL, msg) != 0)
		fprintf(stderr, "%s: request %" PRId64 ": the reply could not be published\n", PROGRAM, msg->request_id);
	sv->answered++;
}

static void reply_error(server *sv, int64_t request_id, double arrived_us, const char *error) {
	pool_lcm_aim_reply_t msg = {.request_id = request_id, .seconds = (now_us() - arrived_us) * 1e-6,
	                            .error = (char *)error};
	reply(sv, &msg);
}

/// Checks a request's options and fills the search's def; 0, or -1 with the message in err.
static int apply_request(const server *sv, const pool_lcm_aim_request_t *rq, const aim_position *position,
                         pool_aim_def *def, double budget, char *err, size_t size) {
	*def = aim_position_def(position);
	if (position->scenario.ball_count > sv->max_balls) {
		snprintf(err, size, "balls: %d balls, the server takes at most %ld", position->scenario.ball_count,
		         sv->max_balls);
		return -1;
	}
	if (rq->has_ball)
		def->ball = rq->ball;
	if (rq->pocket[0] && aim_parse_pocket(rq->pocket, &def->pocket, err, size))
		return -1;
	if (rq->noise[0] && aim_parse_noise(rq->noise, &def->noise, err, size))
		return -1;
	if (rq->kinds[0] && aim_parse_kinds(rq->kinds, &def->kinds, err, size))
		return -1;
	if (rq->top < 0 || rq->top > MAX_TOP) {
		snprintf(err, size, "top: %d is not a number of shots from 1 to %d (0: 5)", (int)rq->top, MAX_TOP);
		return -1;
	}
	if (rq->samples < 0 || rq->samples > sv->max_samples) {
		snprintf(err, size, "samples: %d is not a number of samples from 1 to %ld (0: 400)", (int)rq->samples,
		         sv->max_samples);
		return -1;
	}
	if (!isfinite(rq->time_budget) || rq->time_budget < 0.0) {
		snprintf(err, size, "time_budget: must be a time in seconds >= 0 (0: the server's default)");
		return -1;
	}
	if (rq->top)
		def->top = rq->top;
	if (rq->samples)
		def->samples = rq->samples;
	if (rq->seed)
		def->seed = (uint64_t)rq->seed;
	def->time_budget = budget;
	def->threads = (int)sv->threads;
	def->position = rq->position;
	def->distinct = rq->distinct;
	return 0;
}

static void on_request(const lcm_recv_buf_t *rbuf, const char *channel, const pool_lcm_aim_request_t *rq, void *user) {
	(void)channel;
	server *sv = user;
	const double arrived = (double)rbuf->recv_utime;
	const double budget = rq->time_budget > 0.0 ? fmin(rq->time_budget, sv->max_budget) : sv->default_budget;
	// A bad request is told what is wrong with it, even when its time ran out in the queue (the
	// checks take microseconds).
	char err[512];
	aim_position position;
	if (aim_position_parse(rq->scenario_json, strlen(rq->scenario_json), &position, err, sizeof err) != 0) {
		reply_error(sv, rq->request_id, arrived, err);
		return;
	}
	pool_aim_def def;
	pool_error invalid = {{0}};
	int bad = apply_request(sv, rq, &position, &def, budget, err, sizeof err);
	if (!bad && pool_aim_def_validate(&def, &invalid) != POOL_OK) {
		snprintf(err, sizeof err, "%s", invalid.message);
		bad = -1;
	}
	if (bad) {
		reply_error(sv, rq->request_id, arrived, err);
		aim_position_free(&position);
		return;
	}
	def.time_budget = budget - (now_us() - arrived) * 1e-6;
	if (def.time_budget <= 0.0) {
		snprintf(err, sizeof err, "time_budget: %g s ran out while the request waited", budget);
		reply_error(sv, rq->request_id, arrived, err);
		aim_position_free(&position);
		return;
	}
	pool_aim_shot *shots = calloc((size_t)def.top, sizeof *shots);
	pool_lcm_aim_shot_t *out = calloc((size_t)def.top, sizeof *out);
	char (*pockets)[4] = calloc((size_t)def.top, sizeof *pockets);
	int count = 0;
	pool_aim_stats stats = {0};
	pool_error e = {{0}};
	pool_result r = shots && out && pockets ? pool_aim_search(&def, shots, def.top, &count, &stats, &e)
	                                        : POOL_ERR_OUT_OF_MEMORY;
	if (r != POOL_OK) {
		reply_error(sv, rq->request_id, arrived, e.message[0] ? e.message : pool_result_str(r));
	} else {
		const double deg = 180.0 / 3.14159265358979323846;
		for (int k = 0; k < count; ++k) {
			const pool_aim_shot *s = &shots[k];
			snprintf(pockets[k], sizeof pockets[k], "%s", pool_pocket_name(s->pocket));
			out[k] = (pool_lcm_aim_shot_t){
				.speed = s->strike.speed, .phi = s->strike.phi * deg, .theta = s->strike.theta * deg,
				.a = s->strike.a, .b = s->strike.b, .ball = s->ball, .pocket = pockets[k],
				.kind = (char *)pool_aim_kind_name(s->kind), .has_via = s->via != POOL_AIM_NO_BALL,
				.via = s->via != POOL_AIM_NO_BALL ? s->via : 0,
				.rail = (char *)(s->rail == POOL_RAIL_NONE ? "" : pool_rail_name(s->rail)), .p_success = s->p_success,
				.ci_low = s->ci_low, .ci_high = s->ci_high, .samples = s->samples,
				.cue_final = {s->cue_final.x, s->cue_final.y}, .position = s->position};
		}
		pool_lcm_aim_reply_t msg = {.request_id = rq->request_id, .num_shots = count, .shots = out,
		                            .candidates = stats.candidates, .potting = stats.potting,
		                            .simulations = stats.simulations, .seconds = (now_us() - arrived) * 1e-6,
		                            .budget_reached = stats.budget_reached, .error = ""};
		reply(sv, &msg);
	}
	free(shots);
	free(out);
	free(pockets);
	aim_position_free(&position);
}

static int parse(int argc, char **argv, server *sv, const char **url) {
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			fputs(usage_text, stdout);
			exit(0);
		}
		if (pool_lcm_url_option(argc, argv, &i, url))
			continue;
		if (i + 1 >= argc)
			return pool_cli_usage_error(PROGRAM, "unknown option or missing value: '%s'", pool_cli_arg(a));
		const char *v = argv[++i];
		double x = 0.0;
		long n = 0;
		if (strcmp(a, "--time-budget") == 0 || strcmp(a, "--max-time-budget") == 0) {
			if (!pool_cli_parse_double(v, &x) || x <= 0.0 || x > 3600.0)
				return pool_cli_usage_error(PROGRAM, "%s: '%s' is not a time in seconds (above 0, at most 3600)", a,
				                            pool_cli_arg(v));
			*(strcmp(a, "--time-budget") == 0 ? &sv->default_budget : &sv->max_budget) = x;
		} else if (strcmp(a, "--max-balls") == 0 || strcmp(a, "--max-samples") == 0 || strcmp(a, "--threads") == 0 ||
		           strcmp(a, "--max-requests") == 0) {
			if (!pool_cli_parse_count(v, &n) || n < 1 || n > 100000000L)
				return pool_cli_usage_error(PROGRAM, "%s: '%s' is not a whole number from 1", a, pool_cli_arg(v));
			*(strcmp(a, "--max-balls") == 0     ? &sv->max_balls
			  : strcmp(a, "--max-samples") == 0 ? &sv->max_samples
			  : strcmp(a, "--threads") == 0     ? &sv->threads
			                                    : &sv->max_requests) = n;
		} else {
			return pool_cli_usage_error(PROGRAM, "unknown option '%s'", pool_cli_arg(a));
		}
	}
	if (sv->default_budget > sv->max_budget)
		sv->default_budget = sv->max_budget;
	return 0;
}

int main(int argc, char **argv) {
	server sv = {.default_budget = DEFAULT_TIME_BUDGET, .max_budget = DEFAULT_MAX_TIME_BUDGET,
	             .max_balls = DEFAULT_MAX_BALLS, .max_samples = DEFAULT_MAX_SAMPLES};
	const char *url = NULL;
	int status = parse(argc, argv, &sv, &url);
	if (status)
		return status;
	char err[512];
	sv.lcm = pool_lcm_open(url, err, sizeof err);
	if (!sv.lcm) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return POOL_EXIT_BAD_INPUT;
	}
	pool_lcm_catch_stop_signals();
	pool_lcm_aim_request_t_subscription_t *sub =
	    pool_lcm_aim_request_t_subscribe(sv.lcm, REQUEST_CHANNEL, on_request, &sv);
	pool_lcm_aim_request_t_subscription_set_queue_capacity(sub, QUEUE_CAPACITY);
	fprintf(stderr, "%s: ready on channel %s (budget per request: %g s, at most %g s)\n", PROGRAM, REQUEST_CHANNEL,
	        sv.default_budget, sv.max_budget);
	while (!pool_lcm_stop_requested() && (!sv.max_requests || sv.answered < sv.max_requests)) {
		int ready = pool_lcm_wait(sv.lcm, 200);
		if (ready < 0) {
			status = POOL_EXIT_INTERNAL;
			break;
		}
		if (ready > 0 && lcm_handle(sv.lcm) != 0)
			fprintf(stderr, "%s: a datagram on %s could not be read as an aim_request_t\n", PROGRAM, REQUEST_CHANNEL);
	}
	pool_lcm_aim_request_t_unsubscribe(sv.lcm, sub);
	lcm_destroy(sv.lcm);
	return status;
}
