// Dormand & Prince's explicit Runge-Kutta pair of orders 5 and 4 (Hairer, Nørsett & Wanner,
// "Solving Ordinary Differential Equations I", II.5 and II.6): one step of a small system with
// its error estimate and Shampine's dense output of order 4 inside the step. The caller owns the
// step control and any events (cushion_mathavan.c).
#ifndef POOL_DOPRI5_H
#define POOL_DOPRI5_H

/// The system's size: every step works on vectors of this length, which the compiler unrolls and
/// vectorises (a fixed length saves about a tenth of an impact's instructions against a loop to a
/// run-time size). A smaller system pads its vectors with components whose slope is zero.
#define POOL_DOPRI5_DIM 8

/// dy/dx at y (the systems here are autonomous); ctx: the caller's.
typedef void (*pool_dopri5_rhs)(const void *ctx, const double *y, double *dydx);

/// One step from y0 over h: its stages, the fifth-order end y1 and the estimated error (the
/// difference from the embedded fourth-order solution).
typedef struct pool_dopri5_step {
	double h;
	double y0[POOL_DOPRI5_DIM], y1[POOL_DOPRI5_DIM], err[POOL_DOPRI5_DIM];
	double k[7][POOL_DOPRI5_DIM]; ///< slopes of the stages; k[6] is the slope at y1 (first
	                              ///< slope of the next step)
} pool_dopri5_step;

/// Takes the step from y0 over h; k1: the slope at y0 (the previous step's k[6], or f(y0)).
void pool_dopri5_take(pool_dopri5_rhs f, const void *ctx, const double *y0, const double *k1, double h,
                      pool_dopri5_step *step);

/// The leading components a system integrates while its others stand still (their slope zero).
#define POOL_DOPRI5_LEAD 6

/// pool_dopri5_take where the slope of the components past POOL_DOPRI5_LEAD is zero: those keep
/// y0's values (and a zero slope and error) at about three quarters of the arithmetic.
void pool_dopri5_take_lead(pool_dopri5_rhs f, const void *ctx, const double *y0, const double *k1, double h,
                           pool_dopri5_step *step);

/// The solution at x0 + theta h, 0 <= theta <= 1 (order 4, continuous with both ends).
void pool_dopri5_dense(const pool_dopri5_step *step, double theta, double *y);

/// Component i of the solution at x0 + theta h.
double pool_dopri5_dense_one(const pool_dopri5_step *step, double theta, int i);

/// A linear combination w . y of the dense output, as a polynomial in theta: evaluated by
/// pool_dopri5_linear_at at a few operations a point instead of one dense output per component.
typedef struct pool_dopri5_linear {
	double y0, dy, r3, r4, r5;
} pool_dopri5_linear;

/// The combination w . y of the step's dense output (w: POOL_DOPRI5_DIM weights).
pool_dopri5_linear pool_dopri5_linear_of(const pool_dopri5_step *step, const double *w);

/// w . y at x0 + theta h (the same expression as pool_dopri5_dense_one, on the combined terms).
static inline double pool_dopri5_linear_at(const pool_dopri5_linear *l, double theta) {
	const double t1 = 1.0 - theta;
	return l->y0 + theta * (l->dy + t1 * (l->r3 + theta * (l->r4 + t1 * l->r5)));
}

#endif
