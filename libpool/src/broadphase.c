// The broadphase (broadphase.h).
#include "broadphase.h"

#include <math.h>
#include <string.h>

#include "memory.h"

/// Side of a cell in ball radii: a piece of a path is at most one cell long, so its box (with a
/// radius around it) covers 2 x 2 cells mostly, 3 x 3 at most. On the gas of pool-bench-scale
/// (thesis) 12 and 16 took the fewest instructions of 8, 12, 16 and 24, within 0.5 % of each other
/// at 256 and 1,024 balls (8: 5 % more, 24: 1-2 % more).
#define CELL_RADII 12.0

/// At most this many cells: a table far larger than the balls gets larger cells.
#define MAX_CELLS (1 << 20)

/// A query sorts at most this many candidates itself; more it takes in order from their marks.
#define SORT_MAX 16

/// Entries reserved per ball when a shot starts (more grow as needed): a resting ball takes 1 to 4
/// cells, a moving one its path's. The gas of pool-bench-scale (a quarter of the balls rolling)
/// takes at most 3.4 to 4.0 a ball over its 2 s (64 to 4,096 balls).
#define ENTRIES_PER_BALL 6

// A piece of a path: an interval of time and the box (in the plane) the centre stays in, widened
// by bp->radius (x_lo, x_hi, y_lo, y_hi): two balls whose widened boxes are apart at every common
// instant cannot come within 2 (R + margin) of each other.
typedef struct piece {
	double from, to; // s, absolute
	double box[4];   // m
} piece;

// One coordinate x0 + v t + a t^2 / 2 of a path at the ends of the pieces (times from the
// segment's start), and its vertex, where its speed changes sign.
typedef struct axis {
	double x0, v, a;
	double vertex_t, vertex_x; // the vertex (vertex_t NaN: none on the path)
} axis;

static inline axis axis_of(double x0, double v, double a) {
	axis c = {x0, v, a, NAN, 0.0};
	if (a != 0.0) {
		c.vertex_t = -v / a;
		c.vertex_x = x0 + c.vertex_t * v + 0.5 * c.vertex_t * c.vertex_t * a;
	}
	return c;
}

static inline double axis_at(const axis *c, double t) { return c->x0 + t * c->v + 0.5 * t * t * c->a; }

// The range of the coordinate over a piece whose ends (at t_lo, t_hi) are e0 and e1: the ends
// and, when it lies inside, the vertex (as pool_segment_range_1d, which takes the vertex only
// where the speed visibly changes sign: this range holds that one).
static inline void axis_range(const axis *c, double t_lo, double t_hi, double e0, double e1, double *lo, double *hi) {
	*lo = e0 < e1 ? e0 : e1;
	*hi = e0 < e1 ? e1 : e0;
	if (c->vertex_t > t_lo && c->vertex_t < t_hi) {
		*lo = c->vertex_x < *lo ? c->vertex_x : *lo;
		*hi = c->vertex_x > *hi ? c->vertex_x : *hi;
	}
}

// Cuts the segment's path over [from, to] (absolute) into pieces at most a cell long (at most
// POOL_BROADPHASE_MAX_PIECES); returns their count. A ball that does not translate is one piece.
// Each end between two pieces is evaluated once, for both.
static int cut(const pool_broadphase *bp, const pool_segment *seg, double from, double to, piece *out) {
	const pool_ball_state *s = &seg->start;
	const double r = bp->radius;
	if (!(to >= from))
		to = from;
	if (!seg->model->translating) {
		out[0] = (piece){from, to, {s->pos.x - r, s->pos.x + r, s->pos.y - r, s->pos.y + r}};
		return 1;
	}
	const double t_lo = from - seg->t0, span = to - from;
	// Distance travelled over the window at most |v(t_lo)| span + |a| span^2 / 2 (planar; the
	// 1-norms bound the lengths: a piece may come out shorter than a cell, never longer).
	const double vx = s->vel.x + t_lo * seg->acc.x, vy = s->vel.y + t_lo * seg->acc.y;
	const double reach = (fabs(vx) + fabs(vy) + 0.5 * span * (fabs(seg->acc.x) + fabs(seg->acc.y))) * span;
	const double cells = reach * bp->inv_cell;
	const int k = cells < POOL_BROADPHASE_MAX_PIECES ? 1 + (int)cells : POOL_BROADPHASE_MAX_PIECES;
	const axis ax = axis_of(s->pos.x, s->vel.x, seg->acc.x), ay = axis_of(s->pos.y, s->vel.y, seg->acc.y);
	double t0 = t_lo, x0 = axis_at(&ax, t0), y0 = axis_at(&ay, t0);
	for (int p = 0; p < k; ++p) {
		piece *q = &out[p];
		q->from = p == 0 ? from : out[p - 1].to;
		q->to = p == k - 1 ? to : from + span * (p + 1) / k;
		const double t1 = q->to - seg->t0, x1 = axis_at(&ax, t1), y1 = axis_at(&ay, t1);
		axis_range(&ax, t0, t1, x0, x1, &q->box[0], &q->box[1]);
		axis_range(&ay, t0, t1, y0, y1, &q->box[2], &q->box[3]);
		q->box[0] -= r;
		q->box[1] += r;
		q->box[2] -= r;
		q->box[3] += r;
		t0 = t1;
		x0 = x1;
		y0 = y1;
	}
	return k;
}

// The cell of a coordinate, clamped to the grid (a ball beyond it is filed, and looked for, in the
// border cells). It never decreases as x grows, so a box's cells hold every point of the box's.
// last: count - 1. Clamped as a double first (no branch; a NaN goes to cell 0).
static inline int cell_of(double x, double x0, double inv_cell, double last) {
	double c = (x - x0) * inv_cell;
	c = c > 0.0 ? c : 0.0;
	c = c < last ? c : last;
	return (int)c;
}

// The cells a widened box reaches.
static inline void cells(const pool_broadphase *bp, const double box[4], int *cx0, int *cx1, int *cy0, int *cy1) {
	*cx0 = cell_of(box[0], bp->x0, bp->inv_cell, bp->last_x);
	*cx1 = cell_of(box[1], bp->x0, bp->inv_cell, bp->last_x);
	*cy0 = cell_of(box[2], bp->y0, bp->inv_cell, bp->last_y);
	*cy1 = cell_of(box[3], bp->y0, bp->inv_cell, bp->last_y);
}

static inline int boxes_apart(const double a[4], const double b[4]) {
	return a[0] > b[1] || b[0] > a[1] || a[2] > b[3] || b[2] > a[3];
}

// Grows the per-ball arrays to n balls; 0 or POOL_ERR_OUT_OF_MEMORY (nothing changed).
static pool_result reserve_balls(pool_broadphase *bp, const pool_allocator *a, int n) {
	if (n <= bp->cap_balls)
		return POOL_OK;
	const int cap = pool_mem_next_cap(bp->cap_balls, n), words = (cap + 63) / 64;
	void **arrays[] = {(void **)&bp->own,        (void **)&bp->watch_first, (void **)&bp->watch_next,
	                   (void **)&bp->watch_prev, (void **)&bp->filed,       (void **)&bp->found};
	const size_t elems[] = {sizeof(int), sizeof(int), sizeof(int), sizeof(int), 2 * sizeof(double), sizeof(int)};
	uint64_t *near = pool_mem_alloc(a, sizeof(uint64_t) * (size_t)words);
	if (!near || pool_mem_grow(a, arrays, elems, 6, 0, cap)) {
		pool_mem_free(a, near);
		return POOL_ERR_OUT_OF_MEMORY;
	}
	pool_mem_free(a, bp->near);
	bp->near = near;
	memset(near, 0, sizeof(uint64_t) * (size_t)words);
	bp->cap_balls = cap;
	return POOL_OK;
}

// Room for `need` entries in all; POOL_ERR_OUT_OF_MEMORY when the entries cannot grow.
static pool_result reserve_entries(pool_broadphase *bp, const pool_allocator *a, int need) {
	if (need <= bp->cap_entries)
		return POOL_OK;
	void **arrays[] = {(void **)&bp->entries};
	const size_t elems[] = {sizeof(pool_broadphase_entry)};
	const int cap = pool_mem_next_cap(bp->cap_entries, need);
	if (pool_mem_grow(a, arrays, elems, 1, bp->used_entries, cap))
		return POOL_ERR_OUT_OF_MEMORY;
	bp->cap_entries = cap;
	return POOL_OK;
}

// One more free entry; POOL_ERR_OUT_OF_MEMORY when the entries cannot grow.
static inline pool_result reserve_entry(pool_broadphase *bp, const pool_allocator *a) {
	if (bp->free_entry >= 0 || bp->used_entries < bp->cap_entries)
		return POOL_OK;
	return reserve_entries(bp, a, bp->cap_entries + 1);
}

static int take_entry(pool_broadphase *bp) {
	if (bp->free_entry >= 0) {
		const int e = bp->free_entry;
		bp->free_entry = bp->entries[e].next_own;
		return e;
	}
	return bp->used_entries++;
}

// Takes ball i's entries out of their cells, onto the free list.
static void remove_ball(pool_broadphase *bp, int i) {
	for (int e = bp->own[i]; e >= 0;) {
		pool_broadphase_entry *x = &bp->entries[e];
		const int next = x->next_own;
		if (x->prev >= 0)
			bp->entries[x->prev].next = x->next;
		else
			bp->head[x->cell] = x->next;
		if (x->next >= 0)
			bp->entries[x->next].prev = x->prev;
		x->next_own = bp->free_entry;
		bp->free_entry = e;
		e = next;
	}
	bp->own[i] = -1;
}

void pool_broadphase_set_mode(pool_broadphase *bp, pool_broadphase_mode mode) { bp->mode = mode; }

int pool_broadphase_begin(pool_broadphase *bp, const pool_allocator *a, const pool_table_def *table, double radius,
                          int n) {
	bp->on = bp->watching = 0;
	bp->n = n;
	if (n <= 0 || reserve_balls(bp, a, n))
		return 0;
	// The partner lists, whatever the search: after an event they name the balls to predict
	// again, where a scan of every ball would read every ball's record.
	for (int i = 0; i < n; ++i)
		bp->own[i] = bp->watch_first[i] = bp->watch_next[i] = bp->watch_prev[i] = -1;
	bp->watching = 1;
	const int use = bp->mode == POOL_BROADPHASE_GRID || (bp->mode == POOL_BROADPHASE_AUTO && n >= POOL_BROADPHASE_MIN_BALLS);
	if (!use)
		return 0;
	// The grid: the table and a cell around it; balls beyond (in flight, off the table) are
	// filed in the border cells.
	double cell = CELL_RADII * radius;
	while (((table->length + 2.0 * cell) / cell + 1.0) * ((table->width + 2.0 * cell) / cell + 1.0) > MAX_CELLS)
		cell *= 2.0;
	const int nx = (int)ceil((table->length + 2.0 * cell) / cell), ny = (int)ceil((table->width + 2.0 * cell) / cell);
	if (nx * ny > bp->cap_cells) {
		int *head = pool_mem_alloc(a, sizeof(int) * (size_t)(nx * ny));
		if (!head)
			return 0;
		pool_mem_free(a, bp->head);
		bp->head = head;
		bp->cap_cells = nx * ny;
	}
	bp->cell = cell;
	bp->inv_cell = 1.0 / cell;
	bp->radius = radius + POOL_BROADPHASE_MARGIN;
	bp->x0 = bp->y0 = -cell;
	bp->nx = nx;
	bp->ny = ny;
	bp->last_x = nx - 1;
	bp->last_y = ny - 1;
	for (int c = 0; c < nx * ny; ++c)
		bp->head[c] = -1;
	bp->used_entries = 0;
	bp->free_entry = -1;
	for (int i = 0; i < n; ++i) {
		bp->filed[2 * i] = INFINITY; // no window filed yet
		bp->filed[2 * i + 1] = -INFINITY;
	}
	// Room at once for the entries a shot of n balls files at its start (its first prediction
	// files every ball), rather than growing to it a doubling at a time, each copying the last.
	if (reserve_entries(bp, a, ENTRIES_PER_BALL * n))
		return 0;
	bp->on = 1;
	return 1;
}

void pool_broadphase_place(pool_broadphase *bp, const pool_allocator *a, int i, const pool_segment *seg, int active,
                           double from, double to) {
	if (!bp->on)
		return;
	remove_ball(bp, i);
	bp->filed[2 * i] = INFINITY; // no window filed (a query cuts the path)
	bp->filed[2 * i + 1] = -INFINITY;
	if (!active)
		return;
	if (!isfinite(from) || !isfinite(to)) { // an endless window (no max_time): every pair again
		bp->on = 0;
		return;
	}
	piece pieces[POOL_BROADPHASE_MAX_PIECES];
	const int k = cut(bp, seg, from, to, pieces);
	const int moving = seg->model->translating;
	for (int p = 0; p < k; ++p) {
		const double *box = pieces[p].box;
		int cx0, cx1, cy0, cy1;
		cells(bp, box, &cx0, &cx1, &cy0, &cy1);
		for (int cy = cy0; cy <= cy1; ++cy)
			for (int cx = cx0; cx <= cx1; ++cx) {
				const int c = cy * bp->nx + cx, first = bp->head[c];
				// The previous piece in this cell: it ends where this one starts, so extend it
				// (its box then holds both).
				if (first >= 0 && bp->entries[first].body == i && bp->entries[first].to == pieces[p].from) {
					pool_broadphase_entry *x = &bp->entries[first];
					x->to = pieces[p].to;
					x->box[0] = box[0] < x->box[0] ? box[0] : x->box[0];
					x->box[1] = box[1] > x->box[1] ? box[1] : x->box[1];
					x->box[2] = box[2] < x->box[2] ? box[2] : x->box[2];
					x->box[3] = box[3] > x->box[3] ? box[3] : x->box[3];
					continue;
				}
				if (reserve_entry(bp, a)) {
					bp->on = 0; // out of memory: the schedule goes back to all pairs
					return;
				}
				const int e = take_entry(bp);
				bp->entries[e] = (pool_broadphase_entry){
				    i, c, first, -1, bp->own[i], moving, pieces[p].from, pieces[p].to, {box[0], box[1], box[2], box[3]}};
				if (first >= 0)
					bp->entries[first].prev = e;
				bp->head[c] = e;
				bp->own[i] = e;
			}
	}
	bp->filed[2 * i] = from;
	bp->filed[2 * i + 1] = to;
}

// Lists in bp->found (from *count on) the balls other than i filed in cell c over [from, to]
// whose widened box meets `box` (moving ones only when ball i does not move), each once: a ball
// listed is marked in bp->near, its word in [*lo, *hi].
static inline void walk(pool_broadphase *bp, int i, int moving, int c, double from, double to, const double box[4],
                        int *count, int *lo, int *hi) {
	for (int e = bp->head[c]; e >= 0; e = bp->entries[e].next) {
		const pool_broadphase_entry *x = &bp->entries[e];
		if (x->body == i || !(moving || x->moving) || x->from > to || x->to < from || boxes_apart(x->box, box))
			continue;
		const int w = x->body >> 6;
		const uint64_t bit = (uint64_t)1 << (x->body & 63);
		if (bp->near[w] & bit)
			continue;
		bp->near[w] |= bit;
		*lo = w < *lo ? w : *lo;
		*hi = w > *hi ? w : *hi;
		bp->found[(*count)++] = x->body;
	}
}

int pool_broadphase_query(pool_broadphase *bp, int i, const pool_segment *seg, double now, double horizon) {
	const int moving = seg->model->translating;
	int count = 0, lo = bp->n, hi = -1;
	if (bp->filed[2 * i] <= now && bp->filed[2 * i + 1] == horizon) {
		// Ball i's own entries: its pieces over a window holding [now, horizon], one a cell.
		for (int e = bp->own[i]; e >= 0; e = bp->entries[e].next_own) {
			const pool_broadphase_entry *x = &bp->entries[e];
			if (x->to >= now)
				walk(bp, i, moving, x->cell, x->from > now ? x->from : now, x->to, x->box, &count, &lo, &hi);
		}
	} else {
		piece pieces[POOL_BROADPHASE_MAX_PIECES];
		const int k = cut(bp, seg, now, horizon, pieces);
		for (int p = 0; p < k; ++p) {
			const double *box = pieces[p].box;
			int cx0, cx1, cy0, cy1;
			cells(bp, box, &cx0, &cx1, &cy0, &cy1);
			for (int cy = cy0; cy <= cy1; ++cy)
				for (int cx = cx0; cx <= cx1; ++cx)
					walk(bp, i, moving, cy * bp->nx + cx, pieces[p].from, pieces[p].to, box, &count, &lo, &hi);
		}
	}
	// In index order, the marks cleared: a few balls sorted in place, more read off the marks.
	if (count <= SORT_MAX) {
		for (int k = 1; k < count; ++k) {
			const int b = bp->found[k];
			int at = k;
			for (; at > 0 && bp->found[at - 1] > b; --at)
				bp->found[at] = bp->found[at - 1];
			bp->found[at] = b;
		}
		for (int k = 0; k < count; ++k)
			bp->near[bp->found[k] >> 6] = 0;
	} else {
		int k = 0;
		for (int w = lo; w <= hi; ++w)
			for (; bp->near[w]; bp->near[w] &= bp->near[w] - 1)
				bp->found[k++] = 64 * w + __builtin_ctzll(bp->near[w]);
	}
	return count;
}

void pool_broadphase_repartner(pool_broadphase *bp, int x, int old, int partner) {
	if (!bp->watching || old == partner)
		return;
	if (old >= 0) {
		if (bp->watch_prev[x] >= 0)
			bp->watch_next[bp->watch_prev[x]] = bp->watch_next[x];
		else
			bp->watch_first[old] = bp->watch_next[x];
		if (bp->watch_next[x] >= 0)
			bp->watch_prev[bp->watch_next[x]] = bp->watch_prev[x];
	}
	bp->watch_prev[x] = -1;
	bp->watch_next[x] = -1;
	if (partner >= 0) {
		bp->watch_next[x] = bp->watch_first[partner];
		if (bp->watch_first[partner] >= 0)
			bp->watch_prev[bp->watch_first[partner]] = x;
		bp->watch_first[partner] = x;
	}
}

void pool_broadphase_free(pool_broadphase *bp, const pool_allocator *a) {
	void *arrays[] = {bp->head,        bp->entries,    bp->own,        bp->filed, bp->found,
	                  bp->near,        bp->watch_first, bp->watch_next, bp->watch_prev};
	for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k)
		pool_mem_free(a, arrays[k]);
	const pool_broadphase_mode mode = bp->mode;
	memset(bp, 0, sizeof *bp);
	bp->mode = mode;
}
