// Reading simple CSV text line by line: cells split at commas and trimmed of spaces and tabs, no
// quoting (the commands' CSV inputs hold numbers and names), blank lines and '#' comments
// skipped, CRLF accepted. The caller checks the cells and names the line in its messages.
#ifndef POOL_TOOLS_CSV_LINES_H
#define POOL_TOOLS_CSV_LINES_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/// One cell: [begin, end) of the text, trimmed.
typedef struct pool_csv_cell {
	const char *begin;
	const char *end;
} pool_csv_cell;

/// Where the reader is in the text.
typedef struct pool_csv_reader {
	const char *next; ///< start of the next line
	const char *end;  ///< end of the text
	long line;        ///< number (from 1) of the line last returned
} pool_csv_reader;

/// A reader at the start of length bytes of text.
pool_csv_reader pool_csv_start(const char *text, size_t length);

/// Splits the next line that is neither blank nor a comment into at most max cells. Returns the
/// number of cells (max + 1 when the line has more than max), or 0 at the end of the text.
int pool_csv_next(pool_csv_reader *r, pool_csv_cell *cells, int max);

/// Whether the cell's text is exactly name.
bool pool_csv_is(const pool_csv_cell *cell, const char *name);

/// Reads the cell as a finite double (false for an empty cell, trailing characters, inf, nan).
bool pool_csv_double(const pool_csv_cell *cell, double *out);

#ifdef __cplusplus
}
#endif

#endif
