// The broadphase: which other balls a ball's contact prediction must look at. Re-predicting a
// ball scans every other ball (the schedule's all-pairs loop), so a thousand-ball table spends
// most of each event rejecting balls metres away. Here each ball's reach over its segment's
// window (its path from the segment's start to its own next event: the only stretch of time the
// pair search ever asks about) is cut into short pieces, each a box in the plane for an interval
// of time, and filed in the cells of a uniform grid over the table. A query walks the cells of
// the querying ball's own pieces over [now, horizon] (its own entries: filed over a window that
// holds that one) and keeps the balls with a piece in one of them at an overlapping time whose
// box meets the querying piece's: a superset of those that can come within 2R of it then.
//
// The schedule then runs its unchanged pair loop over those balls in index order, so every pair
// it predicts gets the same window and the same operands as in the all-pairs loop, and a pair
// left out is one that loop would have rejected: the same events bit for bit (tests hash them).
// The grid costs more than it saves on a small table: it is used from POOL_BROADPHASE_MIN_BALLS
// balls (measured), and whenever memory for it runs out the schedule goes back to all pairs.
//
// The broadphase also keeps, for each ball, the balls whose pending contact is with it (with the
// grid or without), so that after an event the schedule finds the balls to predict again without
// scanning every ball.
#ifndef POOL_BROADPHASE_H
#define POOL_BROADPHASE_H

#include <stdint.h>

#include "pool/base.h"
#include "pool/table.h"
#include "segment.h"

/// Which pair search the schedule uses.
typedef enum pool_broadphase_mode {
	POOL_BROADPHASE_AUTO = 0,  ///< the grid from POOL_BROADPHASE_MIN_BALLS balls, all pairs below
	POOL_BROADPHASE_ALL_PAIRS, ///< every pair (what the grid must reproduce)
	POOL_BROADPHASE_GRID,      ///< the grid whatever the ball count (tests, benchmarks)
} pool_broadphase_mode;

/// Ball count from which POOL_BROADPHASE_AUTO uses the grid. Measured in instructions per shot
/// (pool-bench-scale --models thesis under callgrind): the grid costs 12-15 % more at 16 and 32
/// balls (racked break and gas), 2-4 % more at 48, 7 % less on the gas at 64 (4 % more on the
/// break) and less from 96. A build with POOL_BROADPHASE_VERIFY (CMake option of the same name)
/// uses it from 2 balls and checks every search against all pairs.
#ifdef POOL_BROADPHASE_VERIFY
#define POOL_BROADPHASE_MIN_BALLS 2
#else
#define POOL_BROADPHASE_MIN_BALLS 48
#endif

/// m added to every piece's reach: covers POOL_TOUCH_TOLERANCE (a touching pair counts as a
/// contact up to 1e-9 m apart) and the rounding of positions (1e-14 m on a 40 m table), so no pair
/// the narrow phase could take is left out.
#define POOL_BROADPHASE_MARGIN 1e-6

/// At most this many pieces per segment (a longer path gets longer pieces, so bigger boxes).
#define POOL_BROADPHASE_MAX_PIECES 64

/// A piece of a ball's reach filed in one cell (consecutive pieces in the same cell: one entry).
typedef struct pool_broadphase_entry {
	int body;          ///< the ball's index
	int cell;          ///< the cell it is filed in
	int next, prev;    ///< neighbours in the cell's list (-1: none)
	int next_own;      ///< the ball's next entry (-1: none); also the free list's link
	int moving;        ///< the ball translates in this segment
	double from, to;   ///< s, absolute: the piece's time interval
	double box[4];     ///< m, x_lo, x_hi, y_lo, y_hi: where the centre stays then, widened by `radius`
} pool_broadphase_entry;

/// The grid, the entries, and the reverse partner lists.
typedef struct pool_broadphase {
	pool_broadphase_mode mode; ///< requested (pool_broadphase_set_mode)
	int on;                    ///< the grid is in use for this shot
	double radius;             ///< m, a ball's radius plus POOL_BROADPHASE_MARGIN
	double cell;               ///< m, side of a cell; also the longest piece
	double inv_cell;           ///< 1 / cell
	double x0, y0;             ///< m, corner of cell 0 (a cell's margin around the table)
	int nx, ny;                ///< cells along x and y
	double last_x, last_y;     ///< nx - 1 and ny - 1
	int *head;                 ///< first entry of each cell (-1: empty), nx * ny
	int cap_cells;
	pool_broadphase_entry *entries;
	int cap_entries, used_entries; ///< entries allocated, and handed out at least once
	int free_entry;                ///< first free entry (-1: none)
	int *own;                  ///< first entry of each ball (-1: none)
	double *filed;             ///< s, the window [from, to] each ball's entries cover, two per ball
	uint64_t *near;            ///< a query's marks, one bit per ball (all clear between queries)
	int *found;                ///< the balls a query found, in index order
	int watching;              ///< the partner lists are kept for this shot
	int *watch_first, *watch_next, *watch_prev; ///< balls whose partner is a ball (-1 ends)
	int cap_balls;
	int n;                     ///< balls of the shot
} pool_broadphase;

/// Sets the pair search of the next shots (from the next pool_broadphase_begin).
void pool_broadphase_set_mode(pool_broadphase *bp, pool_broadphase_mode mode);

/// Starts a shot of n balls of the given radius on `table`: turns the partner lists on (empty)
/// when memory allows, and the grid (empty) when the mode and ball count also ask for it.
/// Returns whether the grid is on.
int pool_broadphase_begin(pool_broadphase *bp, const pool_allocator *a, const pool_table_def *table, double radius,
                          int n);

/// Ball i's new segment, reaching over [from, to] (absolute times; `active` 0: out of play,
/// filed nowhere): replaces its entries. Out of memory turns the grid off for the shot.
void pool_broadphase_place(pool_broadphase *bp, const pool_allocator *a, int i, const pool_segment *seg, int active,
                           double from, double to);

/// Lists in bp->found, in index order, every ball other than i with a piece near ball i's path
/// over [now, horizon] (moving balls only when i does not translate) and returns their count (the
/// list holds until the next query). When ball i's entries cover the
/// window (its segment was placed over [from, horizon] with from <= now: every search of the
/// schedule), its own entries are the pieces looked from, without cutting its path again.
int pool_broadphase_query(pool_broadphase *bp, int i, const pool_segment *seg, double now, double horizon);

/// Ball x's pending contact is now with `partner` (-1: none) instead of `old` (kept when watching).
void pool_broadphase_repartner(pool_broadphase *bp, int x, int old, int partner);

/// The first ball whose pending contact is with ball j (-1: none), and the one after x.
static inline int pool_broadphase_watcher(const pool_broadphase *bp, int j) { return bp->watch_first[j]; }
static inline int pool_broadphase_next_watcher(const pool_broadphase *bp, int x) { return bp->watch_next[x]; }

/// Releases the broadphase's memory.
void pool_broadphase_free(pool_broadphase *bp, const pool_allocator *a);

#endif
