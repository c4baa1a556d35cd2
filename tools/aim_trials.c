// pool-aim-trials: does pool-aim find the pot, and is its p_success right? Seeded random layouts
// where a straight-in shot exists (a ball, a pocket, a cue ball with a clear cut under 60 degrees,
// up to 6 more balls clear of both paths); pool-aim searches each with that ball and pocket
// under fastfiz noise. Then, independently of the library's search and of its noise generator:
// the top shot re-simulated without noise (does it pot?), and with this program's own Gaussian
// generator many times (is the share that pots inside the reported 95 % interval?); and a plain
// ghost-ball aim at a fixed speed, centre ball, under the same noise, for comparison.
// docs/planning.md "Evidence", docs/measurements.md "pool-aim".
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "pool/aim.h"
#include "splitmix.h"

#define PROGRAM "pool-aim-trials"
#define TRIALS_MAX_BALLS 8
#define PI 3.14159265358979323846

static const char usage_text[] =
	"usage: pool-aim-trials [--layouts N] [--samples N] [--check N] [--speed V] [--seed S]\n"
	"                       [--threads N] [--min-found P] [--min-inside P] [--verbose]\n"
	"\n"
	"  --layouts N     random layouts with a straight-in shot (default 500)\n"
	"  --samples N     pool-aim's samples per reported p_success (default 400)\n"
	"  --check N       this program's own noisy repetitions of each top shot (default 2000)\n"
	"  --speed V       the ghost-ball baseline's cue speed, m/s (default 2)\n"
	"  --seed S        seed of the layouts (default 1)\n"
	"  --threads N     pool-aim's threads (default: online CPUs)\n"
	"  --min-found P   exit 1 when pool-aim's top shot pots without noise in less than P of the layouts\n"
	"  --min-inside P  exit 1 when the re-simulated share lies inside the reported interval in\n"
	"                  less than P of the layouts\n"
	"  --verbose       one line per layout\n"
	"  --print K       print layout K as a scenario (with its pocket) and stop\n";

// ---- this program's own random numbers (splitmix64, Box-Muller): not pool/noise.h -------------

typedef struct rng {
	uint64_t state;
} rng;

static double uniform(rng *r) {
	return pool_splitmix_uniform(&r->state);
}

static double between(rng *r, double lo, double hi) { return lo + (hi - lo) * uniform(r); }

static double normal(rng *r) {
	double u = uniform(r), v = uniform(r);
	return sqrt(-2.0 * log(u)) * cos(2.0 * PI * v);
}

// ---- layouts ----------------------------------------------------------------------------------

typedef struct layout {
	pool_ball_state balls[TRIALS_MAX_BALLS];
	int count;
	pool_pocket pocket;
	double ghost_phi; ///< the plain ghost-ball aim (rad)
} layout;

static double seg_distance(double px, double py, double ax, double ay, double bx, double by) {
	double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
	double f = l2 > 0 ? fmin(fmax(((px - ax) * dx + (py - ay) * dy) / l2, 0.0), 1.0) : 0.0;
	return hypot(px - ax - f * dx, py - ay - f * dy);
}

/// A layout with a straight-in shot of ball 1 into a pocket: the ball 0.2 to 1.2 m from the
/// pocket, inside its opening's reach (approach within 40 degrees of a corner's diagonal, 30 of a
/// side pocket's axis), the cue ball 0.3 to 1.5 m from the ghost ball at a cut under 60 degrees,
/// 0 to 6 more balls apart from both paths by a ball's width.
static void make_layout(rng *r, const pool_sim_def *def, layout *out) {
	const double R = def->params.ball_radius, L = def->table.length, W = def->table.width, margin = 0.08;
	const double px[6] = {0, L, 0, L, L / 2, L / 2}, py[6] = {0, 0, W, W, 0, W};
	const double axis[6] = {-135, -45, 135, 45, -90, 90};
	for (;;) {
		int p = (int)(uniform(r) * 6);
		double spread = p < 4 ? 40.0 : 30.0;
		double back = (axis[p] + 180.0 + between(r, -spread, spread)) * PI / 180.0, d = between(r, 0.2, 1.2);
		double ox = px[p] + d * cos(back), oy = py[p] + d * sin(back);
		if (ox < margin || ox > L - margin || oy < margin || oy > W - margin)
			continue;
		double ux = (px[p] - ox) / d, uy = (py[p] - oy) / d, gx = ox - 2 * R * ux, gy = oy - 2 * R * uy;
		double cut = between(r, -60.0, 60.0) * PI / 180.0, dc = between(r, 0.3, 1.5);
		double ca = atan2(uy, ux) + PI + cut, cx = gx + dc * cos(ca), cy = gy + dc * sin(ca);
		if (cx < margin || cx > L - margin || cy < margin || cy > W - margin || hypot(cx - ox, cy - oy) < 3 * R)
			continue;
		out->count = 2;
		out->pocket = (pool_pocket)p;
		out->ghost_phi = atan2(gy - cy, gx - cx);
		out->balls[0] = (pool_ball_state){.id = 0, .pos = {cx, cy, R}};
		out->balls[1] = (pool_ball_state){.id = 1, .pos = {ox, oy, R}};
		int extra = (int)(uniform(r) * 7);
		for (int tries = 0; out->count < 2 + extra && tries < 200; ++tries) {
			double x = between(r, margin, L - margin), y = between(r, margin, W - margin);
			bool ok = seg_distance(x, y, cx, cy, gx, gy) > 4 * R && seg_distance(x, y, ox, oy, px[p], py[p]) > 4 * R;
			for (int k = 0; k < out->count; ++k)
				ok = ok && hypot(x - out->balls[k].pos.x, y - out->balls[k].pos.y) > 2 * R + 0.005;
			if (ok)
				out->balls[out->count++] = (pool_ball_state){.id = out->count, .pos = {x, y, R}};
		}
		return;
	}
}

/// This program's own judgement: ball 1 dropped in the pocket, the cue ball still on the table.
static bool pots(pool_sim *sim, const pool_sim_def *def, const layout *l, const pool_strike *s) {
	if (pool_sim_reset(sim, def, NULL) != POOL_OK)
		return false;
	for (int k = 0; k < l->count; ++k)
		pool_sim_add_ball(sim, &l->balls[k], NULL);
	if (pool_sim_strike(sim, 0, s, NULL) != POOL_OK || pool_sim_run(sim) != POOL_OK)
		return false;
	int count = 0;
	const pool_event *events = pool_sim_events(sim, &count);
	bool potted = false;
	for (int e = 0; e < count; ++e)
		if (events[e].type == POOL_EVENT_POCKET && events[e].pocket == l->pocket &&
		    pool_sim_event_states(sim, &events[e])[0].id == 1)
			potted = true;
	const pool_motion cue = pool_sim_balls(sim)[0].motion;
	return potted && cue != POOL_MOTION_POCKETED && cue != POOL_MOTION_OFF_TABLE;
}

/// The share of n noisy repetitions of s that pot, noise with the sds of `noise` drawn here.
static double noisy_share(pool_sim *sim, const pool_sim_def *def, const layout *l, const pool_strike *s,
                          const pool_noise *noise, long n, rng *r) {
	long wins = 0;
	for (long i = 0; i < n; ++i) {
		pool_strike x = *s;
		x.speed += noise->speed * normal(r);
		x.phi += noise->phi * normal(r);
		x.theta = fabs(x.theta + noise->theta * normal(r));
		x.a += noise->a * normal(r);
		x.b += noise->b * normal(r);
		wins += pots(sim, def, l, &x);
	}
	return (double)wins / (double)n;
}

int main(int argc, char **argv) {
	long layouts = 500, samples = 400, check = 2000, seed = 1, threads = 0, print = -1;
	double speed = 2.0, min_found = -1.0, min_inside = -1.0;
	bool verbose = false;
	for (int i = 1; i < argc; ++i) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : "";
		if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
			fputs(usage_text, stdout);
			return 0;
		}
		if (strcmp(a, "--verbose") == 0) {
			verbose = true;
			continue;
		}
		++i;
		bool ok = (strcmp(a, "--layouts") == 0 && pool_cli_parse_count(v, &layouts) && layouts > 0) ||
		          (strcmp(a, "--samples") == 0 && pool_cli_parse_count(v, &samples) && samples > 0) ||
		          (strcmp(a, "--print") == 0 && pool_cli_parse_count(v, &print)) ||
		          (strcmp(a, "--check") == 0 && pool_cli_parse_count(v, &check) && check > 0) ||
		          (strcmp(a, "--seed") == 0 && pool_cli_parse_count(v, &seed) && seed > 0) ||
		          (strcmp(a, "--threads") == 0 && pool_cli_parse_count(v, &threads) && threads <= 1024) ||
		          (strcmp(a, "--speed") == 0 && pool_cli_parse_double(v, &speed) && speed > 0.0) ||
		          (strcmp(a, "--min-found") == 0 && pool_cli_parse_double(v, &min_found)) ||
		          (strcmp(a, "--min-inside") == 0 && pool_cli_parse_double(v, &min_inside));
		if (!ok)
			return pool_cli_usage_error(PROGRAM, "bad option or value: %s %s", pool_cli_arg(a), pool_cli_arg(v));
	}
	pool_sim_def def = pool_default_sim_def();
	pool_noise noise;
	pool_noise_preset("fastfiz", &noise);
	pool_sim *sim = NULL;
	if (pool_sim_create(&def, &sim, NULL) != POOL_OK)
		return POOL_EXIT_INTERNAL;
	long found = 0, inside = 0, none = 0, kinds[POOL_AIM_KINDS] = {0};
	double aim_sum = 0.0, ghost_sum = 0.0, seconds = 0.0, max_seconds = 0.0;
	for (long t = 0; t < layouts; ++t) {
		rng r = {.state = (uint64_t)seed * 0x9E3779B97F4A7C15ULL + (uint64_t)t};
		layout l;
		make_layout(&r, &def, &l);
		if (t == print) {
			printf("{\"format\": \"libpool-scenario/1\", \"description\": \"pool-aim-trials layout %ld (seed %ld): ball 1 "
			       "into %s\", \"balls\": [", t, seed, pool_pocket_name(l.pocket));
			for (int k = 0; k < l.count; ++k)
				printf("%s{\"id\": %d, \"pos\": [%.17g, %.17g]}", k ? ", " : "", (int)l.balls[k].id, l.balls[k].pos.x,
				       l.balls[k].pos.y);
			printf("]}\n");
			return 0;
		}
		pool_aim_def d = pool_default_aim_def();
		d.sim = def;
		d.balls = l.balls;
		d.ball_count = l.count;
		d.ball = 1;
		d.pocket = l.pocket;
		d.noise = noise;
		d.samples = (int)samples;
		d.top = 1;
		d.seed = (uint64_t)t + 1;
		d.threads = (int)threads;
		pool_aim_shot shot;
		pool_aim_stats stats;
		int count = 0;
		pool_error e;
		if (pool_aim_search(&d, &shot, 1, &count, &stats, &e) != POOL_OK) {
			fprintf(stderr, "%s: layout %ld: %s\n", PROGRAM, t, e.message);
			return POOL_EXIT_INTERNAL;
		}
		seconds += stats.seconds;
		max_seconds = fmax(max_seconds, stats.seconds);
		pool_strike ghost = {speed, l.ghost_phi, 0.0, 0.0, 0.0};
		double ghost_share = noisy_share(sim, &def, &l, &ghost, &noise, check, &r);
		ghost_sum += ghost_share;
		if (count == 0) {
			++none;
			if (verbose)
				printf("layout %ld: no shot; ghost ball %.3f\n", t, ghost_share);
			continue;
		}
		bool pot = pots(sim, &def, &l, &shot.strike);
		double share = noisy_share(sim, &def, &l, &shot.strike, &noise, check, &r);
		bool in = share >= shot.ci_low && share <= shot.ci_high;
		found += pot;
		inside += in;
		aim_sum += share;
		kinds[shot.kind]++;
		if (verbose)
			printf("layout %ld: %s %s, zero noise %s, p_success %.3f [%.3f, %.3f], re-simulated %.3f%s; ghost ball "
			       "%.3f; %.3f s\n", t, pool_aim_kind_name(shot.kind), pool_pocket_name(shot.pocket), pot ? "pots" : "MISSES",
			       shot.p_success, shot.ci_low, shot.ci_high, share, in ? "" : " OUTSIDE", ghost_share, stats.seconds);
	}
	pool_sim_destroy(sim);
	const double n = (double)layouts;
	printf("%s: %ld layouts with a straight-in shot (seed %ld), fastfiz noise, pool-aim %ld samples, check %ld "
	       "samples\n", PROGRAM, layouts, seed, samples, check);
	printf("  pool-aim's top shot pots without noise: %ld of %ld (%.1f %%); no shot found: %ld\n", found, layouts,
	       100.0 * (double)found / n, none);
	printf("  re-simulated share inside the reported 95 %% interval: %ld of %ld (%.1f %%)\n", inside, layouts,
	       100.0 * (double)inside / n);
	printf("  success under fastfiz noise, mean over layouts: pool-aim's top shot %.3f, ghost ball at %.2f m/s "
	       "%.3f\n", aim_sum / n, speed, ghost_sum / n);
	printf("  top shot kinds:");
	for (int k = 0; k < POOL_AIM_KINDS; ++k)
		printf(" %s %ld", pool_aim_kind_name((pool_aim_kind)k), kinds[k]);
	printf("\n  search time: mean %.3f s, max %.3f s\n", seconds / n, max_seconds);
	bool below = (min_found >= 0.0 && (double)found / n < min_found) || (min_inside >= 0.0 && (double)inside / n < min_inside);
	return below ? 1 : 0;
}
