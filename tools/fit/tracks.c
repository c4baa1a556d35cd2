// Observed tracks: a CSV of time, ball id and position, at any frame rate, with gaps.
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "csv_lines.h"
#include "fit.h"
#include "text_escape.h"

// The columns pool-fit reads; any other column is ignored (a camera's frame number, z, a
// confidence...).
enum { COL_T, COL_ID, COL_X, COL_Y, COL_READ };
static const char *const column_names[COL_READ] = {"t", "id", "x", "y"};
#define TRACKS_MAX_COLUMNS 64
// Observations per file: 10 balls at 1000 frames/s for 100 s.
#define TRACKS_MAX_ROWS 1000000L
// |t|, |x|, |y| above this are not a table's (the scenario parser's limit on numbers).
#define TRACKS_MAX_ABS 1e9

static int fail(char *err, size_t size, const char *format, ...) __attribute__((format(printf, 3, 4)));
static int fail(char *err, size_t size, const char *format, ...) {
	va_list args;
	va_start(args, format);
	vsnprintf(err, size, format, args);
	va_end(args);
	return POOL_EXIT_BAD_INPUT;
}

static int by_time(const void *pa, const void *pb) {
	const fit_observation *a = pa, *b = pb;
	if (a->t != b->t)
		return a->t < b->t ? -1 : 1;
	return a->line < b->line ? -1 : a->line > b->line; // stable: file order
}

int fit_tracks_parse(const char *file, const char *text, size_t length, const pool_scenario *layout,
                     fit_observation **out, long *count, char *err, size_t err_size) {
	*out = NULL;
	*count = 0;
	char name[POOL_ESCAPE_SHORT];
	pool_escape_str(name, sizeof name, file);
	pool_csv_reader r = pool_csv_start(text, length);
	pool_csv_cell cells[TRACKS_MAX_COLUMNS + 1];
	int n = pool_csv_next(&r, cells, TRACKS_MAX_COLUMNS);
	if (n == 0)
		return fail(err, err_size, "%s: no header (a line naming the columns t, id, x, y)", name);
	if (n > TRACKS_MAX_COLUMNS)
		return fail(err, err_size, "%s: line %ld: more than %d columns", name, r.line, TRACKS_MAX_COLUMNS);
	int column[COL_READ] = {-1, -1, -1, -1};
	for (int k = 0; k < n; ++k)
		for (int c = 0; c < COL_READ; ++c)
			if (pool_csv_is(&cells[k], column_names[c])) {
				if (column[c] >= 0)
					return fail(err, err_size, "%s: line %ld, column %d: %s is given twice", name, r.line, k + 1,
					            column_names[c]);
				column[c] = k;
			}
	for (int c = 0; c < COL_READ; ++c)
		if (column[c] < 0)
			return fail(err, err_size, "%s: line %ld: no column %s (the header names t, id, x, y)", name, r.line,
			            column_names[c]);
	const int columns = n;
	size_t capacity = 1024;
	fit_observation *obs = malloc(capacity * sizeof *obs);
	if (!obs) {
		snprintf(err, err_size, "out of memory");
		return POOL_EXIT_INTERNAL;
	}
	long rows = 0;
	int status = 0;
	while ((n = pool_csv_next(&r, cells, TRACKS_MAX_COLUMNS)) > 0) {
		if (n != columns) {
			status = fail(err, err_size, "%s: line %ld: %s%d cells, the header has %d", name, r.line,
			              n > TRACKS_MAX_COLUMNS ? "more than " : "", n > TRACKS_MAX_COLUMNS ? TRACKS_MAX_COLUMNS : n,
			              columns);
			break;
		}
		fit_observation o = {.line = r.line};
		double v[COL_READ];
		bool empty[COL_READ];
		for (int c = 0; c < COL_READ; ++c) {
			const pool_csv_cell *cell = &cells[column[c]];
			empty[c] = cell->begin == cell->end;
			if (empty[c] && (c == COL_X || c == COL_Y))
				continue;
			if (!pool_csv_double(cell, &v[c]) || fabs(v[c]) > TRACKS_MAX_ABS) {
				char shown[POOL_ESCAPE_SHORT];
				pool_escape_text(shown, sizeof shown, cell->begin, (size_t)(cell->end - cell->begin));
				status = fail(err, err_size, "%s: line %ld, column %s: '%s' is not a %s", name, r.line,
				              column_names[c], shown,
				              c == COL_ID ? "ball id" : c == COL_T ? "time in seconds" : "position in metres");
				break;
			}
		}
		if (status)
			break;
		if (empty[COL_X] != empty[COL_Y]) {
			status = fail(err, err_size, "%s: line %ld: x and y must both be given or both be empty (a "
			              "frame where the ball was not seen)", name, r.line);
			break;
		}
		o.ball = -1;
		for (int k = 0; k < layout->ball_count; ++k)
			if ((double)layout->balls[k].id == v[COL_ID])
				o.ball = k;
		if (o.ball < 0) {
			status = fail(err, err_size, "%s: line %ld, column id: no ball of the scenario has id %.17g", name,
			              r.line, v[COL_ID]);
			break;
		}
		if (empty[COL_X])
			continue; // not seen in this frame
		o.t = v[COL_T];
		o.x = v[COL_X];
		o.y = v[COL_Y];
		if (rows == TRACKS_MAX_ROWS) {
			status = fail(err, err_size, "%s: more than %ld observations", name, TRACKS_MAX_ROWS);
			break;
		}
		if ((size_t)rows == capacity) {
			fit_observation *bigger = realloc(obs, 2 * capacity * sizeof *obs);
			if (!bigger) {
				snprintf(err, err_size, "out of memory");
				status = POOL_EXIT_INTERNAL;
				break;
			}
			obs = bigger;
			capacity *= 2;
		}
		obs[rows++] = o;
	}
	if (!status && rows == 0)
		status = fail(err, err_size, "%s: no observations (rows with t, id, x and y)", name);
	if (status) {
		free(obs);
		return status;
	}
	qsort(obs, (size_t)rows, sizeof *obs, by_time);
	*out = obs;
	*count = rows;
	return 0;
}

static int by_value(const void *a, const void *b) {
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

double fit_track_noise(const fit_shot *shots, int count) {
	// Per ball, the second difference of its positions over three frames evenly spaced in time:
	// the motion's share is a dt^2 (0.2 mm at 100 Hz for 2 m/s^2), the noise's has variance 6
	// sigma^2. The median of |d| is 0.6745 sqrt(6) sigma for Gaussian noise, and collisions, a few
	// frames among hundreds, do not move it.
	long total = 0;
	for (int s = 0; s < count; ++s)
		total += 2 * shots[s].obs_count;
	double *d = malloc((size_t)(total > 0 ? total : 1) * sizeof *d);
	if (!d)
		return NAN;
	long n = 0;
	for (int s = 0; s < count; ++s) {
		const fit_shot *sh = &shots[s];
		for (int b = 0; b < sh->scenario.ball_count; ++b) {
			const fit_observation *prev = NULL, *mid = NULL;
			for (long i = 0; i < sh->obs_count; ++i) {
				const fit_observation *o = &sh->obs[i];
				if (o->ball != b)
					continue;
				if (prev && mid && fabs((o->t - mid->t) - (mid->t - prev->t)) <= 1e-9 * fabs(o->t - prev->t) &&
				    o->t > mid->t) {
					d[n++] = fabs(o->x - 2.0 * mid->x + prev->x);
					d[n++] = fabs(o->y - 2.0 * mid->y + prev->y);
				}
				prev = mid;
				mid = o;
			}
		}
	}
	double sigma = NAN;
	if (n >= 10) {
		qsort(d, (size_t)n, sizeof *d, by_value);
		sigma = d[n / 2] / (0.6744897501960817 * sqrt(6.0));
	}
	free(d);
	return sigma;
}
