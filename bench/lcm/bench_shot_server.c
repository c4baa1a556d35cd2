// pool-bench-shot-server: load benchmark of a running pool-shot-server. Sends shot requests for
// one scenario at increasing rates (uniformly paced), counts the answers, and reports the highest
// rate at which every request was answered and the server kept up (the last answer came within
// --slack seconds of the last request). Prints per-run figures, then the median and minimum over
// runs and the machine. Run it (and the server) inside a private network namespace; see
// bench/lcm/bench_shot_server.sh.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "bench_util.h"
#include "lcm_convert.h"

static const char usage_text[] =
	"usage: pool-bench-shot-server --scenario FILE [--name NAME] [--lcm-url URL] [--runs N]\n"
	"                              [--duration S] [--start-rate R] [--max-rate R] [--slack S]\n"
	"\n"
	"Needs a pool-shot-server on the same LCM URL. For each run, sends requests for FILE at\n"
	"start-rate, doubling until a rate loses a request or falls behind, then bisects twice.\n"
	"Defaults: --runs 3 --duration 1 --start-rate 25 --max-rate 200000 --slack 0.05\n";

typedef struct bench {
	lcm_t *lcm;
	char *scenario_json;
	int64_t first_id;   // request ids of the current burst are first_id .. first_id + sent - 1
	long sent;
	long answered;      // distinct answers of the current burst
	long errors;        // answers with error set
	unsigned char *seen; // per request of the burst
	long seen_size;
	double last_answer; // monotonic s
} bench;

static int64_t be64(const unsigned char *p)
{
	uint64_t v = 0;
	for (int i = 0; i < 8; ++i) {
		v = (v << 8) | p[i];
	}
	return (int64_t)v;
}

// Reads only request_id (bytes 24..31 after the fingerprint, utime, shot_id) and whether `error`,
// the last field, is empty: decoding whole breaks would steal CPU from the server on a small box.
static void on_shot(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
	(void)channel;
	bench *b = user;
	const unsigned char *d = rbuf->data;
	if (rbuf->data_size < 32 + 5) {
		return;
	}
	int64_t index = be64(d + 24) - b->first_id;
	if (index < 0 || index >= b->sent || index >= b->seen_size || b->seen[index]) {
		return; // an answer to an earlier burst or a duplicate
	}
	b->seen[index] = 1;
	b->answered++;
	const unsigned char *tail = d + rbuf->data_size - 5;
	bool empty_error = tail[0] == 0 && tail[1] == 0 && tail[2] == 0 && tail[3] == 1 && tail[4] == 0;
	if (!empty_error) {
		b->errors++;
	}
	b->last_answer = pool_bench_now_s();
}

static void pump(bench *b, double until)
{
	struct pollfd pfd = {.fd = lcm_get_fileno(b->lcm), .events = POLLIN};
	for (;;) {
		double left = until - pool_bench_now_s();
		int ms = left > 0 ? (int)ceil(left * 1e3) : 0;
		int ready = poll(&pfd, 1, ms);
		if (ready > 0) {
			lcm_handle(b->lcm);
		} else if (ready == 0 || (ready < 0 && errno != EINTR)) {
			return;
		}
		if (pool_bench_now_s() >= until) {
			// Drain what is already there without waiting.
			while (poll(&pfd, 1, 0) > 0) {
				lcm_handle(b->lcm);
			}
			return;
		}
	}
}

/// One burst at `rate` requests/s; returns true when every request was answered in time.
static bool burst(bench *b, double rate, double duration, double slack, double *throughput)
{
	long n = (long)ceil(rate * duration);
	if (n < 10) {
		n = 10;
	}
	if (n > b->seen_size) {
		free(b->seen);
		b->seen = malloc((size_t)n);
		b->seen_size = b->seen ? n : 0;
		if (!b->seen) {
			return false;
		}
	}
	memset(b->seen, 0, (size_t)n);
	b->first_id += b->sent + 1000000; // never reuse ids of a burst still being answered
	b->sent = 0;
	b->answered = 0;
	b->errors = 0;
	double start = pool_bench_now_s();
	pool_lcm_shot_request_t request = {.scenario_json = b->scenario_json};
	for (long i = 0; i < n; ++i) {
		pump(b, start + (double)i / rate);
		request.utime = pool_lcm_utime_now();
		request.request_id = b->first_id + i;
		b->sent = i + 1;
		pool_lcm_shot_request_t_publish(b->lcm, POOL_LCM_CHANNEL_SHOT_REQUEST, &request);
	}
	double last_send = pool_bench_now_s();
	// Wait until everything is answered or clearly late.
	while (b->answered < n && pool_bench_now_s() < last_send + slack + 1.0) {
		pump(b, pool_bench_now_s() + 0.01);
	}
	bool ok = b->answered == n && b->errors == 0 && b->last_answer <= last_send + slack;
	*throughput = (double)b->answered / (b->last_answer - start);
	if (!ok) {
		// Let the server work off its backlog so the next burst starts clean.
		double quiet_since = pool_bench_now_s();
		long before = b->answered;
		while (pool_bench_now_s() - quiet_since < 1.0) {
			pump(b, pool_bench_now_s() + 0.1);
			if (b->answered != before) {
				before = b->answered;
				quiet_since = pool_bench_now_s();
			}
		}
	}
	return ok;
}

static char *read_file(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		return NULL;
	}
	size_t cap = 4096, len = 0;
	char *data = malloc(cap);
	size_t got;
	while (data && (got = fread(data + len, 1, cap - len - 1, f)) > 0) {
		len += got;
		if (cap - len - 1 == 0) {
			char *bigger = realloc(data, cap * 2);
			if (!bigger) {
				free(data);
				data = NULL;
				break;
			}
			data = bigger;
			cap *= 2;
		}
	}
	fclose(f);
	if (data) {
		data[len] = '\0';
	}
	return data;
}

static void print_machine(void)
{
	char model[256];
	struct utsname u;
	uname(&u);
	printf("machine: %s, %ld CPUs online, %s %s %s\n", pool_bench_cpu_model(model, sizeof model),
	       pool_bench_cpus_online(), u.sysname, u.release, u.machine);
}

int main(int argc, char **argv)
{
	const char *scenario_path = NULL, *name = NULL, *url = NULL;
	int runs = 3;
	double duration = 1.0, start_rate = 25.0, max_rate = 200000.0, slack = 0.05;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i];
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			fputs(usage_text, stdout);
			return 0;
		}
		if (i + 1 >= argc) {
			fprintf(stderr, "pool-bench-shot-server: unknown or incomplete option '%s'\n", a);
			return 2;
		}
		const char *v = argv[++i];
		if (strcmp(a, "--scenario") == 0) {
			scenario_path = v;
		} else if (strcmp(a, "--name") == 0) {
			name = v;
		} else if (strcmp(a, "--lcm-url") == 0) {
			url = v;
		} else if (strcmp(a, "--runs") == 0) {
			runs = atoi(v);
		} else if (strcmp(a, "--duration") == 0) {
			duration = atof(v);
		} else if (strcmp(a, "--start-rate") == 0) {
			start_rate = atof(v);
		} else if (strcmp(a, "--max-rate") == 0) {
			max_rate = atof(v);
		} else if (strcmp(a, "--slack") == 0) {
			slack = atof(v);
		} else {
			fprintf(stderr, "pool-bench-shot-server: unknown option '%s'\n", a);
			return 2;
		}
	}
	if (!scenario_path || runs < 1 || !(duration > 0) || !(start_rate > 0) || !(max_rate >= start_rate) ||
	    !(slack > 0)) {
		fprintf(stderr, "pool-bench-shot-server: needs --scenario FILE and positive numbers\n");
		return 2;
	}
	bench b;
	memset(&b, 0, sizeof b);
	b.scenario_json = read_file(scenario_path);
	if (!b.scenario_json) {
		fprintf(stderr, "pool-bench-shot-server: cannot read %s\n", scenario_path);
		return 2;
	}
	const char *resolved = pool_lcm_resolve_url(url);
	b.lcm = lcm_create(resolved);
	if (!b.lcm) {
		fprintf(stderr, "pool-bench-shot-server: cannot open LCM on '%s'\n", resolved);
		return 2;
	}
	lcm_subscription_t *sub = lcm_subscribe(b.lcm, POOL_LCM_CHANNEL_SHOT, on_shot, &b);
	lcm_subscription_set_queue_capacity(sub, 100000);
	b.first_id = pool_lcm_utime_now();

	// Warm-up: one request, which also checks that a server answers at all.
	double unused;
	if (!burst(&b, 10.0, 1.0, 2.0, &unused) && b.answered == 0) {
		fprintf(stderr, "pool-bench-shot-server: no pool-shot-server answers on %s\n", resolved);
		return 1;
	}

	double *sustained = calloc((size_t)runs, sizeof *sustained);
	double *throughput = calloc((size_t)runs, sizeof *throughput);
	if (!sustained || !throughput) {
		return 1;
	}
	for (int r = 0; r < runs; ++r) {
		double good = 0.0, bad = 0.0, good_tp = 0.0, tp = 0.0;
		for (double rate = start_rate; rate <= max_rate; rate *= 2.0) {
			if (burst(&b, rate, duration, slack, &tp)) {
				good = rate;
				good_tp = tp;
			} else {
				bad = rate;
				break;
			}
		}
		for (int k = 0; k < 2 && bad > 0.0 && good > 0.0; ++k) {
			double mid = 0.5 * (good + bad);
			if (burst(&b, mid, duration, slack, &tp)) {
				good = mid;
				good_tp = tp;
			} else {
				bad = mid;
			}
		}
		sustained[r] = good;
		throughput[r] = good_tp;
		char failing[64] = "none up to --max-rate";
		if (bad > 0.0) {
			snprintf(failing, sizeof failing, "%.0f /s", bad);
		}
		printf("run %d: %s: sustained %.0f requests/s with none lost (answers %.0f /s); "
		       "first failing rate %s\n",
		       r + 1, name ? name : scenario_path, good, good_tp, failing);
		fflush(stdout);
	}
	pool_bench_summary rate = pool_bench_summarise(sustained, (size_t)runs);
	printf("%s: sustained request rate, no request lost: median %.0f /s, min %.0f /s over %d runs "
	       "(%.1f s bursts, answers within %.2f s)\n",
	       name ? name : scenario_path, rate.median, rate.min, runs, duration, slack);
	print_machine();
	lcm_unsubscribe(b.lcm, sub);
	lcm_destroy(b.lcm);
	free(sustained);
	free(throughput);
	free(b.seen);
	free(b.scenario_json);
	return 0;
}
