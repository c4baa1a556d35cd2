// SVG pictures of the table seen from above, written as text so the C commands need no plotting
// library: the rails, the cloth and the pocket mouths as pool-plot draws them, in a frame whose
// y axis points up like the table's. Shared by pool-sensitivity, pool-fit and pool-aim.
#ifndef POOL_TOOLS_SVG_TABLE_H
#define POOL_TOOLS_SVG_TABLE_H

#include <stdbool.h>

#include "pool/pool.h"
#include "text_buffer.h"

#ifdef __cplusplus
extern "C" {
#endif

/// px per metre of the pictures.
#define POOL_SVG_SCALE 400.0
/// m, the rails' width as drawn (pool-plot's RAIL_WIDTH); the physics uses the noses only.
#define POOL_SVG_RAIL 0.10
/// m of white around the rails.
#define POOL_SVG_MARGIN 0.02

/// A picture being written: the text, and where the current table's top edge is.
typedef struct pool_svg {
	pool_text_buffer b;
	double width;    ///< m, the table's width, to flip y
	double top;      ///< px, where the current table's drawing starts (tables may be stacked)
} pool_svg;

/// Appends formatted text (lines up to 1 KiB).
void pool_svg_put(pool_svg *g, const char *format, ...) __attribute__((format(printf, 2, 3)));

/// Appends text with XML's five special characters escaped.
void pool_svg_put_escaped(pool_svg *g, const char *text);

/// px of a table x (m).
double pool_svg_x(double x);
/// px of a table y (m), y pointing up on the current table.
double pool_svg_y(const pool_svg *g, double y);

/// px, the width and height of a table's drawing with its rails and margin.
double pool_svg_table_width(const pool_table_def *table);
double pool_svg_table_height(const pool_table_def *table);

/// Opens the document (white background) of width x height px.
void pool_svg_begin(pool_svg *g, double width, double height);

/// Draws a table (rails, cloth, pockets) with its top edge at top px, and makes it the current one.
void pool_svg_table(pool_svg *g, const pool_table_def *table, double top);

/// The ball's conventional colour as pool-plot draws it (0 white, 1-7 solids, 8 black, 9-15 the
/// stripes of 1-7, others from a palette).
const char *pool_svg_ball_colour(int id);

/// Closes the document: its malloc'd text, or NULL when an allocation failed.
char *pool_svg_end(pool_svg *g);

#ifdef __cplusplus
}
#endif

#endif
