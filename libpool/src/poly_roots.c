// First falling root by Bernstein subdivision (poly_roots.h says why it finds every crossing).
#include "poly_roots.h"

#include <math.h>

double pool_poly_eval(const double *p, int deg, double t) {
	double v = p[deg];
	for (int k = deg - 1; k >= 0; --k)
		v = v * t + p[k];
	return v;
}

void pool_poly_mul(const double *a, int da, const double *b, int db, double *c) {
	for (int k = 0; k <= da + db; ++k)
		c[k] = 0.0;
	for (int i = 0; i <= da; ++i)
		for (int j = 0; j <= db; ++j)
			c[i + j] += a[i] * b[j];
}

// Sign changes among the coefficients, zeros taking the sign before them.
static int variations(const double *b, int n) {
	int count = 0, sign = 0;
	for (int i = 0; i <= n; ++i) {
		const int s = b[i] > 0.0 ? 1 : b[i] < 0.0 ? -1 : 0;
		if (s == 0)
			continue;
		if (sign != 0 && s != sign)
			++count;
		sign = s;
	}
	return count;
}

// The root of p in [a, b] where p(a) >= 0 > p(b), bisected on p itself to the last bit.
static double bisect(const double *p, int deg, double a, double b) {
	for (int i = 0; i < 200; ++i) {
		const double mid = 0.5 * (a + b);
		if (mid <= a || mid >= b)
			break;
		if (pool_poly_eval(p, deg, mid) >= 0.0)
			a = mid;
		else
			b = mid;
	}
	return a;
}

// Searches [lo, hi] (Bernstein coefficients b, degree n) for the first falling root of p.
static double search(const double *p, int deg, const double *b, int n, double lo, double hi, double min_width) {
	const int v = variations(b, n);
	if (v == 0)
		return INFINITY;
	// The value at each end is its end coefficient.
	const int falls = b[0] >= 0.0 && b[n] < 0.0;
	if ((v == 1 && falls) || (hi - lo <= min_width && falls))
		return bisect(p, deg, lo, hi);
	if (v == 1 || hi - lo <= min_width)
		return INFINITY; // a rising root, or a graze within rounding
	// de Casteljau at the middle: left half in l, right half in r.
	double l[POOL_POLY_MAX_DEGREE + 1], r[POOL_POLY_MAX_DEGREE + 1], w[POOL_POLY_MAX_DEGREE + 1];
	for (int i = 0; i <= n; ++i)
		w[i] = b[i];
	for (int k = 0; k <= n; ++k) {
		l[k] = w[0];
		r[n - k] = w[n - k];
		for (int i = 0; i < n - k; ++i)
			w[i] = 0.5 * (w[i] + w[i + 1]);
	}
	const double mid = 0.5 * (lo + hi);
	const double first = search(p, deg, l, n, lo, mid, min_width);
	return first < INFINITY ? first : search(p, deg, r, n, mid, hi, min_width);
}

double pool_poly_first_falling_root(const double *p, int deg, double lo, double hi) {
	while (deg > 0 && p[deg] == 0.0)
		--deg;
	if (!(lo <= hi) || !isfinite(lo) || !isfinite(hi) || deg > POOL_POLY_MAX_DEGREE)
		return INFINITY;
	if (deg == 0)
		return INFINITY;
	// q(u) = p(lo + w u), u in [0, 1]: Taylor shift to lo, then scale by w.
	double q[POOL_POLY_MAX_DEGREE + 1];
	for (int k = 0; k <= deg; ++k)
		q[k] = p[k];
	for (int i = 0; i < deg; ++i)
		for (int k = deg - 1; k >= i; --k)
			q[k] += lo * q[k + 1];
	const double w = hi - lo;
	double scale = 1.0;
	for (int k = 0; k <= deg; ++k) {
		q[k] *= scale;
		scale *= w;
	}
	// Bernstein coefficients: b_i = sum_{j <= i} C(i, j) / C(n, j) q_j.
	double b[POOL_POLY_MAX_DEGREE + 1];
	for (int i = 0; i <= deg; ++i) {
		double sum = 0.0, cij = 1.0, cnj = 1.0; // C(i, j), C(n, j) for j = 0
		for (int j = 0; j <= i; ++j) {
			sum += cij / cnj * q[j];
			cij = cij * (i - j) / (j + 1);
			cnj = cnj * (deg - j) / (j + 1);
		}
		b[i] = sum;
	}
	return search(p, deg, b, deg, lo, hi, fmax(w * POOL_POLY_MIN_WIDTH, 0.0));
}
