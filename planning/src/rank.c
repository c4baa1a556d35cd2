// Shots ranked by their chance of success under the stroke's noise. Every shot that pots without
// noise is repeated with noise (pool/noise.h: sample i of a stream is a pure function of the
// seed and i), in rounds of doubling size; after each round a shot whose 95 % interval lies
// wholly below the top K's lower bounds is dropped, so samples go only where the ranking is
// undecided. The K chosen are then estimated afresh, from samples that played no part in the
// choice: a shot picked because its first samples were lucky would otherwise be reported too
// good (the winner's curse).
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "aim_internal.h"

// Samples of the first round; each round doubles them, up to def->samples.
#define AIM_FIRST_ROUND 32
// Samples per round of the fresh estimate when a time budget may stop it (at least one round).
#define AIM_REPORT_CHUNK 64
// Sample numbers: stream << 62 | candidate << 24 | i. 2^24 samples per shot and 2^38 candidates
// are far beyond any search.
#define AIM_SAMPLE_BITS 24

// The two-sided 95 % normal quantile.
#define AIM_Z95 1.959963984540054

void aim_wilson(long k, long n, double *lo, double *hi) {
	if (n <= 0) {
		*lo = 0.0, *hi = 1.0;
		return;
	}
	// Wilson's score interval with continuity correction (Newcombe 1998, method 4). Without the
	// correction its coverage dips below 95 % for shares near 0 and 1, the shares a good shot has.
	const double z = AIM_Z95, z2 = z * z, nn = (double)n, p = (double)k / nn, q = 1.0 - p;
	const double denom = 2.0 * (nn + z2);
	*lo = k == 0 ? 0.0 : fmax(0.0, (2.0 * nn * p + z2 - 1.0 - z * sqrt(z2 - 2.0 - 1.0 / nn + 4.0 * p * (nn * q + 1.0))) / denom);
	*hi = k == n ? 1.0 : fmin(1.0, (2.0 * nn * p + z2 + 1.0 + z * sqrt(z2 + 2.0 - 1.0 / nn + 4.0 * p * (nn * q - 1.0))) / denom);
}

/// One round: candidates list[0..count) get samples [have[k], want) of a stream.
typedef struct round_job {
	const int *list;
	int count;
	const long *have;     ///< per listed candidate
	long want;
	const long *first;    ///< prefix sums of the tasks per listed candidate (count + 1)
	atomic_long *wins;    ///< per listed candidate
	uint64_t stream;
} round_job;

static void sample_task(aim_search *s, aim_worker *w, long task, void *ctx) {
	round_job *j = ctx;
	int lo = 0, hi = j->count - 1; // the listed candidate whose tasks hold this one
	while (lo < hi) {
		int mid = (lo + hi + 1) / 2;
		if (j->first[mid] <= task)
			lo = mid;
		else
			hi = mid - 1;
	}
	const int index = j->list[lo];
	const aim_candidate *c = &s->cands[index];
	const uint64_t i = (uint64_t)(j->have[lo] + (task - j->first[lo]));
	const uint64_t sample = j->stream << 62 | (uint64_t)index << AIM_SAMPLE_BITS | i;
	pool_strike strike = pool_noise_apply(&s->def->noise, s->def->seed, sample, &c->strike);
	// A noisy strike the library refuses (a miscue: a^2 + b^2 >= R^2) is a failure.
	if (aim_simulate(s, w, c, &strike) == POOL_OK && aim_success(s, w, c))
		atomic_fetch_add(&j->wins[lo], 1);
}

/// Brings the listed candidates to `want` samples of the stream (ranking or report counters).
static int sample_round(aim_search *s, const int *list, int count, long want, uint64_t stream) {
	long *have = malloc((size_t)count * sizeof *have), *first = malloc(((size_t)count + 1) * sizeof *first);
	atomic_long *wins = malloc((size_t)count * sizeof *wins);
	if (!have || !first || !wins) {
		free(have), free(first), free(wins);
		return -1;
	}
	first[0] = 0;
	for (int k = 0; k < count; ++k) {
		const aim_candidate *c = &s->cands[list[k]];
		have[k] = stream ? c->report_samples : c->samples;
		first[k + 1] = first[k] + (want > have[k] ? want - have[k] : 0);
		atomic_init(&wins[k], 0);
	}
	round_job job = {list, count, have, want, first, wins, stream};
	aim_parallel(s, first[count], sample_task, &job);
	for (int k = 0; k < count; ++k) {
		aim_candidate *c = &s->cands[list[k]];
		long added = first[k + 1] - first[k], won = atomic_load(&wins[k]);
		if (stream) {
			c->report_samples += added, c->report_successes += won;
		} else {
			c->samples += added, c->successes += won;
		}
	}
	free(have), free(first), free(wins);
	return 0;
}

static double rate(const aim_candidate *c, bool report) {
	long n = report ? c->report_samples : c->samples, k = report ? c->report_successes : c->successes;
	return n > 0 ? (double)k / (double)n : 0.0;
}

/// Better first: the higher rate, then the better position, then the easier geometry, then the
/// earlier candidate (a total order: the result does not depend on the sort).
static int compare(const aim_search *s, int a, int b, bool report) {
	const aim_candidate *x = &s->cands[a], *y = &s->cands[b];
	double px = rate(x, report), py = rate(y, report);
	if (px != py)
		return px > py ? -1 : 1;
	if (x->position != y->position)
		return x->position > y->position ? -1 : 1;
	if (x->difficulty != y->difficulty)
		return x->difficulty < y->difficulty ? -1 : 1;
	return (a > b) - (a < b);
}
/// Sorts candidate indices, better first (insertion: a few hundred at most, and no global state
/// for qsort's comparison, so searches may run in parallel).
static void sort_indices(const aim_search *s, int *order, int n, bool report) {
	for (int k = 1; k < n; ++k) {
		int v = order[k], j = k;
		for (; j > 0 && compare(s, order[j - 1], v, report) > 0; --j)
			order[j] = order[j - 1];
		order[j] = v;
	}
}

/// Whether two candidates are the same shot but for speed and spin (def->distinct keeps one).
static bool same_shot(const aim_search *s, int a, int b) {
	const aim_candidate *x = &s->cands[a], *y = &s->cands[b];
	return x->kind == y->kind && x->ball == y->ball && x->via == y->via && x->pocket == y->pocket && x->rail == y->rail;
}

/// With def->distinct, the candidates order[0..n) that another one before them does not repeat
/// (the first of each shot), moved to the front in order; else all. Returns how many.
static int distinct_first(const aim_search *s, int *order, int n) {
	if (!s->def->distinct)
		return n;
	int kept = 0;
	for (int k = 0; k < n; ++k) {
		bool repeat = false;
		for (int j = 0; j < kept && !repeat; ++j)
			repeat = same_shot(s, order[j], order[k]);
		if (!repeat) { // keep the rest behind, in their order
			int v = order[k];
			for (int j = k; j > kept; --j)
				order[j] = order[j - 1];
			order[kept++] = v;
		}
	}
	return kept;
}

int aim_rank(aim_search *s, int *order) {
	const pool_aim_def *d = s->def;
	int alive = 0;
	for (int k = 0; k < s->count; ++k)
		if (s->cands[k].state == AIM_POTS)
			order[alive++] = k;
	const int K = d->top;
	double *lower = malloc((size_t)(alive > 0 ? alive : 1) * sizeof *lower);
	if (!lower)
		return -1;
	for (long want = AIM_FIRST_ROUND < d->samples ? AIM_FIRST_ROUND : d->samples; alive > 0;) {
		if (sample_round(s, order, alive, want, 0) != 0) {
			free(lower);
			return -1;
		}
		if (alive <= K || want >= d->samples || aim_now() > s->deadline)
			break;
		// The K-th best lower bound: a shot whose upper bound is below it cannot be in the top K.
		// With def->distinct, each shot counts once, by its best variant.
		int shots = 0;
		for (int k = 0; k < alive; ++k) {
			double hi;
			aim_wilson(s->cands[order[k]].successes, s->cands[order[k]].samples, &lower[k], &hi);
			for (int j = 0; d->distinct && j < k && lower[k] >= 0.0; ++j)
				if (lower[j] >= 0.0 && same_shot(s, order[j], order[k])) {
					if (lower[k] > lower[j])
						lower[j] = lower[k];
					lower[k] = -1.0;
				}
			shots += lower[k] >= 0.0;
		}
		if (shots <= K)
			break;
		double *sorted = lower; // descending, in place: only the K-th value is needed
		for (int a = 0; a < K; ++a)
			for (int b = a + 1; b < alive; ++b)
				if (sorted[b] > sorted[a]) {
					double t = sorted[a];
					sorted[a] = sorted[b], sorted[b] = t;
				}
		const double threshold = sorted[K - 1];
		int kept = 0;
		for (int k = 0; k < alive; ++k) {
			double lo, hi;
			aim_wilson(s->cands[order[k]].successes, s->cands[order[k]].samples, &lo, &hi);
			if (hi >= threshold)
				order[kept++] = order[k];
		}
		alive = kept;
		if (alive <= K)
			break;
		want = 2 * want < d->samples ? 2 * want : d->samples;
	}
	free(lower);
	sort_indices(s, order, alive, false);
	const int shots = distinct_first(s, order, alive);
	int chosen = shots < K ? shots : K;
	// The fresh estimate of the chosen, in chunks while a time budget runs.
	for (long want = isfinite(s->deadline) ? AIM_REPORT_CHUNK : d->samples;; want += AIM_REPORT_CHUNK) {
		if (want > d->samples)
			want = d->samples;
		if (chosen > 0 && sample_round(s, order, chosen, want, 1) != 0)
			return -1;
		if (want >= d->samples || aim_now() > s->deadline)
			break;
	}
	sort_indices(s, order, chosen, true);
	return chosen;
}
