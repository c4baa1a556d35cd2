// pool-shot-server: answers every shot_request_t on POOL_SHOT_REQUEST with a shot_t on POOL_SHOT
// carrying the same request_id. Each worker thread reuses one simulation for every request it
// takes (pool_sim_reset via pool_scenario_setup), so a steady stream of shots does not allocate per
// request; after a shot that grew it past RETAIN_EVENTS events, or one cut by a budget, it is
// freed, so one huge shot does not pin its memory.
//
// 1 + --workers threads (default 1 worker). The main one only receives: it takes each request off
// liblcm's queue as soon as liblcm has it, and either appends it to the server's own queue or,
// when that queue is full (--max-queue-requests, --max-queue-bytes), answers at once with an error
// starting "server busy:". So requests wait in a queue bounded in count and bytes, not in
// liblcm's (whose capacity, LCM_QUEUE_CAPACITY or --max-queue-requests if larger, is a backstop for
// bursts that arrive faster than the main thread can sort them). The workers share that one
// queue: each takes the oldest waiting request, simulates it on its own pool_sim (the library is
// thread-safe with one pool_sim per thread) and publishes the answer, so with several workers
// requests are taken up in arrival order but answered in the order they finish. Every publish
// holds publish_lock: liblcm's udpm provider already holds a lock of its own over each whole
// message (all its fragments), so this costs nothing there, and it keeps other providers (file://)
// whose publish is not serialized in every liblcm version safe.
//
// Every request has a budget: at most --max-balls balls, at most --max-events events (capping the
// scenario's own options.max_events) and --max-shot-seconds of wall time counted from the moment
// liblcm received it, so time spent queued is part of it: a request whose budget ran out while it
// waited is answered with an error without being simulated, and one taken up late gets only what
// is left. The shot is stepped in chunks of STEP_CHUNK events; between chunks the worker checks
// the clock and the stop flag, so a request over budget is answered with an error, and SIGINT/
// SIGTERM abandon every running shot at once (the queued requests are answered with an error
// too). An answer whose encoding would exceed --max-answer-bytes (LCM over UDP multicast loses
// messages larger than the receivers' socket buffers) is replaced by one carrying the final states
// and an error saying so.
//
// Memory: a request's scenario is freed once it is answered; blocks of LARGE_BLOCK_BYTES or more
// (liblcm's receive thread assembles each large datagram in a block of its own size) are mappings
// of their own, returned to the system when freed; and once no datagram has come for 200 ms the
// main thread gives back what malloc kept of smaller freed blocks (glibc malloc_trim), so the
// resident size goes back down after a burst of large requests.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <lcm/lcm.h>

#include "cli.h"
#include "lcm_convert.h"
#include "lcm_service.h"
#include "pool/scenario.h"

#define EXIT_BAD_INPUT 2
#define EXIT_INTERNAL 1

#define DEFAULT_MAX_SHOT_SECONDS 10.0
#define DEFAULT_MAX_EVENTS 1000000L
#define DEFAULT_MAX_BALLS 2000L
#define DEFAULT_MAX_ANSWER_BYTES 4194304L
#define DEFAULT_MAX_QUEUE_REQUESTS 4096L
#define DEFAULT_MAX_QUEUE_BYTES 67108864L
#define DEFAULT_WORKERS 1L
/// Most accepted --workers.
#define MAX_WORKERS 256L
/// Least capacity of liblcm's own queue of requests the main thread has not taken yet (it is
/// --max-queue-requests when that is larger).
#define LCM_QUEUE_CAPACITY 1024L
/// Smallest accepted --max-answer-bytes: room for an error answer.
#define MIN_MAX_ANSWER_BYTES 512L
/// Events stepped between two looks at the clock and the stop flag (a step of a 2000-ball shot
/// takes well under a millisecond).
#define STEP_CHUNK 16
/// A simulation that held more events than this is freed after the shot instead of reused.
#define RETAIN_EVENTS 100000
/// Request bytes received after which an idle server trims malloc's heaps (release_memory).
#define TRIM_BYTES (1L << 20)
/// Blocks at least this large get a mapping of their own (fix_malloc_thresholds).
#define LARGE_BLOCK_BYTES (256 * 1024)

static const char usage_text[] =
	"usage: pool-shot-server [--lcm-url URL] [--max-requests N] [--max-shot-seconds S]\n"
	"                        [--max-events N] [--max-balls N] [--max-answer-bytes N]\n"
	"                        [--max-queue-requests N] [--max-queue-bytes N] [--workers N]\n"
	"                        [--help]\n"
	"\n"
	"Answers every pool_lcm.shot_request_t on POOL_SHOT_REQUEST (a libpool-scenario/1 document)\n"
	"with a pool_lcm.shot_t on POOL_SHOT carrying the same request_id: every event and the final\n"
	"state of every ball, or `error` naming the offending field of a bad scenario or the limit a\n"
	"request exceeded. Requests wait their turn in a queue bounded by --max-queue-requests and\n"
	"--max-queue-bytes; one that does not fit is answered at once with an error starting\n"
	"\"server busy:\" (send it again later). --workers N simulate N requests at once; answers may\n"
	"then come in another order than the requests (match them by request_id). Undecodable\n"
	"datagrams are logged on standard error and skipped. Stops on SIGINT or SIGTERM (abandoning the\n"
	"shots in progress and answering the queued requests with an error) and reports what it\n"
	"answered, refused and dropped.\n"
	"\n"
	"  --lcm-url URL           LCM provider (default $LCM_DEFAULT_URL, else\n"
	"                          udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608)\n"
	"  --max-requests N        exit after answering N requests, busy answers included\n"
	"                          (0 = serve until a signal)\n"
	"  --max-shot-seconds S    wall time one request may take from its arrival to its answer,\n"
	"                          time queued and parsing included (default 10); a request that\n"
	"                          waited longer is answered with an error, not simulated\n"
	"  --max-events N          events one shot may take; caps the scenario's options.max_events\n"
	"                          (default 1000000)\n"
	"  --max-balls N           balls one scenario may hold (default 2000)\n"
	"  --max-answer-bytes N    largest answer sent; a larger one is replaced by the final states\n"
	"                          and an error (default 4194304 = 4 MiB)\n"
	"  --max-queue-requests N  requests that may wait while the workers simulate (default 4096)\n"
	"  --max-queue-bytes N     encoded bytes of the waiting requests together (default 67108864\n"
	"                          = 64 MiB); a single larger request is refused with an error\n"
	"  --workers N             worker threads simulating requests at once, each on its own\n"
	"                          simulation (default 1: one at a time, answers in arrival order);\n"
	"                          1..256\n"
	"  -h, --help              show this help\n";

/// The per-request budget and the queue's bounds (command-line options).
typedef struct server_limits {
	double max_shot_seconds;
	long max_events;
	long max_balls;
	long max_answer_bytes;
	long max_queue_requests;
	long max_queue_bytes;
} server_limits;

/// A request waiting in the server's queue.
typedef struct queued_request {
	struct queued_request *next;
	pool_lcm_shot_request_t request; // decoded; the scenario is freed once it is answered
	long bytes;                      // its encoded size, counted against --max-queue-bytes
	double arrived;                  // monotonic s when liblcm received it
} queued_request;

/// What all threads share. `lock` guards the queue and the counters written by the main thread
/// and the workers (answered, errors, publish_failures, last_shot_id); the counters the workers
/// write (over_budget ... abandoned_queued) are atomic, read by the main thread after joining
/// them; those only the main thread writes (undecodable, busy, too_large) are plain.
typedef struct server_state {
	lcm_t *lcm;
	server_limits limits;
	long max_requests;    // --max-requests
	pthread_mutex_t lock;
	pthread_mutex_t publish_lock; // held over every lcm publish (see the top of this file)
	pthread_cond_t wake;  // signalled when a request is queued or the server stops
	queued_request *head; // oldest
	queued_request *tail;
	long queued;          // requests in the queue (reserved ones included)
	long queued_bytes;
	long peak_queued;     // largest queue seen, requests and bytes
	long peak_queued_bytes;
	atomic_bool stopping; // the main loop ended: the workers abandon what they have and return
	int wake_pipe[2];     // a worker writes a byte when --max-requests answers are reached
	int64_t last_shot_id; // shot ids strictly increase even within one microsecond
	long answered;        // shot_t published (errors included)
	long errors;          // answers carrying an error (all the refusals below included)
	long publish_failures;
	long undecodable;     // datagrams that were not a shot_request_t (main thread only)
	long busy;            // refused with "server busy:" because the queue was full (main only)
	long too_large;       // requests alone larger than --max-queue-bytes (main only)
	atomic_long over_budget; // requests over --max-shot-seconds (while running), --max-events or
	                         // --max-balls (workers; the report adds too_large)
	atomic_long trim_bytes; // request bytes received or freed since the last malloc_trim
	atomic_long expired;    // budget spent in the queue: answered with an error, not simulated
	atomic_long oversized;  // answers over --max-answer-bytes, replaced by the final states
	atomic_long abandoned;  // running shots given up because a stop signal arrived
	atomic_long abandoned_queued; // queued requests answered with an error because the server
	                              // stopped
} server_state;

/// One worker thread and the simulation it reuses for every request it takes.
typedef struct worker {
	server_state *s;
	pool_sim *sim;
	pthread_t thread;
} worker;

static double monotonic_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int64_t next_shot_id(server_state *s)
{
	int64_t now = pool_lcm_utime_now();
	pthread_mutex_lock(&s->lock);
	s->last_shot_id = now > s->last_shot_id ? now : s->last_shot_id + 1;
	int64_t id = s->last_shot_id;
	pthread_mutex_unlock(&s->lock);
	return id;
}

static bool stop_now(server_state *s)
{
	return pool_lcm_stop_requested() || atomic_load(&s->stopping);
}

/// What the shot2_t answer adds to a request's shot: its cushion parts, its table, and the verdict
/// of the rules its scenario asked for ("game").
typedef struct shot_game {
	const pool_sim *sim;        // the shot, or NULL (an error answer)
	const pool_game_state *game; // NULL without a game
	const pool_sim_def *def;     // the scenario's table, balls and laws
} shot_game;

// Publishes the answer on POOL_SHOT, and the same with the later fields (shot2_t) on POOL_SHOT2.
static void publish_shot(server_state *s, const pool_lcm_shot_t *shot, bool is_error, const shot_game *g)
{
	pool_lcm_shot2_t shot2;
	bool converted = pool_lcm_shot2_fill(shot, g ? g->sim : NULL, g ? g->def : NULL, g ? g->game : NULL,
	                                     &shot2) == 0 ||
	                 pool_lcm_shot2_fill(shot, NULL, NULL, NULL, &shot2) == 0;
	pthread_mutex_lock(&s->publish_lock);
	bool failed = pool_lcm_shot_t_publish(s->lcm, POOL_LCM_CHANNEL_SHOT, shot) != 0;
	failed = (converted && pool_lcm_shot2_t_publish(s->lcm, POOL_LCM_CHANNEL_SHOT2, &shot2) != 0) || failed;
	pthread_mutex_unlock(&s->publish_lock);
	if (converted) {
		pool_lcm_shot2_release(&shot2);
	}
	if (failed) {
		fprintf(stderr, "pool-shot-server: could not publish the answer to request %lld\n",
		        (long long)shot->request_id);
	}
	pthread_mutex_lock(&s->lock);
	s->publish_failures += failed;
	s->errors += is_error;
	s->answered++;
	bool reached = s->max_requests > 0 && s->answered == s->max_requests;
	pthread_mutex_unlock(&s->lock);
	if (reached) {
		// Wake the main loop so it stops now rather than at its next poll timeout.
		ssize_t w = write(s->wake_pipe[1], "", 1);
		(void)w;
	}
}

static void answer_error(server_state *s, int64_t shot_id, int64_t request_id, const char *message)
{
	pool_lcm_shot_t shot;
	if (pool_lcm_shot_fill_error(shot_id, request_id, pool_lcm_utime_now(), message, &shot) != 0) {
		fprintf(stderr, "pool-shot-server: out of memory answering request %lld\n",
		        (long long)request_id);
		pthread_mutex_lock(&s->lock);
		s->errors++;
		pthread_mutex_unlock(&s->lock);
		return;
	}
	publish_shot(s, &shot, true, NULL);
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
// chunks. deadline: monotonic time the answer is due (arrival + --max-shot-seconds).
static run_outcome run_budgeted(worker *w, double deadline, double queued_s, char *err,
                                size_t err_size)
{
	server_state *s = w->s;
	for (;;) {
		for (int k = 0; k < STEP_CHUNK; ++k) {
			int status = pool_sim_step(w->sim);
			if (status < 0) {
				snprintf(err, err_size, "simulation failed at t = %.17g s: %s",
				         pool_sim_time(w->sim),
				         pool_sim_last_error(w->sim)[0] ? pool_sim_last_error(w->sim)
				                                        : pool_result_str((pool_result)status));
				return RUN_FAILED;
			}
			if (status == 0) {
				return RUN_DONE;
			}
		}
		if (stop_now(s)) {
			return RUN_STOPPED;
		}
		if (monotonic_s() > deadline) {
			int count = 0;
			pool_sim_events(w->sim, &count);
			snprintf(err, err_size,
			         "shot exceeded the server's budget of %g s (--max-shot-seconds): stopped "
			         "after %d events at t = %.6g s (the budget counts from the request's "
			         "arrival; %.3f s of it spent queued)",
			         s->limits.max_shot_seconds, count, pool_sim_time(w->sim), queued_s);
			return RUN_OVER_TIME;
		}
	}
}

// Publishes the shot, or, when its encoding would exceed --max-answer-bytes, an answer carrying
// the final states (when they fit) and an error giving the size.
static void answer_shot(worker *w, int64_t shot_id, int64_t request_id, const shot_game *g)
{
	server_state *s = w->s;
	pool_lcm_shot_t shot;
	int64_t events_size = pool_lcm_shot_events_encoded_size(w->sim);
	if (events_size < 0 ||
	    pool_lcm_shot_fill_final(w->sim, shot_id, request_id, pool_lcm_utime_now(), &shot) != 0) {
		answer_error(s, shot_id, request_id, "out of memory converting the shot");
		return;
	}
	int64_t size = (int64_t)pool_lcm_shot_t_encoded_size(&shot) + events_size;
	if (size <= s->limits.max_answer_bytes) {
		pool_lcm_shot_release(&shot);
		if (pool_lcm_shot_fill(w->sim, shot_id, request_id, shot.utime, &shot) != 0) {
			answer_error(s, shot_id, request_id, "out of memory converting the shot");
			return;
		}
		publish_shot(s, &shot, false, g);
		pool_lcm_shot_release(&shot);
		return;
	}
	int count = 0;
	pool_sim_events(w->sim, &count);
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
		atomic_fetch_add(&s->oversized, 1);
		answer_error(s, shot_id, request_id, message);
		return;
	}
	fprintf(stderr, "pool-shot-server: request %lld: %s\n", (long long)request_id, message);
	atomic_fetch_add(&s->oversized, 1);
	publish_shot(s, &shot, true, g);
	pool_lcm_shot_release(&shot);
}

// Frees the simulation after a shot that made it large, so its memory goes back to the system.
// A shot cut by a budget frees it whatever its size: such a shot is an outlier, not the steady
// stream the reuse is for, and how many events it reached depends on the machine's load, so
// keeping it would make what the server holds afterwards a matter of timing.
static void trim_sim(worker *w, bool cut_by_budget)
{
	if (w->sim == NULL) {
		return;
	}
	int count = 0;
	pool_sim_events(w->sim, &count);
	if (cut_by_budget || count > RETAIN_EVENTS) {
		pool_sim_destroy(w->sim);
		w->sim = NULL;
	}
}

// The error of a request whose budget ran out before it was simulated (or while it was parsed).
static void answer_expired(server_state *s, int64_t shot_id, const queued_request *q, double now,
                           const char *when)
{
	char err[400];
	snprintf(err, sizeof err,
	         "request expired in the server's queue: it waited %.3f s, and the server's budget of "
	         "%g s (--max-shot-seconds), counted from its arrival, ran out %s; not simulated",
	         now - q->arrived, s->limits.max_shot_seconds, when);
	atomic_fetch_add(&s->expired, 1);
	answer_error(s, shot_id, q->request.request_id, err);
}

static void answer_request(worker *w, const queued_request *q)
{
	server_state *s = w->s;
	double started = monotonic_s();
	double deadline = q->arrived + s->limits.max_shot_seconds;
	double queued_s = started - q->arrived;
	int64_t shot_id = next_shot_id(s);
	int64_t request_id = q->request.request_id;
	if (started > deadline) {
		answer_expired(s, shot_id, q, started, "before its turn came");
		return;
	}
	char err[512];
	pool_scenario scenario;
	const char *json = q->request.scenario_json;
	if (pool_scenario_parse(json, strlen(json), &scenario, err, sizeof err) != 0) {
		answer_error(s, shot_id, request_id, err);
		return;
	}
	if (scenario.ball_count > s->limits.max_balls) {
		snprintf(err, sizeof err, "balls: %d balls, more than the server's limit of %ld "
		         "(--max-balls)", scenario.ball_count, s->limits.max_balls);
		pool_scenario_free(&scenario);
		atomic_fetch_add(&s->over_budget, 1);
		answer_error(s, shot_id, request_id, err);
		return;
	}
	// The scenario may ask for fewer events than the server allows, never more.
	bool capped = scenario.def.max_events > s->limits.max_events;
	if (capped) {
		scenario.def.max_events = (int)s->limits.max_events;
	}
	pool_error perr = {{0}};
	pool_result r = pool_scenario_setup(&scenario, &w->sim, &perr);
	// The game is judged after the run: keep it (the scenario's balls are freed now).
	const pool_game_state game = scenario.game;
	const pool_sim_def def = scenario.def;
	const bool has_game = scenario.has_game;
	pool_scenario_free(&scenario);
	if (r != POOL_OK) {
		answer_error(s, shot_id, request_id, perr.message[0] ? perr.message : pool_result_str(r));
		return;
	}
	run_outcome outcome = run_budgeted(w, deadline, queued_s, err, sizeof err);
	if (outcome == RUN_DONE && capped && pool_sim_stop_reason(w->sim) == POOL_STOP_MAX_EVENTS) {
		snprintf(err, sizeof err,
		         "shot exceeded the server's budget of %ld events (--max-events) at t = %.6g s",
		         s->limits.max_events, pool_sim_time(w->sim));
		outcome = RUN_OVER_TIME; // over budget, like the time limit
	}
	switch (outcome) {
	case RUN_DONE: {
		const shot_game g = {w->sim, has_game ? &game : NULL, &def};
		answer_shot(w, shot_id, request_id, &g);
		break;
	}
	case RUN_FAILED:
		answer_error(s, shot_id, request_id, err);
		break;
	case RUN_OVER_TIME:
		fprintf(stderr, "pool-shot-server: request %lld: %s\n", (long long)request_id, err);
		atomic_fetch_add(&s->over_budget, 1);
		answer_error(s, shot_id, request_id, err);
		break;
	case RUN_STOPPED:
		atomic_fetch_add(&s->abandoned, 1);
		answer_error(s, shot_id, request_id, pool_lcm_stop_requested()
		             ? "shot abandoned: the server is stopping (SIGINT/SIGTERM)"
		             : "shot abandoned: the server is stopping (--max-requests answered)");
		break;
	}
	trim_sim(w, outcome == RUN_OVER_TIME);
}

static void free_queued(queued_request *q)
{
	pool_lcm_shot_request_t_decode_cleanup(&q->request);
	free(q);
}

// A worker thread: takes the oldest queued request and answers it, until the server stops; then
// answers what is still queued with an error (the workers share that, each taking the oldest).
static void *worker_main(void *user)
{
	worker *w = user;
	server_state *s = w->s;
	for (;;) {
		pthread_mutex_lock(&s->lock);
		while (s->head == NULL && !stop_now(s)) {
			// A timeout so a signal (which sets a flag, nothing else) is seen within 200 ms.
			struct timespec until;
			clock_gettime(CLOCK_REALTIME, &until);
			until.tv_nsec += 200000000L;
			if (until.tv_nsec >= 1000000000L) {
				until.tv_sec++;
				until.tv_nsec -= 1000000000L;
			}
			pthread_cond_timedwait(&s->wake, &s->lock, &until);
		}
		queued_request *q = s->head;
		if (q != NULL) {
			s->head = q->next;
			if (s->head == NULL) {
				s->tail = NULL;
			}
			s->queued--;
			s->queued_bytes -= q->bytes;
		}
		pthread_mutex_unlock(&s->lock);
		if (q == NULL) {
			return NULL; // stopping, nothing left
		}
		if (stop_now(s)) {
			atomic_fetch_add(&s->abandoned_queued, 1);
			answer_error(s, next_shot_id(s), q->request.request_id, pool_lcm_stop_requested()
			             ? "request abandoned before its turn: the server is stopping "
			               "(SIGINT/SIGTERM)"
			             : "request abandoned before its turn: the server is stopping "
			               "(--max-requests answered)");
		} else {
			answer_request(w, q);
		}
		atomic_fetch_add(&s->trim_bytes, q->bytes);
		free_queued(q);
	}
}

// Monotonic time at which liblcm received a datagram (recv_utime, wall clock; the kernel's
// timestamp of its last fragment), so time in liblcm's queue counts against the budget too.
static double arrival_time(int64_t recv_utime)
{
	double now = monotonic_s();
	double age = (double)(pool_lcm_utime_now() - recv_utime) * 1e-6;
	if (!(age >= 0.0) || age > 3600.0) {
		age = 0.0; // the wall clock moved, or no timestamp: take now
	}
	return now - age;
}

// Raw handler rather than lcm-gen's typed one: a datagram that does not decode must be counted
// and logged, and its framing checked before lcm-gen's decoder trusts it; a request refused as
// busy is answered from its request_id alone, without copying its scenario.
static void on_request(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
	(void)channel;
	server_state *s = user;
	atomic_fetch_add(&s->trim_bytes, (long)rbuf->data_size);
	char err[400];
	int64_t request_id = 0;
	if (pool_lcm_request_peek(rbuf->data, rbuf->data_size, &request_id, err, sizeof err) != 0) {
		s->undecodable++;
		fprintf(stderr, "pool-shot-server: %s (skipped)\n", err);
		return;
	}
	double arrived = arrival_time(rbuf->recv_utime);
	long bytes = (long)rbuf->data_size;
	const server_limits *lim = &s->limits;
	if (bytes > lim->max_queue_bytes) {
		snprintf(err, sizeof err, "request of %ld bytes is larger than the server's queue "
		         "(--max-queue-bytes %ld); not simulated", bytes, lim->max_queue_bytes);
		s->too_large++;
		answer_error(s, next_shot_id(s), request_id, err);
		return;
	}
	pthread_mutex_lock(&s->lock);
	long queued = s->queued, queued_bytes = s->queued_bytes;
	bool fits = queued < lim->max_queue_requests && queued_bytes + bytes <= lim->max_queue_bytes;
	if (fits) {
		// Reserve the room now; the request is appended once decoded.
		s->queued++;
		s->queued_bytes += bytes;
		if (s->queued > s->peak_queued) {
			s->peak_queued = s->queued;
		}
		if (s->queued_bytes > s->peak_queued_bytes) {
			s->peak_queued_bytes = s->queued_bytes;
		}
	}
	pthread_mutex_unlock(&s->lock);
	if (!fits) {
		snprintf(err, sizeof err,
		         "server busy: %ld requests (%ld bytes) already queued, the limit is %ld requests "
		         "(--max-queue-requests) and %ld bytes (--max-queue-bytes); not simulated, send "
		         "it again later", queued, queued_bytes, lim->max_queue_requests,
		         lim->max_queue_bytes);
		s->busy++;
		answer_error(s, next_shot_id(s), request_id, err);
		return;
	}
	queued_request *q = calloc(1, sizeof *q);
	if (q == NULL || pool_lcm_request_decode(rbuf->data, rbuf->data_size, &q->request, err,
	                                         sizeof err) != 0) {
		free(q);
		pthread_mutex_lock(&s->lock);
		s->queued--;
		s->queued_bytes -= bytes;
		pthread_mutex_unlock(&s->lock);
		answer_error(s, next_shot_id(s), request_id, "out of memory queueing the request");
		return;
	}
	q->bytes = bytes;
	q->arrived = arrived;
	pthread_mutex_lock(&s->lock);
	if (s->tail != NULL) {
		s->tail->next = q;
	} else {
		s->head = q;
	}
	s->tail = q;
	pthread_cond_signal(&s->wake);
	pthread_mutex_unlock(&s->lock);
}

// After 200 ms without a datagram, and at least TRIM_BYTES of requests received or freed since the
// last time:
// gives back to the system what malloc keeps of freed blocks smaller than LARGE_BLOCK_BYTES, in
// every thread's heap (the decoded requests, a freed simulation's smaller arrays); glibc keeps
// them for reuse, which is fast during a burst but would hold them for good once it is over.
static void release_memory(server_state *s)
{
#ifdef __GLIBC__
	if (atomic_load(&s->trim_bytes) >= TRIM_BYTES) {
		atomic_store(&s->trim_bytes, 0);
		malloc_trim(0);
	}
#else
	(void)s;
#endif
}

// glibc raises its mmap threshold to the size of the largest mapped block freed (up to 32 MiB);
// after that, the 4 MiB blocks of large datagrams come from the receive thread's heap, whose top
// malloc_trim does not give back (only the main heap's): after a flood of 4 MiB requests the
// server kept 0 to 20 MiB more from run to run. A fixed threshold keeps every block of
// LARGE_BLOCK_BYTES or more in a mapping of its own, unmapped when freed: one mmap and munmap per
// large request, nothing beside receiving it.
static void fix_malloc_thresholds(void)
{
#ifdef __GLIBC__
	mallopt(M_MMAP_THRESHOLD, LARGE_BLOCK_BYTES);
#endif
}

static bool parse_size_option(const char *value, long min, long *out)
{
	return pool_cli_parse_count(value, out) && *out >= min && *out <= INT_MAX;
}

int main(int argc, char **argv)
{
	const char *url = NULL;
	long max_requests = 0;
	long workers = DEFAULT_WORKERS;
	server_limits limits = {DEFAULT_MAX_SHOT_SECONDS, DEFAULT_MAX_EVENTS, DEFAULT_MAX_BALLS,
	                        DEFAULT_MAX_ANSWER_BYTES, DEFAULT_MAX_QUEUE_REQUESTS,
	                        DEFAULT_MAX_QUEUE_BYTES};
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
			    !(limits.max_shot_seconds > 0.0) || !(limits.max_shot_seconds <= 1e6)) {
				fprintf(stderr, "pool-shot-server: --max-shot-seconds: '%s' is not a time in "
				                "(0, 1e6] seconds\n", argv[i]);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-events") == 0 && i + 1 < argc) {
			if (!parse_size_option(argv[++i], 1, &limits.max_events)) {
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
			if (!parse_size_option(argv[++i], MIN_MAX_ANSWER_BYTES, &limits.max_answer_bytes)) {
				fprintf(stderr, "pool-shot-server: --max-answer-bytes: '%s' is not a size in "
				                "%ld..%d bytes\n", argv[i], MIN_MAX_ANSWER_BYTES, INT_MAX);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-queue-requests") == 0 && i + 1 < argc) {
			if (!parse_size_option(argv[++i], 1, &limits.max_queue_requests)) {
				fprintf(stderr, "pool-shot-server: --max-queue-requests: '%s' is not a count in "
				                "1..%d\n", argv[i], INT_MAX);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--workers") == 0 && i + 1 < argc) {
			if (!pool_cli_parse_count(argv[++i], &workers) || workers < 1 ||
			    workers > MAX_WORKERS) {
				fprintf(stderr, "pool-shot-server: --workers: '%s' is not a count in 1..%ld\n",
				        argv[i], MAX_WORKERS);
				return EXIT_BAD_INPUT;
			}
		} else if (strcmp(a, "--max-queue-bytes") == 0 && i + 1 < argc) {
			if (!parse_size_option(argv[++i], 1, &limits.max_queue_bytes)) {
				fprintf(stderr, "pool-shot-server: --max-queue-bytes: '%s' is not a size in "
				                "1..%d bytes\n", argv[i], INT_MAX);
				return EXIT_BAD_INPUT;
			}
		} else {
			fprintf(stderr, "pool-shot-server: unknown or incomplete option '%s'\n"
			                "Try 'pool-shot-server --help'.\n", a);
			return EXIT_BAD_INPUT;
		}
	}

	pool_lcm_catch_stop_signals();
	fix_malloc_thresholds();

	server_state s;
	memset(&s, 0, sizeof s);
	s.limits = limits;
	s.max_requests = max_requests;
	atomic_init(&s.stopping, false);
	atomic_init(&s.trim_bytes, 0);
	atomic_init(&s.over_budget, 0);
	atomic_init(&s.expired, 0);
	atomic_init(&s.oversized, 0);
	atomic_init(&s.abandoned, 0);
	atomic_init(&s.abandoned_queued, 0);
	if (pipe(s.wake_pipe) != 0) {
		perror("pool-shot-server: pipe");
		return EXIT_INTERNAL;
	}
	pthread_mutex_init(&s.lock, NULL);
	pthread_mutex_init(&s.publish_lock, NULL);
	pthread_cond_init(&s.wake, NULL);
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
	// liblcm keeps at most this many complete requests the main thread has not taken yet (its
	// default is 30). The main thread takes them as they come, so this is only a backstop that
	// holds a burst of small requests until each is queued or refused: what liblcm drops beyond it
	// is never seen, hence never answered nor counted.
	long lcm_capacity = limits.max_queue_requests > LCM_QUEUE_CAPACITY ? limits.max_queue_requests
	                                                                   : LCM_QUEUE_CAPACITY;
	lcm_subscription_set_queue_capacity(sub, (int)lcm_capacity);
	worker *pool = calloc((size_t)workers, sizeof *pool);
	if (pool == NULL) {
		fprintf(stderr, "pool-shot-server: out of memory\n");
		lcm_unsubscribe(s.lcm, sub);
		lcm_destroy(s.lcm);
		return EXIT_INTERNAL;
	}
	// The workers block SIGINT and SIGTERM, so they reach the main thread and cut its poll short.
	sigset_t stop_signals, old_mask;
	sigemptyset(&stop_signals);
	sigaddset(&stop_signals, SIGINT);
	sigaddset(&stop_signals, SIGTERM);
	pthread_sigmask(SIG_BLOCK, &stop_signals, &old_mask);
	long started = 0;
	for (; started < workers; ++started) {
		pool[started].s = &s;
		if (pthread_create(&pool[started].thread, NULL, worker_main, &pool[started]) != 0) {
			break;
		}
	}
	pthread_sigmask(SIG_SETMASK, &old_mask, NULL);
	int status = 0;
	if (started < workers) {
		fprintf(stderr, "pool-shot-server: cannot start worker thread %ld of %ld\n", started + 1,
		        workers);
		status = EXIT_INTERNAL;
	} else {
		fprintf(stderr, "pool-shot-server: ready on %s, channel %s (budget per request: %g s "
		        "from arrival, %ld events, %ld balls, %ld-byte answers; queue: %ld requests, %ld "
		        "bytes; %ld worker%s)\n",
		        pool_lcm_resolve_url(url), POOL_LCM_CHANNEL_SHOT_REQUEST,
		        limits.max_shot_seconds, limits.max_events, limits.max_balls,
		        limits.max_answer_bytes, limits.max_queue_requests, limits.max_queue_bytes,
		        workers, workers == 1 ? "" : "s");
	}

	while (status == 0) {
		pthread_mutex_lock(&s.lock);
		bool done = max_requests > 0 && s.answered >= max_requests;
		pthread_mutex_unlock(&s.lock);
		if (done || pool_lcm_stop_requested()) {
			break;
		}
		// A timeout so a signal that arrives between the check and poll stops us within 200 ms;
		// 200 ms without a datagram is also when memory is given back.
		struct pollfd pfd[2] = {{.fd = lcm_get_fileno(s.lcm), .events = POLLIN},
		                        {.fd = s.wake_pipe[0], .events = POLLIN}};
		int ready = poll(pfd, 2, 200);
		if (ready < 0 && errno != EINTR) {
			perror("pool-shot-server: poll");
			status = EXIT_INTERNAL;
			break;
		}
		if (ready > 0 && (pfd[0].revents & POLLIN) && lcm_handle(s.lcm) != 0) {
			fprintf(stderr, "pool-shot-server: lcm_handle failed\n");
			status = EXIT_INTERNAL;
			break;
		}
		if (ready == 0) {
			release_memory(&s);
		}
	}
	pthread_mutex_lock(&s.lock);
	atomic_store(&s.stopping, true);
	pthread_cond_broadcast(&s.wake);
	pthread_mutex_unlock(&s.lock);
	for (long k = 0; k < started; ++k) {
		pthread_join(pool[k].thread, NULL);
	}

	fprintf(stderr,
	        "pool-shot-server: answered %ld requests (%ld with an error), skipped %ld undecodable "
	        "datagrams, %ld publish failures; %ld over budget, %ld answers over "
	        "--max-answer-bytes, %ld shots abandoned on stop; %ld refused as busy (queue full), "
	        "%ld expired in the queue, %ld queued requests abandoned on stop; queue peak %ld "
	        "requests, %ld bytes\n",
	        s.answered, s.errors, s.undecodable, s.publish_failures,
	        atomic_load(&s.over_budget) + s.too_large, atomic_load(&s.oversized),
	        atomic_load(&s.abandoned), s.busy, atomic_load(&s.expired),
	        atomic_load(&s.abandoned_queued), s.peak_queued, s.peak_queued_bytes);
	lcm_unsubscribe(s.lcm, sub);
	lcm_destroy(s.lcm);
	for (long k = 0; k < workers; ++k) {
		pool_sim_destroy(pool[k].sim);
	}
	free(pool);
	pthread_cond_destroy(&s.wake);
	pthread_mutex_destroy(&s.publish_lock);
	pthread_mutex_destroy(&s.lock);
	close(s.wake_pipe[0]);
	close(s.wake_pipe[1]);
	return status;
}
