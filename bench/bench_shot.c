// pool-bench-shot: how long libpool takes to simulate whole shots, reusing one pool_sim.
// Scenes: a 15-ball break at 8 m/s on a frozen rack and on a rack with a tiny gap, and random
// shots on the table a break leaves. Prints median and minimum time per shot, events per second,
// the library's peak heap before and after the runs (it must not grow with the number of shots),
// the process's peak resident memory, and the machine.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include <pool/link.h>
#include <pool/pool.h>

#include "bench_util.h"

static long maxrss_kib(void) {
	struct rusage ru;
	getrusage(RUSAGE_SELF, &ru);
	return ru.ru_maxrss;
}

static void print_machine(void) {
	char model[256];
	printf("machine: %s, %ld cores online, libpool %d\n", pool_bench_cpu_model(model, sizeof model),
	       pool_bench_cpus_online(), POOL_VERSION);
}

typedef struct shot {
	pool_ball_state balls[16];
	int n;
	int32_t cue;
	pool_strike strike;
} shot;

static int run(pool_sim *sim, const shot *s, int *events) {
	if (pool_sim_reset(sim, NULL, NULL) != POOL_OK)
		return -1;
	for (int i = 0; i < s->n; ++i)
		if (pool_sim_add_ball(sim, &s->balls[i], NULL) != POOL_OK)
			return -1;
	if (pool_sim_strike(sim, s->cue, &s->strike, NULL) != POOL_OK || pool_sim_run(sim) != POOL_OK)
		return -1;
	pool_sim_events(sim, events);
	return 0;
}

// --only: the scenes whose name starts with it (NULL: every scene).
static const char *only;
// --hash: print a hash of every event and state of each scene's shots (to compare versions).
static int hash_events;

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
	const unsigned char *c = p;
	for (size_t i = 0; i < n; ++i)
		h = (h ^ c[i]) * 0x100000001B3ull;
	return h;
}

// Every event (its fields and the states after it) and the final states of the shot just run.
static uint64_t hash_shot(uint64_t h, const pool_sim *sim) {
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	for (int k = 0; k < count; ++k) {
		h = fnv(h, &events[k].time, sizeof events[k].time);
		const int fields[4] = {(int)events[k].type, (int)events[k].rail, (int)events[k].pocket, events[k].ball_count};
		h = fnv(h, fields, sizeof fields);
		h = fnv(h, pool_sim_event_states(sim, &events[k]), sizeof(pool_ball_state) * (size_t)events[k].ball_count);
	}
	return fnv(h, pool_sim_balls(sim), sizeof(pool_ball_state) * (size_t)pool_sim_ball_count(sim));
}

// Times `runs` runs over the shot list (cycled); prints median / min per shot and events/s.
// t holds `runs` doubles (allocated before the memory baseline). Not inlined: callgrind's
// --toggle-collect=measure counts the instructions of the timed runs alone.
__attribute__((noinline)) static int measure(pool_sim *sim, const char *name, const shot *shots, int count, int runs,
                                             double *t) {
	if (only && strncmp(name, only, strlen(only)) != 0)
		return 0;
	long events = 0, link_steps = 0;
	double total = 0.0;
	uint64_t hash = 0xCBF29CE484222325ull;
	for (int r = 0; r < runs; ++r) {
		int ev = 0;
		double t0 = pool_bench_now_s();
		if (run(sim, &shots[r % count], &ev)) {
			fprintf(stderr, "pool-bench-shot: %s: shot %d failed\n", name, r % count);
			return -1;
		}
		t[r] = pool_bench_now_s() - t0;
		if (hash_events && r < count) // each shot of the list once, outside the timing
			hash = hash_shot(hash, sim);
		total += t[r];
		events += ev;
		pool_link_stats ls;
		if (pool_sim_link_stats(sim, &ls) == POOL_OK)
			link_steps += ls.steps;
	}
	pool_bench_summary sum = pool_bench_summarise(t, (size_t)runs);
	printf("%-34s runs %6d  median %8.1f us  min %8.1f us  mean %8.1f us  events/shot %6.1f  link steps/shot %5.1f  "
	       "events/s %.3g\n",
	       name, runs, 1e6 * sum.median, 1e6 * sum.min, 1e6 * total / runs, (double)events / runs,
	       (double)link_steps / runs, (double)events / total);
	if (hash_events)
		printf("%-34s events hash %016llx (%d shots)\n", name, (unsigned long long)hash, runs < count ? runs : count);
	fflush(stdout);
	return 0;
}

// Counts the library's allocations and the bytes it holds (live and peak), to show that reused
// shots allocate nothing and that the library's memory does not grow with the number of shots.
// Each block carries its size in a header, as the allocator interface passes none to free.
typedef union block_header {
	size_t size;
	max_align_t align;
} block_header;
static long lib_allocs;
static size_t lib_live_bytes, lib_peak_bytes;
static void *counting_alloc(size_t size, void *ctx) {
	(void)ctx;
	block_header *h = malloc(sizeof *h + size);
	if (!h)
		return NULL;
	h->size = size;
	++lib_allocs;
	lib_live_bytes += size;
	if (lib_live_bytes > lib_peak_bytes)
		lib_peak_bytes = lib_live_bytes;
	return h + 1;
}
static void counting_free(void *p, void *ctx) {
	(void)ctx;
	if (!p)
		return;
	block_header *h = (block_header *)p - 1;
	lib_live_bytes -= h->size;
	free(h);
}

static uint64_t rng = 0x243F6A8885A308D3ull;
static double urand(void) {
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

int main(int argc, char **argv) {
	int runs = 2000, pockets = POOL_POCKETS_JAWS;
	const char *models = "default";
	for (int i = 1; i < argc; ++i) {
		if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
			printf("usage: pool-bench-shot [--runs N] [--models default|thesis] [--pockets jaws|mouth_lines]\n"
			       "                       [--only NAME] [--hash]\n"
			       "Times whole shots with libpool, reusing one pool_sim (pool_sim_reset):\n"
			       "  break-frozen      15-ball rack, gap 0, centre-ball break at 8 m/s\n"
			       "  break-gap-0.1mm   same with 0.1 mm between neighbours\n"
			       "  post-break        random strikes (0.5-6 m/s, spin, elevation) on the tables\n"
			       "                    that breaks leave\n"
			       "  random breaks     500 frozen-rack breaks at 1-8 m/s, aimed up to 3 deg off the\n"
			       "                    apex (slow, off-centre breaks leave balls pushing: LINK)\n"
			       "  jump (airborne)   a 5 m/s cue at 45 deg clearing a blocking ball\n"
			       "  break (airborne)  the 0.1 mm break with the cue elevated 5 deg, airborne motion\n"
			       "Prints median, minimum and mean time per shot over N runs (default 2000), events\n"
			       "and LINK steps per shot, events per second, the library's peak heap bytes and allocation count before and after the\n"
			       "runs (they must not grow), the process's peak resident memory, and the machine.\n"
			       "--models: the model set of every shot (default: the library's defaults, the\n"
			       "measured laws; thesis: the 2012 work's).\n"
			       "--pockets: the table's pocket model (default jaws; mouth_lines: the thesis model).\n"
			       "--only NAME times only the scenes whose printed name starts with NAME (break-frozen,\n"
			       "post-break, ...): for profiling, e.g. valgrind --tool=callgrind --toggle-collect=measure\n"
			       "pool-bench-shot --runs 100 --only break-frozen (instructions of the timed runs / 100).\n"
			       "--hash prints a hash of every event and state of each scene's shots (outside the timing):\n"
			       "two versions that print the same hashes gave the same events bit for bit.\n");
			return 0;
		}
		if (strcmp(argv[i], "--pockets") == 0 && i + 1 < argc) {
			pockets = pool_pockets_model_from_name(argv[++i]);
			if (pockets < 0) {
				fprintf(stderr, "pool-bench-shot: --pockets: jaws, mouth_lines or none\n");
				return 2;
			}
		} else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
			runs = atoi(argv[++i]);
			if (runs <= 0) {
				fprintf(stderr, "pool-bench-shot: --runs: must be > 0\n");
				return 2;
			}
		} else if (strcmp(argv[i], "--models") == 0 && i + 1 < argc) {
			models = argv[++i];
			pool_models m;
			if (pool_models_preset(models, &m) != POOL_OK) {
				fprintf(stderr, "pool-bench-shot: --models: unknown model set '%s' (default, thesis)\n", models);
				return 2;
			}
		} else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
			only = argv[++i];
		} else if (strcmp(argv[i], "--hash") == 0) {
			hash_events = 1;
		} else {
			fprintf(stderr, "pool-bench-shot: unknown argument '%s' (see --help)\n", argv[i]);
			return 2;
		}
	}
	print_machine();
	printf("models: %s\n", models);
	pool_sim_def def = pool_default_sim_def();
	pool_models_preset(models, &def.models);
	def.table.pockets = (pool_pockets_model)pockets;
	printf("pockets: %s\n", pool_pockets_model_name(def.table.pockets));
	def.allocator = (pool_allocator){counting_alloc, counting_free, NULL};
	pool_sim *sim;
	pool_error err;
	if (pool_sim_create(&def, &sim, &err) != POOL_OK) {
		fprintf(stderr, "pool-bench-shot: %s\n", err.message);
		return 1;
	}
	shot frozen, gap;
	frozen.n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 0.0, frozen.balls, 16);
	gap.n = pool_rack(POOL_RACK_8BALL, &def.table, &def.params, 1e-4, gap.balls, 16);
	frozen.cue = gap.cue = 0;
	frozen.strike = gap.strike = pool_break_strike(8.0);

	// Post-break tables: breaks with slightly varied aim; then random strikes of the cue ball
	// (re-spotted on the head spot if pocketed) among the balls left.
	enum { TABLES = 50, PER_TABLE = 20 };
	shot *post = malloc(sizeof *post * TABLES * PER_TABLE);
	if (!post)
		return 1;
	int count = 0;
	const double R = def.params.ball_radius;
	for (int k = 0; k < TABLES; ++k) {
		shot b = gap;
		b.strike.phi = (urand() - 0.5) * 0.01;
		int ev;
		if (run(sim, &b, &ev))
			return 1;
		shot table;
		table.n = 0;
		const pool_ball_state *fin = pool_sim_balls(sim);
		for (int i = 0; i < pool_sim_ball_count(sim); ++i)
			if (fin[i].motion != POOL_MOTION_POCKETED || fin[i].id == 0) {
				pool_ball_state s = fin[i];
				if (s.motion == POOL_MOTION_POCKETED) {
					s.pos.x = 0.25 * def.table.length;
					s.pos.y = 0.5 * def.table.width;
				}
				s.vel = s.omega = (pool_vec3){0, 0, 0};
				s.motion = POOL_MOTION_STATIONARY;
				int ok = 1;
				for (int j = 0; j < table.n; ++j)
					ok &= hypot(s.pos.x - table.balls[j].pos.x, s.pos.y - table.balls[j].pos.y) >= 2 * R;
				if (ok)
					table.balls[table.n++] = s;
			}
		for (int j = 0; j < PER_TABLE; ++j) {
			shot s = table;
			s.cue = 0;
			double r = 0.7 * R * sqrt(urand()), a = urand() * 6.283185307179586;
			s.strike = (pool_strike){0.5 + 5.5 * urand(), urand() * 6.283185307179586,
			                         urand() < 0.7 ? 0.0 : urand() * 0.5, r * cos(a), r * sin(a)};
			post[count++] = s;
		}
	}
	// Random frozen breaks: the 15-ball rack, gap 0, the cue at 1-8 m/s aimed up to 3 degrees off
	// the apex (slow and off-centre breaks leave balls pushing each other: LINK's share).
	enum { RANDOM_BREAKS = 500 };
	shot *breaks = malloc(sizeof *breaks * RANDOM_BREAKS);
	if (!breaks)
		return 1;
	for (int k = 0; k < RANDOM_BREAKS; ++k) {
		breaks[k] = frozen;
		breaks[k].strike = pool_break_strike(1.0 + 7.0 * urand());
		breaks[k].strike.phi = (2.0 * urand() - 1.0) * 3.0 * 3.14159265358979323846 / 180.0;
	}
	// Warm up (allocations reach their final size), then measure.
	double *times = malloc(sizeof *times * (size_t)runs * 5);
	if (!times)
		return 1;
	memset(times, 0, sizeof *times * (size_t)runs * 5); // resident before the baseline
	pool_bench_summarise(times, (size_t)runs * 5);      // sorting allocates glibc's qsort buffer too
	printf("measuring...\n");
	fflush(stdout);
	// Airborne motion: the same machinery with flight segments and ball-cloth impacts.
	pool_sim_def air_def = def;
	air_def.airborne = true;
	pool_sim *air;
	if (pool_sim_create(&air_def, &air, &err) != POOL_OK) {
		fprintf(stderr, "pool-bench-shot: %s\n", err.message);
		return 1;
	}
	shot jump = {0};
	jump.n = 3;
	const double ids_x[3] = {0.6, 0.85, 1.9};
	for (int i = 0; i < 3; ++i) {
		jump.balls[i].id = i;
		jump.balls[i].pos = (pool_vec3){ids_x[i], 0.635, R};
	}
	jump.strike = (pool_strike){5.0, 0.0, 45.0 * 3.14159265358979323846 / 180.0, 0.0, 0.0};
	shot air_break = gap;
	air_break.strike.theta = 5.0 * 3.14159265358979323846 / 180.0;
	int ev;
	run(air, &jump, &ev); // warm up both simulations before the heap baseline
	run(air, &air_break, &ev);
	run(sim, &frozen, &ev);
	for (int i = 0; i < count; ++i)
		run(sim, &post[i], &ev);
	for (int i = 0; i < RANDOM_BREAKS; ++i)
		run(sim, &breaks[i], &ev);
	long rss_before = maxrss_kib(), allocs_before = lib_allocs;
	size_t peak_before = lib_peak_bytes;
	if (measure(sim, "break-frozen (8 m/s)", &frozen, 1, runs, times) ||
	    measure(sim, "break-gap-0.1mm (8 m/s)", &gap, 1, runs, times) ||
	    measure(sim, "post-break random shots", post, count, runs * 5, times) ||
	    measure(sim, "random frozen breaks (1-8 m/s)", breaks, RANDOM_BREAKS, runs, times))
		return 1;
	if (measure(air, "jump (airborne, 5 m/s, 45 deg)", &jump, 1, runs, times) ||
	    measure(air, "break-gap-0.1mm (airborne, 5 deg)", &air_break, 1, runs, times))
		return 1;
	pool_sim_destroy(air);
	long rss_after = maxrss_kib();
	printf("library heap: peak %zu bytes after warm-up, %zu bytes after %d more shots (one pool_sim reused); "
	       "library allocations during the runs: %ld\n",
	       peak_before, lib_peak_bytes, runs * 10, lib_allocs - allocs_before);
	printf("process peak resident memory (getrusage, includes the benchmark's own buffers): %ld KiB after "
	       "warm-up, %ld KiB after the runs\n",
	       rss_before, rss_after);
	free(times);
	free(post);
	free(breaks);
	pool_sim_destroy(sim);
	return 0;
}
