// pool-batch: one layout (a libpool-scenario/1 file), many strikes (a CSV or JSON list, a grid or a
// seeded random sample), simulated on every core, one result row per strike in input order.
// Exit status: 0 success (rows of strikes the library refuses carry its message), 2 bad input or
// usage (message names the option, field, line or column), 1 internal failure (out of memory, an
// output that cannot be written, a shot the library failed to simulate: its row says so).
//
// Threads: each worker owns one pool_sim, reused for every shot it takes (pool_scenario_setup
// resets it), and claims the next shot index under a mutex. Each shot's row is formatted into a
// slot of a ring of BATCH_WINDOW slots; the main thread writes the slots out in index order, so
// the output does not depend on the number of threads or on which thread ran which shot.
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "batch_layout.h"
#include "pool/batch.h"
#include "cli.h"
#include "game_json.h"
#include "json_writer.h"
#include "models_json.h"
#include "read_input.h"
#include "pool/scenario.h"
#include "text_buffer.h"
#include "text_escape.h"

#define PROGRAM "pool-batch"
// The scenario parser's limit on numbers (nothing on a table is 1e9 m, m/s or degrees).
#define BATCH_MAX_ABS POOL_SCENARIO_MAX_ABS
#define BATCH_MAX_SHOTS 100000000L
#define BATCH_MAX_THREADS 1024
// Rows formatted ahead of the one being written: bounds the memory of a streamed run.
#define BATCH_WINDOW 4096
// Rows the writer lets finish before it wakes up to write them (far below BATCH_WINDOW).
#define BATCH_WAKE_ROWS 64

enum { P_SPEED, P_PHI, P_THETA, P_A, P_B, P_COUNT };
static const char *const param_names[P_COUNT] = {"speed", "phi", "theta", "a", "b"};

/// A strike as the user writes it: angles in degrees.
typedef struct batch_strike {
	int32_t ball;
	double v[P_COUNT]; ///< speed m/s, phi deg, theta deg, a m, b m
} batch_strike;

typedef enum batch_mode { MODE_NONE, MODE_LIST, MODE_GRID, MODE_RANDOM } batch_mode;
typedef enum batch_format { FORMAT_CSV, FORMAT_JSONL } batch_format;

/// One parameter of --grid (lo:hi:count) or --ranges (lo:hi), in the order written.
typedef struct batch_axis {
	int param;
	double lo, hi;
	long count; ///< grid points (1 for a fixed value); unused by --ranges
} batch_axis;

typedef struct batch_options {
	const char *layout_path;
	const char *output_path; ///< NULL = standard output
	batch_mode mode;
	const char *strikes_path;
	const char *grid_spec;
	const char *ranges_spec;
	const char *noise_spec; ///< --noise: a preset or NAME=SD pairs (pool/noise.h)
	long random_count;
	long seed;
	bool have_ball;
	int32_t ball;
	long threads; ///< 0 = online CPUs
	batch_format format;
	const char *models; ///< --models: applied to the layout's models (NULL: the layout's)
	size_t max_input;
	bool no_progress;
	bool help;
} batch_options;

static const char usage_text[] =
	"usage: pool-batch LAYOUT.json (--strikes FILE | --grid SPEC | --random N --ranges SPEC)\n"
	"                  [--noise NAME|SPEC] [--seed S] [--ball ID] [--threads N] [--models SET]\n"
	"                  [--format csv|jsonl] [-o FILE] [--max-input BYTES] [--no-progress]\n"
	"\n"
	"Simulates many strikes on one layout (a libpool-scenario/1 file; its strike, if any, is the\n"
	"base strike: parameters a strike does not give are taken from it) on every core, and prints\n"
	"one row per strike, in input order: the strike, stop reason, event count, first ball hit by\n"
	"the struck ball, pocketed and off-table balls, final position and state of every ball; with a\n"
	"\"game\" in the layout, whether the shot was legal, its fouls, outcome, reason and points.\n"
	"\n"
	"  --strikes FILE     a CSV file (header naming columns among ball,speed,phi,theta,a,b) or a\n"
	"                     JSON array of objects with those keys; angles in degrees\n"
	"  --grid SPEC        every combination of NAME=LO:HI:COUNT (COUNT evenly spaced values from\n"
	"                     LO to HI inclusive) or NAME=VALUE, comma-separated, NAME among\n"
	"                     speed,phi,theta,a,b; the first parameter varies slowest\n"
	"  --random N         N strikes with each parameter of --ranges drawn uniformly in [LO, HI)\n"
	"  --ranges SPEC      NAME=LO:HI or NAME=VALUE, comma-separated (with --random)\n"
	"  --noise NAME|SPEC  Gaussian noise on every strike: a preset (none, fastfiz) or NAME=SD\n"
	"                     pairs, comma-separated, NAME among speed (m/s), phi, theta (degrees),\n"
	"                     a, b (m); the rows show the strikes as simulated\n"
	"  --seed S           seed of --random and --noise (integer >= 0, default 1); strike i\n"
	"                     depends only on the seed, i and the ranges or noise\n"
	"  --ball ID          struck ball when a strike does not say (default: the layout's strike\n"
	"                     ball, else the layout's first ball)\n"
	"  --threads N        worker threads (default: the number of online CPUs)\n"
	"  --format F         csv (default; one column group per ball id) or jsonl (a JSON object\n"
	"                     per line)\n"
	"  --models SET       the laws of every shot instead of the layout's \"models\": a model set,\n"
	"                     default (the measured laws) or thesis (the 2012 work's), or model names\n"
	"                     joined with '+' (thesis+endmass), applied to the layout's models\n"
	"  -o, --output FILE  write to FILE instead of standard output (atomically)\n"
	"  --max-input BYTES  refuse a layout or strike file longer than BYTES (default 64M)\n"
	"  --no-progress      no progress line (it is shown on a terminal for runs over 1 s)\n"
	"  -h, --help         show this help\n"
	"\n"
	"A strike the library refuses (a^2 + b^2 >= R^2, unknown ball, speed out of range...) gives a\n"
	"row with stop_reason \"error\" and the library's message; the other rows are simulated.\n"
	"Exit status: 0 success, 2 bad input or usage (message names the field), 1 internal error.\n";

// ---- small helpers --------------------------------------------------------------------------

static bool parse_int32(const char *text, int32_t *out) {
	char *end = NULL;
	errno = 0;
	long long x = strtoll(text, &end, 10);
	if (errno || end == text || *end || x < INT32_MIN || x > INT32_MAX)
		return false;
	*out = (int32_t)x;
	return true;
}

/// Output rows and files are built in the tools' growing text buffer.
typedef pool_text_buffer sbuf;

static void sb_put(sbuf *b, const char *text, size_t n) { pool_text_append(b, text, n); }

static void sb_str(sbuf *b, const char *text) { sb_put(b, text, strlen(text)); }

static void sb_num(sbuf *b, double x) {
	char text[32];
	pool_jw_format_double(x, text);
	sb_str(b, text);
}

static void sb_int(sbuf *b, long long x) {
	char text[32];
	snprintf(text, sizeof text, "%lld", x);
	sb_str(b, text);
}

/// A CSV field in double quotes (quotes doubled, line breaks as spaces).
static void sb_csv_quoted(sbuf *b, const char *text) {
	sb_put(b, "\"", 1);
	for (const char *p = text; *p; ++p) {
		if (*p == '"')
			sb_put(b, "\"\"", 2);
		else if (*p == '\n' || *p == '\r')
			sb_put(b, " ", 1);
		else
			sb_put(b, p, 1);
	}
	sb_put(b, "\"", 1);
}

static int param_index(const char *name, size_t n) {
	for (int p = 0; p < P_COUNT; ++p)
		if (strlen(param_names[p]) == n && strncmp(param_names[p], name, n) == 0)
			return p;
	return -1;
}

// ---- --grid and --ranges --------------------------------------------------------------------

/// Parses "NAME=LO:HI:COUNT,..." (grid) or "NAME=LO:HI,..." (ranges); NAME=VALUE is one value.
static int parse_axes(const char *option, const char *spec, bool grid, batch_axis *axes,
                      int *count) {
	*count = 0;
	if (!spec[0])
		return pool_cli_usage_error(PROGRAM, "%s: empty specification (e.g. speed=1:6:11,phi=0:350:36)",
		                            option);
	const char *p = spec;
	for (;;) {
		const char *end = strchr(p, ',');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		char item[256];
		char shown[POOL_ESCAPE_SHORT];
		pool_escape_text(shown, sizeof shown, p, n);
		if (n == 0 || n >= sizeof item)
			return pool_cli_usage_error(PROGRAM, "%s: '%s' is not NAME=%s", option, shown,
			                            grid ? "LO:HI:COUNT" : "LO:HI");
		memcpy(item, p, n);
		item[n] = '\0';
		char *eq = strchr(item, '=');
		if (!eq)
			return pool_cli_usage_error(PROGRAM, "%s: '%s' is not NAME=%s", option, shown,
			                            grid ? "LO:HI:COUNT" : "LO:HI");
		int param = param_index(item, (size_t)(eq - item));
		if (param < 0) {
			char name[POOL_ESCAPE_SHORT];
			pool_escape_text(name, sizeof name, item, (size_t)(eq - item));
			return pool_cli_usage_error(PROGRAM, "%s: '%s': unknown parameter (speed, phi, theta, a, b)",
			                            option, name);
		}
		for (int i = 0; i < *count; ++i)
			if (axes[i].param == param)
				return pool_cli_usage_error(PROGRAM, "%s: %s is given twice", option, param_names[param]);
		char *parts[4] = {eq + 1, NULL, NULL, NULL};
		int nparts = 1;
		for (char *c = eq + 1; *c; ++c)
			if (*c == ':') {
				*c = '\0';
				if (nparts == 4)
					break;
				parts[nparts++] = c + 1;
			}
		batch_axis *a = &axes[*count];
		a->param = param;
		a->count = 1;
		int want = grid ? 3 : 2;
		if (nparts != 1 && nparts != want)
			return pool_cli_usage_error(PROGRAM, "%s: %s: '%s' is not %s or a single value", option,
			                            param_names[param], shown, grid ? "LO:HI:COUNT" : "LO:HI");
		double values[2];
		for (int k = 0; k < (nparts == 1 ? 1 : 2); ++k) {
			if (!pool_cli_parse_double(parts[k], &values[k]))
				return pool_cli_usage_error(PROGRAM, "%s: %s: '%s' is not a number", option,
				                            param_names[param], pool_cli_arg(parts[k]));
			if (fabs(values[k]) > BATCH_MAX_ABS)
				return pool_cli_usage_error(PROGRAM, "%s: %s: %s is too large (limit %g)", option,
				                            param_names[param], pool_cli_arg(parts[k]), BATCH_MAX_ABS);
		}
		a->lo = values[0];
		a->hi = nparts == 1 ? values[0] : values[1];
		if (grid && nparts == 3) {
			if (!pool_cli_parse_count(parts[2], &a->count) || a->count < 1 || a->count > BATCH_MAX_SHOTS)
				return pool_cli_usage_error(PROGRAM, "%s: %s: count '%s' is not a whole number from 1 to %ld",
				                            option, param_names[param], pool_cli_arg(parts[2]),
				                            BATCH_MAX_SHOTS);
			if (a->count == 1 && a->lo != a->hi)
				return pool_cli_usage_error(PROGRAM, "%s: %s: a count of 1 needs LO = HI (or write %s=VALUE)",
				                            option, param_names[param], param_names[param]);
		}
		++*count;
		if (!end)
			break;
		p = end + 1;
	}
	return 0;
}

/// Value k of count evenly spaced from lo to hi inclusive (exactly lo and hi at the ends).
static double grid_value(const batch_axis *a, long k) {
	if (a->count == 1 || k == 0)
		return a->lo;
	if (k == a->count - 1)
		return a->hi;
	return a->lo + ((a->hi - a->lo) * (double)k) / (double)(a->count - 1);
}

static uint64_t splitmix64(uint64_t *state) {
	uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

// ---- strike lists ---------------------------------------------------------------------------

typedef struct strike_list {
	batch_strike *items;
	long count, capacity;
} strike_list;

static int list_push(strike_list *l, const batch_strike *s) {
	if (l->count == l->capacity) {
		long capacity = l->capacity ? 2 * l->capacity : 256;
		batch_strike *items = realloc(l->items, (size_t)capacity * sizeof *items);
		if (!items)
			return -1;
		l->items = items;
		l->capacity = capacity;
	}
	l->items[l->count++] = *s;
	return 0;
}

/// What a strike takes when it does not give a parameter.
typedef struct strike_base {
	batch_strike strike;
	bool has_speed; ///< the layout had a strike (else every strike must give its speed)
} strike_base;

static int list_error(const char *file, const char *format, ...) __attribute__((format(printf, 2, 3)));
static int list_error(const char *file, const char *format, ...) {
	char shown[POOL_ESCAPE_LONG];
	fprintf(stderr, "%s: %s: ", PROGRAM, pool_escape_str(shown, sizeof shown, file));
	va_list args;
	va_start(args, format);
	vfprintf(stderr, format, args);
	va_end(args);
	fputc('\n', stderr);
	return POOL_EXIT_BAD_INPUT;
}

static const char no_speed[] = "the layout has no strike to take the speed from";

static int parse_json_list(const char *file, const char *data, size_t length, const strike_base *base,
                           strike_list *out) {
	json_error_t jerr;
	json_t *root = json_loadb(data, length, JSON_REJECT_DUPLICATES, &jerr);
	if (!root) {
		char shown[POOL_ESCAPE_LONG];
		return list_error(file, "malformed JSON at line %d, column %d: %s", jerr.line, jerr.column,
		                  pool_escape_str(shown, sizeof shown, jerr.text));
	}
	int status = 0;
	if (!json_is_array(root)) {
		status = list_error(file, "(document): must be a JSON array of strikes");
		goto done;
	}
	for (size_t i = 0; i < json_array_size(root) && status == 0; ++i) {
		json_t *o = json_array_get(root, i);
		if (!json_is_object(o)) {
			status = list_error(file, "[%zu]: must be an object", i);
			break;
		}
		batch_strike s = base->strike;
		const char *key;
		json_t *value;
		json_object_foreach(o, key, value) {
			int p = param_index(key, strlen(key));
			if (p < 0 && strcmp(key, "ball") != 0) {
				char shown[POOL_ESCAPE_SHORT];
				status = list_error(file, "[%zu].%s: unknown field (ball, speed, phi, theta, a, b)", i,
				                    key[0] ? pool_escape_str(shown, sizeof shown, key) : "\"\"");
				break;
			}
			if (p < 0) {
				json_int_t id = json_integer_value(value);
				if (!json_is_integer(value) || id < INT32_MIN || id > INT32_MAX) {
					status = list_error(file, "[%zu].ball: must be a ball id (a 32-bit integer)", i);
					break;
				}
				s.ball = (int32_t)id;
				continue;
			}
			if (!json_is_number(value)) {
				status = list_error(file, "[%zu].%s: must be a number", i, param_names[p]);
				break;
			}
			double x = json_number_value(value);
			if (!isfinite(x) || fabs(x) > BATCH_MAX_ABS) {
				status = list_error(file, "[%zu].%s: %g is too large (limit %g)", i, param_names[p], x,
				                    BATCH_MAX_ABS);
				break;
			}
			s.v[p] = x;
		}
		if (status)
			break;
		if (!base->has_speed && !json_object_get(o, "speed")) {
			status = list_error(file, "[%zu].speed: missing (%s)", i, no_speed);
			break;
		}
		if (out->count >= BATCH_MAX_SHOTS) {
			status = list_error(file, "more than %ld strikes", BATCH_MAX_SHOTS);
			break;
		}
		if (list_push(out, &s)) {
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
			status = POOL_EXIT_INTERNAL;
		}
	}
done:
	json_decref(root);
	return status;
}

/// Cuts the spaces and tabs around [*begin, *end).
static void trim(const char **begin, const char **end) {
	while (*begin < *end && (**begin == ' ' || **begin == '\t'))
		++*begin;
	while (*end > *begin && ((*end)[-1] == ' ' || (*end)[-1] == '\t'))
		--*end;
}

static int parse_csv_list(const char *file, const char *data, size_t length, const strike_base *base,
                          strike_list *out) {
	int columns[P_COUNT + 1]; // per header cell: a param index, P_COUNT for ball
	int ncolumns = 0;
	bool header = false;
	long line = 0;
	const char *p = data, *end_of_data = data + length;
	while (p < end_of_data) {
		const char *nl = memchr(p, '\n', (size_t)(end_of_data - p));
		const char *line_end = nl ? nl : end_of_data;
		const char *next = nl ? nl + 1 : end_of_data;
		++line;
		if (line_end > p && line_end[-1] == '\r')
			--line_end;
		const char *b = p, *e = line_end;
		trim(&b, &e);
		p = next;
		if (b == e || *b == '#')
			continue; // blank lines and comments
		// Split into cells.
		const char *cells[P_COUNT + 2][2];
		int ncells = 0;
		const char *c = b;
		bool too_many = false;
		for (;;) {
			const char *comma = memchr(c, ',', (size_t)(e - c));
			const char *cell_end = comma ? comma : e;
			if (ncells == P_COUNT + 2) {
				too_many = true;
				break;
			}
			cells[ncells][0] = c;
			cells[ncells][1] = cell_end;
			trim(&cells[ncells][0], &cells[ncells][1]);
			++ncells;
			if (!comma)
				break;
			c = comma + 1;
		}
		if (!header) {
			if (too_many || ncells > P_COUNT + 1)
				return list_error(file, "line %ld: the header has more than the %d columns ball, speed, "
				                  "phi, theta, a, b", line, P_COUNT + 1);
			for (int k = 0; k < ncells; ++k) {
				size_t n = (size_t)(cells[k][1] - cells[k][0]);
				int col = n == 4 && strncmp(cells[k][0], "ball", 4) == 0 ? P_COUNT
				                                                         : param_index(cells[k][0], n);
				char shown[POOL_ESCAPE_SHORT];
				pool_escape_text(shown, sizeof shown, cells[k][0], n);
				if (col < 0)
					return list_error(file, "line %ld, column %d: '%s' is not a column name (ball, speed, "
					                  "phi, theta, a, b)", line, k + 1, shown);
				for (int j = 0; j < k; ++j)
					if (columns[j] == col)
						return list_error(file, "line %ld, column %d: %s is given twice", line, k + 1, shown);
				columns[k] = col;
			}
			ncolumns = ncells;
			bool speed = false;
			for (int k = 0; k < ncolumns; ++k)
				speed = speed || columns[k] == P_SPEED;
			if (!speed && !base->has_speed)
				return list_error(file, "line %ld: no speed column (%s)", line, no_speed);
			header = true;
			continue;
		}
		long index = out->count;
		if (too_many || ncells != ncolumns)
			return list_error(file, "line %ld (strike %ld): %s%d cells, the header has %d", line, index,
			                  too_many ? "more than " : "", too_many ? P_COUNT + 2 : ncells, ncolumns);
		batch_strike s = base->strike;
		for (int k = 0; k < ncolumns; ++k) {
			const char *name = columns[k] == P_COUNT ? "ball" : param_names[columns[k]];
			size_t n = (size_t)(cells[k][1] - cells[k][0]);
			char shown[POOL_ESCAPE_SHORT];
			pool_escape_text(shown, sizeof shown, cells[k][0], n);
			if (n == 0) {
				if (columns[k] == P_SPEED && !base->has_speed)
					return list_error(file, "line %ld (strike %ld), column speed: empty (%s)", line, index,
					                  no_speed);
				continue; // the base value
			}
			char text[64];
			if (n >= sizeof text || memchr(cells[k][0], '\0', n))
				return list_error(file, "line %ld (strike %ld), column %s: '%s' is not a %s", line, index,
				                  name, shown, columns[k] == P_COUNT ? "ball id" : "number");
			memcpy(text, cells[k][0], n);
			text[n] = '\0';
			if (columns[k] == P_COUNT) {
				if (!parse_int32(text, &s.ball))
					return list_error(file, "line %ld (strike %ld), column ball: '%s' is not a ball id (a "
					                  "32-bit integer)", line, index, shown);
				continue;
			}
			double x;
			if (!pool_cli_parse_double(text, &x))
				return list_error(file, "line %ld (strike %ld), column %s: '%s' is not a number", line,
				                  index, name, shown);
			if (fabs(x) > BATCH_MAX_ABS)
				return list_error(file, "line %ld (strike %ld), column %s: '%s' is too large (limit %g)",
				                  line, index, name, shown, BATCH_MAX_ABS);
			s.v[columns[k]] = x;
		}
		if (out->count >= BATCH_MAX_SHOTS)
			return list_error(file, "more than %ld strikes", BATCH_MAX_SHOTS);
		if (list_push(out, &s)) {
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
			return POOL_EXIT_INTERNAL;
		}
	}
	if (!header)
		return list_error(file, "no header line (columns among ball, speed, phi, theta, a, b)");
	return 0;
}

static int load_strike_list(const char *file, size_t max_input, const strike_base *base,
                            strike_list *out) {
	char *data = NULL;
	size_t length = 0;
	char err[512];
	if (pool_read_input(file, max_input, &data, &length, err, sizeof err) != 0) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		return POOL_EXIT_BAD_INPUT;
	}
	size_t i = 0;
	while (i < length && (data[i] == ' ' || data[i] == '\t' || data[i] == '\n' || data[i] == '\r'))
		++i;
	int status = i < length && (data[i] == '[' || data[i] == '{')
	                 ? parse_json_list(file, data, length, base, out)
	                 : parse_csv_list(file, data, length, base, out);
	free(data);
	if (status == 0 && out->count == 0)
		status = list_error(file, "no strikes");
	return status;
}

// ---- the batch ------------------------------------------------------------------------------

typedef struct batch_slot {
	char *text;    ///< the row (malloc'd), NULL when formatting ran out of memory
	bool done;     ///< the row is ready
	bool internal; ///< the shot failed inside the library (exit status 1)
} batch_slot;

typedef struct batch {
	const batch_options *o;
	const pool_scenario *layout;
	const strike_base *base;
	const strike_list *list;
	batch_axis axes[P_COUNT];
	int naxes;
	uint64_t seed_state; ///< mixed from --seed
	bool noisy;          ///< --noise given (and not "none")
	pool_noise noise;    ///< its standard deviations
	long n;              ///< shots
	char **pos_text;     ///< per layout ball, its position as "x,y,z" (NULL: none cached)

	pthread_mutex_t lock;
	pthread_cond_t space; ///< a slot of the window was freed
	pthread_cond_t ready; ///< the row next to be written is done
	long next_claim;
	long next_write;
	long completed; ///< shots done (written or not)
	long wake_at;   ///< signal the writer when completed reaches this
	bool stop;
	batch_slot slots[BATCH_WINDOW];
} batch;

static void nominal_strike(const batch *b, long i, batch_strike *s) {
	if (b->o->mode == MODE_LIST) {
		*s = b->list->items[i];
		return;
	}
	*s = b->base->strike;
	if (b->o->mode == MODE_GRID) {
		long rest = i;
		for (int k = b->naxes - 1; k >= 0; --k) {
			const batch_axis *a = &b->axes[k];
			s->v[a->param] = grid_value(a, rest % a->count);
			rest /= a->count;
		}
		return;
	}
	// Random: a generator of its own per shot, so shot i depends only on the seed, i, the ranges.
	uint64_t state = b->seed_state ^ ((uint64_t)i * 0xD1B54A32D192ED03ull);
	(void)splitmix64(&state);
	for (int k = 0; k < b->naxes; ++k) {
		const batch_axis *a = &b->axes[k];
		double u = (double)(splitmix64(&state) >> 11) * (1.0 / 9007199254740992.0);
		double x = a->lo + (a->hi - a->lo) * u;
		s->v[a->param] = x < a->hi || a->lo == a->hi ? x : a->lo; // [lo, hi) despite rounding
	}
}

/// Strike i as simulated: the nominal one, with --noise's deviates of sample i under --seed.
static void shot_strike(const batch *b, long i, batch_strike *s) {
	nominal_strike(b, i, s);
	if (!b->noisy)
		return;
	const pool_batch_strike nominal = {s->ball, s->v[P_SPEED], s->v[P_PHI], s->v[P_THETA], s->v[P_A], s->v[P_B]};
	const pool_batch_strike noisy = pool_batch_noisy(&nominal, &b->noise, (uint64_t)b->o->seed, (uint64_t)i);
	s->v[P_SPEED] = noisy.speed;
	s->v[P_PHI] = noisy.phi;
	s->v[P_THETA] = noisy.theta;
	s->v[P_A] = noisy.a;
	s->v[P_B] = noisy.b;
}

/// Per-thread state: a simulation reused for every shot and scratch buffers.
typedef struct worker {
	batch *b;
	pool_sim *sim;
	pool_ball_state *final;
	pool_batch_shot shot;
	sbuf row;
} worker;

/// A JSON string (escaped as json_writer.c does).
static void sb_json_string(sbuf *b, const char *text) {
	sb_put(b, "\"", 1);
	for (const unsigned char *p = (const unsigned char *)text; *p; ++p) {
		char escaped[8];
		switch (*p) {
		case '"': sb_str(b, "\\\""); break;
		case '\\': sb_str(b, "\\\\"); break;
		case '\n': sb_str(b, "\\n"); break;
		case '\t': sb_str(b, "\\t"); break;
		case '\r': sb_str(b, "\\r"); break;
		default:
			if (*p < 0x20) {
				snprintf(escaped, sizeof escaped, "\\u%04x", *p);
				sb_str(b, escaped);
			} else {
				sb_put(b, (const char *)p, 1);
			}
		}
	}
	sb_put(b, "\"", 1);
}

/// The strike's fields: CSV "shot,ball,speed,phi,theta,a,b" or JSON "shot":...,..."b":...
static void put_strike(sbuf *r, bool json, long i, const batch_strike *s) {
	if (json)
		sb_str(r, "\"shot\":");
	sb_int(r, i);
	sb_str(r, json ? ",\"ball\":" : ",");
	sb_int(r, s->ball);
	for (int p = 0; p < P_COUNT; ++p) {
		sb_put(r, ",", 1);
		if (json) {
			sb_put(r, "\"", 1);
			sb_str(r, param_names[p]);
			sb_str(r, "\":");
		}
		sb_num(r, s->v[p]);
	}
}

/// "x,y,z" of a ball's final position; a ball that did not move reuses its layout text (most
/// balls of a shot on a full table), formatted once at the start.
static void put_pos(sbuf *r, const batch *b, int k, const pool_vec3 *pos) {
	if (b->pos_text && memcmp(pos, &b->layout->balls[k].pos, sizeof *pos) == 0) {
		sb_str(r, b->pos_text[k]);
		return;
	}
	sb_num(r, pos->x);
	sb_put(r, ",", 1);
	sb_num(r, pos->y);
	sb_put(r, ",", 1);
	sb_num(r, pos->z);
}

/// The game's cells of a row (CSV: ,legal,fouls,outcome,reason,points; JSON lines: the same keys).
static void put_game(sbuf *r, bool json, const pool_batch_shot *shot) {
	const pool_game_result g = shot->game;
	char fouls[128] = "";
	if (!shot->judged) { // the parser checked the layout's balls: not expected
		sb_str(r, json ? ",\"legal\":null,\"fouls\":null,\"outcome\":null,\"reason\":null,\"points\":null"
		               : ",,,,,");
		return;
	}
	sb_str(r, json ? ",\"legal\":" : ",");
	sb_str(r, g.legal ? "true" : "false");
	if (json) {
		sb_str(r, ",\"fouls\":[");
		for (int k = 0, first = 1; k < POOL_GAME_FOUL_KINDS; ++k)
			if (g.fouls & (1u << k)) {
				sb_str(r, first ? "\"" : ",\"");
				sb_str(r, pool_game_foul_name(1u << k));
				sb_str(r, "\"");
				first = 0;
			}
		sb_str(r, "],\"outcome\":\"");
	} else {
		pool_game_foul_list(g.fouls, " ", fouls, sizeof fouls);
		sb_str(r, ",");
		sb_str(r, fouls);
		sb_str(r, ",");
	}
	sb_str(r, pool_game_outcome_name(g.outcome));
	sb_str(r, json ? "\",\"reason\":\"" : ",");
	sb_str(r, pool_game_reason_name(g.reason));
	sb_str(r, json ? "\",\"points\":" : ",");
	sb_int(r, g.points);
}

/// Simulates shot i and returns its row (malloc'd; NULL when out of memory).
static char *run_shot(worker *w, long i, bool *internal) {
	const batch *b = w->b;
	const pool_scenario *layout = b->layout;
	batch_strike s;
	shot_strike(b, i, &s);
	const pool_batch_strike strike = {s.ball, s.v[P_SPEED], s.v[P_PHI], s.v[P_THETA], s.v[P_A], s.v[P_B]};
	pool_batch_shot *shot = &w->shot;
	(void)pool_batch_run(layout, &strike, 1, &w->sim, shot, w->final);
	*internal = shot->failed;
	const char *error = shot->message;

	int n = layout->ball_count;
	const char *stop = error[0] ? "error" : pool_stop_reason_name(shot->stop_reason);
	bool json = b->o->format == FORMAT_JSONL;
	sbuf *r = &w->row;
	r->length = 0;
	r->failed = false;
	if (json)
		sb_put(r, "{", 1);
	put_strike(r, json, i, &s);
	sb_str(r, json ? ",\"stop_reason\":\"" : ",");
	sb_str(r, stop);
	if (json)
		sb_put(r, "\"", 1);
	if (error[0]) {
		if (json) {
			sb_str(r, ",\"error\":");
			sb_json_string(r, error);
		} else {
			sb_str(r, ",,,,,,");
			sb_csv_quoted(r, error);
			if (layout->has_game)
				sb_str(r, ",,,,,");
			for (int k = 0; k < n; ++k)
				sb_str(r, ",,,,");
		}
	} else {
		sb_str(r, json ? ",\"events\":" : ",");
		sb_int(r, shot->events);
		sb_str(r, json ? ",\"end_time\":" : ",");
		sb_num(r, shot->end_time);
		sb_str(r, json ? ",\"first_hit\":" : ",");
		if (shot->hit)
			sb_int(r, shot->first_hit);
		else if (json)
			sb_str(r, "null");
		for (int pass = 0; pass < 2; ++pass) {
			sb_str(r, json ? (pass == 0 ? ",\"pocketed\":[" : ",\"off_table\":[") : ",");
			pool_motion m = pass == 0 ? POOL_MOTION_POCKETED : POOL_MOTION_OFF_TABLE;
			bool first = true;
			for (int k = 0; k < n; ++k)
				if (w->final[k].motion == m) {
					if (!first)
						sb_put(r, json ? "," : " ", 1);
					sb_int(r, w->final[k].id);
					first = false;
				}
			if (json)
				sb_put(r, "]", 1);
		}
		if (!json)
			sb_str(r, ","); // the empty error column
		if (layout->has_game)
			put_game(r, json, shot);
		sb_str(r, json ? ",\"final\":[" : "");
		for (int k = 0; k < n; ++k) {
			if (json) {
				sb_str(r, k ? ",{\"id\":" : "{\"id\":");
				sb_int(r, w->final[k].id);
				sb_str(r, ",\"pos\":[");
				put_pos(r, b, k, &w->final[k].pos);
				sb_str(r, "],\"state\":\"");
				sb_str(r, pool_motion_name(w->final[k].motion));
				sb_str(r, "\"}");
			} else {
				sb_put(r, ",", 1);
				put_pos(r, b, k, &w->final[k].pos);
				sb_put(r, ",", 1);
				sb_str(r, pool_motion_name(w->final[k].motion));
			}
		}
		if (json)
			sb_put(r, "]", 1);
	}
	sb_str(r, json ? "}\n" : "\n");
	if (r->failed)
		return NULL;
	char *text = malloc(r->length + 1);
	if (text)
		memcpy(text, r->data, r->length + 1);
	return text;
}

static void *worker_main(void *arg) {
	worker *w = arg;
	batch *b = w->b;
	for (;;) {
		pthread_mutex_lock(&b->lock);
		while (!b->stop && b->next_claim < b->n && b->next_claim >= b->next_write + BATCH_WINDOW)
			pthread_cond_wait(&b->space, &b->lock);
		if (b->stop || b->next_claim >= b->n) {
			pthread_mutex_unlock(&b->lock);
			break;
		}
		long i = b->next_claim++;
		pthread_mutex_unlock(&b->lock);

		bool internal = false;
		char *text = run_shot(w, i, &internal);

		pthread_mutex_lock(&b->lock);
		batch_slot *slot = &b->slots[i % BATCH_WINDOW];
		slot->text = text;
		slot->internal = internal;
		slot->done = true;
		// The writer sleeps until enough rows are done (not once per row: a context switch per
		// short shot would cost more than the shot).
		if (++b->completed >= b->wake_at)
			pthread_cond_signal(&b->ready);
		pthread_mutex_unlock(&b->lock);
	}
	return NULL;
}

static double now_s(void) {
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void csv_header(sbuf *out, const pool_scenario *layout) {
	sb_str(out, "shot,ball,speed,phi,theta,a,b,stop_reason,events,end_time,first_hit,pocketed,"
	            "off_table,error");
	if (layout->has_game)
		sb_str(out, ",legal,fouls,outcome,reason,points");
	static const char *const suffix[] = {"x", "y", "z", "state"};
	for (int k = 0; k < layout->ball_count; ++k)
		for (int c = 0; c < 4; ++c) {
			char name[48];
			snprintf(name, sizeof name, ",ball_%d_%s", (int)layout->balls[k].id, suffix[c]);
			sb_str(out, name);
		}
	sb_put(out, "\n", 1);
}

/// Runs every shot and writes the rows in order. Returns the exit status.
static int run_batch(batch *b, long threads) {
	const batch_options *o = b->o;
	bool to_file = o->output_path != NULL;
	sbuf out = {0};
	if (o->format == FORMAT_CSV)
		csv_header(&out, b->layout);
	if (!to_file && out.length) {
		fputs(out.data, stdout);
		out.length = 0;
	}

	pthread_mutex_init(&b->lock, NULL);
	pthread_cond_init(&b->space, NULL);
	pthread_cond_init(&b->ready, NULL);
	worker *workers = calloc((size_t)threads, sizeof *workers);
	pthread_t *ids = calloc((size_t)threads, sizeof *ids);
	int status = 0;
	long started = 0;
	if (!workers || !ids) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		status = POOL_EXIT_INTERNAL;
	}
	for (long t = 0; t < threads && status == 0; ++t) {
		workers[t].b = b;
		workers[t].final = calloc((size_t)b->layout->ball_count + 1, sizeof *workers[t].final);
		if (!workers[t].final) {
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
			status = POOL_EXIT_INTERNAL;
			break;
		}
		int e = pthread_create(&ids[t], NULL, worker_main, &workers[t]);
		if (e != 0) {
			fprintf(stderr, "%s: cannot start thread %ld: %s\n", PROGRAM, t + 1, strerror(e));
			status = POOL_EXIT_INTERNAL;
			free(workers[t].final);
			workers[t].final = NULL;
			break;
		}
		started++;
	}

	bool progress = !o->no_progress && isatty(STDERR_FILENO);
	bool progress_shown = false;
	double start = now_s(), last_progress = 0.0;
	long internal_failures = 0;
	pthread_mutex_lock(&b->lock);
	if (status != 0)
		b->stop = true;
	while (status == 0 && b->next_write < b->n) {
		batch_slot *slot = &b->slots[b->next_write % BATCH_WINDOW];
		while (!slot->done) {
			// Wake up when BATCH_WAKE_ROWS more rows from here are done, or at the next completion
			// when that many are done already (the row to write is a slow one), or at the end.
			long target = b->next_write + BATCH_WAKE_ROWS;
			if (target <= b->completed)
				target = b->completed + 1;
			b->wake_at = target < b->n ? target : b->n;
			if (!progress) {
				pthread_cond_wait(&b->ready, &b->lock);
				continue;
			}
			struct timespec until;
			clock_gettime(CLOCK_REALTIME, &until);
			until.tv_nsec += 250000000L;
			if (until.tv_nsec >= 1000000000L)
				until.tv_sec += 1, until.tv_nsec -= 1000000000L;
			pthread_cond_timedwait(&b->ready, &b->lock, &until);
			double t = now_s() - start;
			if (t > 1.0 && t - last_progress >= 0.25) {
				fprintf(stderr, "\r%s: %ld of %ld shots (%.0f%%), %.1f s", PROGRAM, b->next_write, b->n,
				        100.0 * (double)b->next_write / (double)b->n, t);
				progress_shown = true;
				last_progress = t;
			}
		}
		char *text = slot->text;
		bool internal = slot->internal;
		slot->text = NULL;
		slot->done = false;
		b->next_write++;
		pthread_cond_broadcast(&b->space);
		pthread_mutex_unlock(&b->lock);
		if (!text) {
			fprintf(stderr, "%s: out of memory\n", PROGRAM);
			status = POOL_EXIT_INTERNAL;
		} else {
			internal_failures += internal;
			if (to_file)
				sb_str(&out, text);
			else
				fputs(text, stdout);
			free(text);
			if (out.failed) {
				fprintf(stderr, "%s: out of memory\n", PROGRAM);
				status = POOL_EXIT_INTERNAL;
			}
		}
		pthread_mutex_lock(&b->lock);
		if (status != 0) {
			b->stop = true;
			pthread_cond_broadcast(&b->space);
		}
	}
	pthread_mutex_unlock(&b->lock);
	for (long t = 0; t < started; ++t)
		pthread_join(ids[t], NULL);
	if (progress_shown)
		fprintf(stderr, "\r%s: %ld of %ld shots (100%%), %.1f s\n", PROGRAM, b->n, b->n, now_s() - start);
	for (long t = 0; t < threads && workers; ++t) {
		pool_sim_destroy(workers[t].sim);
		free(workers[t].final);
		free(workers[t].row.data);
	}
	for (int k = 0; k < BATCH_WINDOW; ++k)
		free(b->slots[k].text);
	free(workers);
	free(ids);
	pthread_cond_destroy(&b->ready);
	pthread_cond_destroy(&b->space);
	pthread_mutex_destroy(&b->lock);

	if (status == 0) {
		if (to_file) {
			status = pool_cli_write_output(PROGRAM, o->output_path, out.data ? out.data : "");
		} else if (fflush(stdout) != 0 || ferror(stdout)) {
			fprintf(stderr, "%s: standard output: %s\n", PROGRAM, strerror(errno));
			status = POOL_EXIT_INTERNAL;
		}
	}
	free(out.data);
	if (status == 0 && internal_failures > 0) {
		fprintf(stderr, "%s: %ld shot(s) failed inside the library (their rows say why)\n", PROGRAM,
		        internal_failures);
		status = POOL_EXIT_INTERNAL;
	}
	return status;
}

// ---- command line ---------------------------------------------------------------------------

static int set_mode(batch_options *o, batch_mode mode, const char *option) {
	if (o->mode != MODE_NONE && o->mode != mode)
		return pool_cli_usage_error(PROGRAM, "%s: give one of --strikes, --grid and --random", option);
	if (o->mode == mode)
		return pool_cli_usage_error(PROGRAM, "%s: given twice", option);
	o->mode = mode;
	return 0;
}

// One option of pool-batch (pool_cli_walk); *have_seed in the options' context.
typedef struct batch_parse {
	batch_options *o;
	bool have_seed;
} batch_parse;

static int batch_option(void *context, const char *a, const char *v) {
	batch_parse *bp = context;
	batch_options *o = bp->o;
	if (strcmp(a, "--no-progress") == 0) {
		o->no_progress = true;
		return 0;
	}
	if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
		o->output_path = v;
	} else if (strcmp(a, "--strikes") == 0) {
		o->strikes_path = v;
		return set_mode(o, MODE_LIST, a);
	} else if (strcmp(a, "--grid") == 0) {
		o->grid_spec = v;
		return set_mode(o, MODE_GRID, a);
	} else if (strcmp(a, "--random") == 0) {
		const int status = set_mode(o, MODE_RANDOM, a);
		if (status == 0 && (!pool_cli_parse_count(v, &o->random_count) || o->random_count < 1 ||
		                    o->random_count > BATCH_MAX_SHOTS))
			return pool_cli_usage_error(PROGRAM, "--random: '%s' is not a number of shots from 1 to %ld",
			                            pool_cli_arg(v), BATCH_MAX_SHOTS);
		return status;
	} else if (strcmp(a, "--ranges") == 0) {
		o->ranges_spec = v;
	} else if (strcmp(a, "--noise") == 0) {
		o->noise_spec = v;
	} else if (strcmp(a, "--seed") == 0) {
		bp->have_seed = true;
		if (!pool_cli_parse_count(v, &o->seed))
			return pool_cli_usage_error(PROGRAM, "--seed: '%s' is not a whole number >= 0", pool_cli_arg(v));
	} else if (strcmp(a, "--ball") == 0) {
		o->have_ball = true;
		if (!parse_int32(v, &o->ball))
			return pool_cli_usage_error(PROGRAM, "--ball: '%s' is not a ball id (a 32-bit integer)", pool_cli_arg(v));
	} else if (strcmp(a, "--threads") == 0) {
		if (!pool_cli_parse_count(v, &o->threads) || o->threads < 1 || o->threads > BATCH_MAX_THREADS)
			return pool_cli_usage_error(PROGRAM, "--threads: '%s' is not a number of threads from 1 to %d",
			                            pool_cli_arg(v), BATCH_MAX_THREADS);
	} else if (strcmp(a, "--format") == 0) {
		if (strcmp(v, "csv") == 0)
			o->format = FORMAT_CSV;
		else if (strcmp(v, "jsonl") == 0)
			o->format = FORMAT_JSONL;
		else
			return pool_cli_usage_error(PROGRAM, "--format: '%s' is not csv or jsonl", pool_cli_arg(v));
	} else if (strcmp(a, "--max-input") == 0) {
		return pool_cli_max_input(PROGRAM, v, &o->max_input);
	} else if (strcmp(a, "--models") == 0) {
		pool_models check = pool_default_models();
		char err[512];
		if (pool_models_parse_spec(&check, v, err, sizeof err))
			return pool_cli_usage_error(PROGRAM, "--models: %s", err);
		o->models = v;
	}
	return 0;
}

static int parse_options(int argc, char **argv, batch_options *o) {
	memset(o, 0, sizeof *o);
	o->max_input = POOL_INPUT_DEFAULT_MAX;
	o->seed = 1;
	static const char *const flags[] = {"--no-progress", NULL};
	static const char *const with_value[] = {"-o",     "--output", "--strikes", "--grid",   "--random",    "--ranges",
	                                         "--seed", "--ball",   "--threads", "--format", "--max-input", "--noise",
	                                         "--models", NULL};
	batch_parse bp = {o, false};
	const int status =
	    pool_cli_walk(PROGRAM, argc, argv, "layout", flags, with_value, batch_option, &bp, &o->layout_path, &o->help);
	if (status)
		return status;
	const bool have_seed = bp.have_seed;
	if (o->help)
		return 0;
	if (!o->layout_path)
		return pool_cli_usage_error(PROGRAM, "%s", "missing LAYOUT.json");
	if (o->mode == MODE_NONE)
		return pool_cli_usage_error(PROGRAM, "%s", "no strikes: give --strikes FILE, --grid SPEC or --random N");
	if (o->mode == MODE_RANDOM && !o->ranges_spec)
		return pool_cli_usage_error(PROGRAM, "%s", "--random needs --ranges (e.g. --ranges speed=0.5:6,phi=0:360)");
	if (o->mode != MODE_RANDOM && o->ranges_spec)
		return pool_cli_usage_error(PROGRAM, "%s", "--ranges goes with --random");
	if (o->mode != MODE_RANDOM && !o->noise_spec && have_seed)
		return pool_cli_usage_error(PROGRAM, "%s", "--seed goes with --random or --noise");
	return 0;
}

int main(int argc, char **argv) {
	batch_options o;
	int status = parse_options(argc, argv, &o);
	if (status)
		return status;
	if (o.help) {
		fputs(usage_text, stdout);
		return 0;
	}
	batch *b = calloc(1, sizeof *b);
	if (!b) {
		fprintf(stderr, "%s: out of memory\n", PROGRAM);
		return POOL_EXIT_INTERNAL;
	}
	b->o = &o;
	if (o.mode == MODE_GRID)
		status = parse_axes("--grid", o.grid_spec, true, b->axes, &b->naxes);
	else if (o.mode == MODE_RANDOM)
		status = parse_axes("--ranges", o.ranges_spec, false, b->axes, &b->naxes);
	if (status) {
		free(b);
		return status;
	}

	pool_scenario layout;
	char err[512];
	status = pool_batch_load_layout(o.layout_path, o.max_input, &layout, err, sizeof err);
	if (status) {
		fprintf(stderr, "%s: %s\n", PROGRAM, err);
		free(b);
		return status;
	}

	if (o.models) // checked with the options: it applies
		pool_models_parse_spec(&layout.def.models, o.models, err, sizeof err);

	strike_base base = {0};
	if (layout.has_strike) {
		base.has_speed = true;
		base.strike.ball = layout.written.ball; // the strike as the file gives it, in degrees
		base.strike.v[P_SPEED] = layout.written.speed;
		base.strike.v[P_PHI] = layout.written.phi;
		base.strike.v[P_THETA] = layout.written.theta;
		base.strike.v[P_A] = layout.written.a;
		base.strike.v[P_B] = layout.written.b;
	} else {
		base.strike.ball = layout.balls[0].id;
	}
	if (o.have_ball) {
		bool found = false;
		for (int k = 0; k < layout.ball_count; ++k)
			found = found || layout.balls[k].id == o.ball;
		if (!found) {
			status = pool_cli_usage_error(PROGRAM, "--ball: no ball of the layout has id %d", (int)o.ball);
			pool_scenario_free(&layout);
			free(b);
			return status;
		}
		base.strike.ball = o.ball;
	}

	strike_list list = {0};
	b->layout = &layout;
	b->base = &base;
	b->list = &list;
	if (o.mode == MODE_LIST) {
		status = load_strike_list(o.strikes_path, o.max_input, &base, &list);
		b->n = list.count;
	} else if (o.mode == MODE_GRID) {
		b->n = 1;
		bool speed = false;
		for (int k = 0; k < b->naxes; ++k) {
			speed = speed || b->axes[k].param == P_SPEED;
			if (b->n > BATCH_MAX_SHOTS / b->axes[k].count) {
				status = pool_cli_usage_error(PROGRAM, "--grid: more than %ld shots", BATCH_MAX_SHOTS);
				break;
			}
			b->n *= b->axes[k].count;
		}
		if (status == 0 && !speed && !base.has_speed)
			status = pool_cli_usage_error(PROGRAM, "--grid: no speed (%s)", no_speed);
	} else {
		b->n = o.random_count;
		uint64_t mix = (uint64_t)o.seed;
		b->seed_state = splitmix64(&mix);
		bool speed = false;
		for (int k = 0; k < b->naxes; ++k)
			speed = speed || b->axes[k].param == P_SPEED;
		if (!speed && !base.has_speed)
			status = pool_cli_usage_error(PROGRAM, "--ranges: no speed (%s)", no_speed);
	}
	if (status == 0 && o.noise_spec) {
		pool_error e;
		if (pool_noise_parse(o.noise_spec, &b->noise, &e) != POOL_OK) {
			char shown[POOL_ESCAPE_SHORT];
			status = pool_cli_usage_error(PROGRAM, "--noise: %s (e.g. fastfiz, or speed=0.075,phi=0.125)",
			                              pool_escape_str(shown, sizeof shown, e.message + strlen("noise: ")));
		}
		const pool_noise *n = &b->noise;
		b->noisy = n->speed > 0.0 || n->phi > 0.0 || n->theta > 0.0 || n->a > 0.0 || n->b > 0.0;
	}
	if (status == 0) {
		long threads = o.threads;
		if (threads == 0) {
			threads = sysconf(_SC_NPROCESSORS_ONLN);
			if (threads < 1)
				threads = 1;
			if (threads > BATCH_MAX_THREADS)
				threads = BATCH_MAX_THREADS;
		}
		if (threads > b->n)
			threads = b->n;
		// Every ball's layout position as text, for the balls a shot leaves where they were.
		b->pos_text = calloc((size_t)layout.ball_count, sizeof *b->pos_text);
		for (int k = 0; b->pos_text && k < layout.ball_count; ++k) {
			sbuf t = {0};
			sb_num(&t, layout.balls[k].pos.x);
			sb_put(&t, ",", 1);
			sb_num(&t, layout.balls[k].pos.y);
			sb_put(&t, ",", 1);
			sb_num(&t, layout.balls[k].pos.z);
			b->pos_text[k] = t.failed ? NULL : t.data;
			if (!b->pos_text[k]) { // out of memory: format every position instead
				for (int j = 0; j < k; ++j)
					free(b->pos_text[j]);
				free(b->pos_text);
				b->pos_text = NULL;
			}
		}
		status = run_batch(b, threads);
		for (int k = 0; b->pos_text && k < layout.ball_count; ++k)
			free(b->pos_text[k]);
		free(b->pos_text);
	}
	free(list.items);
	pool_scenario_free(&layout);
	free(b);
	return status;
}
