// Dormand-Prince 5(4): the tableau as in Hairer, Nørsett & Wanner (table II.5.2), with the error
// coefficients (b - b^) and Shampine's dense output of DOPRI5 (II.6).
#include "dopri5.h"

// The stages' abscissae (1/5, 3/10, 4/5, 8/9, 1, 1) are left out: the systems here are autonomous.
static const double a21 = 1.0 / 5.0;
static const double a31 = 3.0 / 40.0, a32 = 9.0 / 40.0;
static const double a41 = 44.0 / 45.0, a42 = -56.0 / 15.0, a43 = 32.0 / 9.0;
static const double a51 = 19372.0 / 6561.0, a52 = -25360.0 / 2187.0, a53 = 64448.0 / 6561.0, a54 = -212.0 / 729.0;
static const double a61 = 9017.0 / 3168.0, a62 = -355.0 / 33.0, a63 = 46732.0 / 5247.0, a64 = 49.0 / 176.0,
                    a65 = -5103.0 / 18656.0;
static const double b1 = 35.0 / 384.0, b3 = 500.0 / 1113.0, b4 = 125.0 / 192.0, b5 = -2187.0 / 6784.0,
                    b6 = 11.0 / 84.0;
static const double e1 = 71.0 / 57600.0, e3 = -71.0 / 16695.0, e4 = 71.0 / 1920.0, e5 = -17253.0 / 339200.0,
                    e6 = 22.0 / 525.0, e7 = -1.0 / 40.0;
static const double d1 = -12715105075.0 / 11282082432.0, d3 = 87487479700.0 / 32700410799.0,
                    d4 = -10690763975.0 / 1880347072.0, d5 = 701980252875.0 / 199316789632.0,
                    d6 = -1453857185.0 / 822651844.0, d7 = 69997945.0 / 29380423.0;

// The step over the first n components (n: a constant once inlined, so the loops vectorise);
// the rest keep y0's values and a zero slope.
static inline void take(pool_dopri5_rhs f, const void *ctx, const double *y0, const double *k1, double h,
                        pool_dopri5_step *st, const int n) {
	double y[POOL_DOPRI5_DIM];
	double(*k)[POOL_DOPRI5_DIM] = st->k;
	st->h = h;
	for (int i = n; i < POOL_DOPRI5_DIM; ++i) {
		y[i] = st->y0[i] = st->y1[i] = y0[i];
		st->err[i] = 0.0;
	}
	for (int i = 0; i < n; ++i) {
		st->y0[i] = y0[i];
		k[0][i] = k1[i];
		y[i] = y0[i] + h * a21 * k[0][i];
	}
	f(ctx, y, k[1]);
	for (int i = 0; i < n; ++i)
		y[i] = y0[i] + h * (a31 * k[0][i] + a32 * k[1][i]);
	f(ctx, y, k[2]);
	for (int i = 0; i < n; ++i)
		y[i] = y0[i] + h * (a41 * k[0][i] + a42 * k[1][i] + a43 * k[2][i]);
	f(ctx, y, k[3]);
	for (int i = 0; i < n; ++i)
		y[i] = y0[i] + h * (a51 * k[0][i] + a52 * k[1][i] + a53 * k[2][i] + a54 * k[3][i]);
	f(ctx, y, k[4]);
	for (int i = 0; i < n; ++i)
		y[i] = y0[i] + h * (a61 * k[0][i] + a62 * k[1][i] + a63 * k[2][i] + a64 * k[3][i] + a65 * k[4][i]);
	f(ctx, y, k[5]);
	for (int i = 0; i < n; ++i)
		st->y1[i] = y0[i] + h * (b1 * k[0][i] + b3 * k[2][i] + b4 * k[3][i] + b5 * k[4][i] + b6 * k[5][i]);
	f(ctx, st->y1, k[6]);
	for (int i = n; i < POOL_DOPRI5_DIM; ++i) // (whatever f wrote there)
		for (int j = 0; j < 7; ++j)
			k[j][i] = 0.0;
	for (int i = 0; i < n; ++i)
		st->err[i] = h * (e1 * k[0][i] + e3 * k[2][i] + e4 * k[3][i] + e5 * k[4][i] + e6 * k[5][i] + e7 * k[6][i]);
}

void pool_dopri5_take(pool_dopri5_rhs f, const void *ctx, const double *y0, const double *k1, double h,
                      pool_dopri5_step *st) {
	take(f, ctx, y0, k1, h, st, POOL_DOPRI5_DIM);
}

void pool_dopri5_take_lead(pool_dopri5_rhs f, const void *ctx, const double *y0, const double *k1, double h,
                           pool_dopri5_step *st) {
	take(f, ctx, y0, k1, h, st, POOL_DOPRI5_LEAD);
}

double pool_dopri5_dense_one(const pool_dopri5_step *st, double theta, int i) {
	const double h = st->h, t1 = 1.0 - theta;
	const double dy = st->y1[i] - st->y0[i];
	const double r3 = h * st->k[0][i] - dy;
	const double r4 = dy - h * st->k[6][i] - r3;
	const double r5 = h * (d1 * st->k[0][i] + d3 * st->k[2][i] + d4 * st->k[3][i] + d5 * st->k[4][i] +
	                       d6 * st->k[5][i] + d7 * st->k[6][i]);
	return st->y0[i] + theta * (dy + t1 * (r3 + theta * (r4 + t1 * r5)));
}

void pool_dopri5_dense(const pool_dopri5_step *st, double theta, double *y) {
	for (int i = 0; i < POOL_DOPRI5_DIM; ++i)
		y[i] = pool_dopri5_dense_one(st, theta, i);
}

pool_dopri5_linear pool_dopri5_linear_of(const pool_dopri5_step *st, const double *w) {
	pool_dopri5_linear l = {0.0, 0.0, 0.0, 0.0, 0.0};
	const double h = st->h;
	for (int i = 0; i < POOL_DOPRI5_DIM; ++i) {
		if (w[i] == 0.0)
			continue;
		const double dy = st->y1[i] - st->y0[i];
		const double r3 = h * st->k[0][i] - dy;
		const double r4 = dy - h * st->k[6][i] - r3;
		const double r5 = h * (d1 * st->k[0][i] + d3 * st->k[2][i] + d4 * st->k[3][i] + d5 * st->k[4][i] +
		                       d6 * st->k[5][i] + d7 * st->k[6][i]);
		l.y0 += w[i] * st->y0[i];
		l.dy += w[i] * dy;
		l.r3 += w[i] * r3;
		l.r4 += w[i] * r4;
		l.r5 += w[i] * r5;
	}
	return l;
}
