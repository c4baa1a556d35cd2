// Simple CSV lines (csv_lines.h).
#include "csv_lines.h"

#include <string.h>

#include "cli.h"

pool_csv_reader pool_csv_start(const char *text, size_t length) {
	return (pool_csv_reader){.next = text, .end = text + length, .line = 0};
}

/// Cuts the spaces and tabs around a cell.
static void trim(pool_csv_cell *c) {
	while (c->begin < c->end && (*c->begin == ' ' || *c->begin == '\t'))
		++c->begin;
	while (c->end > c->begin && (c->end[-1] == ' ' || c->end[-1] == '\t'))
		--c->end;
}

int pool_csv_next(pool_csv_reader *r, pool_csv_cell *cells, int max) {
	while (r->next < r->end) {
		const char *nl = memchr(r->next, '\n', (size_t)(r->end - r->next));
		pool_csv_cell line = {r->next, nl ? nl : r->end};
		r->next = nl ? nl + 1 : r->end;
		++r->line;
		if (line.end > line.begin && line.end[-1] == '\r')
			--line.end;
		trim(&line);
		if (line.begin == line.end || *line.begin == '#')
			continue;
		int n = 0;
		for (const char *c = line.begin;;) {
			const char *comma = memchr(c, ',', (size_t)(line.end - c));
			if (n == max)
				return max + 1;
			cells[n] = (pool_csv_cell){c, comma ? comma : line.end};
			trim(&cells[n++]);
			if (!comma)
				return n;
			c = comma + 1;
		}
	}
	return 0;
}

bool pool_csv_is(const pool_csv_cell *cell, const char *name) {
	size_t n = (size_t)(cell->end - cell->begin);
	return strlen(name) == n && memcmp(cell->begin, name, n) == 0;
}

bool pool_csv_double(const pool_csv_cell *cell, double *out) {
	char text[64];
	size_t n = (size_t)(cell->end - cell->begin);
	if (n == 0 || n >= sizeof text || memchr(cell->begin, '\0', n))
		return false;
	memcpy(text, cell->begin, n);
	text[n] = '\0';
	return pool_cli_parse_double(text, out);
}
