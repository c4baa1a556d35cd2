// pool-bench-quartic: the two data sets (the 2012 thesis's random set and real ball pairs).
#include <math.h>

#include "bench_quartic_ref.h"

void bq_gen_thesis(gsl_rng *rng, double *coeffs, long n) {
	for (long i = 0; i < 5 * n; ++i) {
		double mag = pow(10.0, -6.0 + 12.0 * gsl_rng_uniform(rng));
		coeffs[i] = gsl_rng_uniform(rng) < 0.5 ? -mag : mag;
	}
}

// Table and ball (docs/physics.md): playing area, radius, friction.
static const double bq_len = 2.54, bq_wid = 1.27, bq_r = 0.028575, bq_g = 9.81;
static const double bq_pi = 3.14159265358979323846;
static const double bq_mu_slide = 0.2, bq_mu_roll = 0.01;

typedef struct bq_ball {
	double p[2], v[2], a[2];
} bq_ball;

static void bq_place(gsl_rng *rng, bq_ball *b) {
	b->p[0] = bq_r + (bq_len - 2.0 * bq_r) * gsl_rng_uniform(rng);
	b->p[1] = bq_r + (bq_wid - 2.0 * bq_r) * gsl_rng_uniform(rng);
}

// Random velocity up to 8 m/s and spin; sliding (friction opposes the contact point's slip
// u = v + R k x w) or rolling (rolling resistance opposes v).
static void bq_motion(gsl_rng *rng, bq_ball *b) {
	double speed = 8.0 * gsl_rng_uniform(rng), dir = 2.0 * bq_pi * gsl_rng_uniform(rng);
	b->v[0] = speed * cos(dir);
	b->v[1] = speed * sin(dir);
	if (gsl_rng_uniform(rng) < 0.5) {
		double wmax = 8.0 / bq_r;
		double wx = wmax * (2.0 * gsl_rng_uniform(rng) - 1.0), wy = wmax * (2.0 * gsl_rng_uniform(rng) - 1.0);
		double ux = b->v[0] - bq_r * wy, uy = b->v[1] + bq_r * wx; // k x w = (-wy, wx)
		double un = hypot(ux, uy);
		b->a[0] = un > 0.0 ? -bq_mu_slide * bq_g * ux / un : 0.0;
		b->a[1] = un > 0.0 ? -bq_mu_slide * bq_g * uy / un : 0.0;
	} else {
		double vn = hypot(b->v[0], b->v[1]);
		b->a[0] = vn > 0.0 ? -bq_mu_roll * bq_g * b->v[0] / vn : 0.0;
		b->a[1] = vn > 0.0 ? -bq_mu_roll * bq_g * b->v[1] / vn : 0.0;
	}
}

void bq_gen_balls(gsl_rng *rng, double *coeffs, long n) {
	for (long i = 0; i < n; ++i) {
		bq_ball b1, b2;
		double kind = gsl_rng_uniform(rng);
		bq_place(rng, &b1);
		bq_motion(rng, &b1);
		if (kind < 0.05) {
			// Touching pair: a0 = P0.P0 - 4R^2 is zero up to rounding.
			double th = 2.0 * bq_pi * gsl_rng_uniform(rng);
			b2.p[0] = b1.p[0] + 2.0 * bq_r * cos(th);
			b2.p[1] = b1.p[1] + 2.0 * bq_r * sin(th);
			bq_motion(rng, &b2);
		} else {
			do
				bq_place(rng, &b2);
			while (hypot(b1.p[0] - b2.p[0], b1.p[1] - b2.p[1]) < 2.0 * bq_r);
			if (kind < 0.10) {
				// Both rolling the same way, acceleration from the same direction: a4 = a3 = 0.
				double vn = hypot(b1.v[0], b1.v[1]), s = 8.0 * gsl_rng_uniform(rng);
				if (vn == 0.0)
					vn = 1.0;
				b1.a[0] = -bq_mu_roll * bq_g * b1.v[0] / vn;
				b1.a[1] = -bq_mu_roll * bq_g * b1.v[1] / vn;
				b2.v[0] = s * b1.v[0] / vn;
				b2.v[1] = s * b1.v[1] / vn;
				b2.a[0] = b1.a[0];
				b2.a[1] = b1.a[1];
			} else if (kind < 0.15) {
				// Both rolling the same way, each acceleration from its own velocity: equal up to
				// rounding, so a4 is tiny (~1e-33) but not zero.
				double s = 8.0 * gsl_rng_uniform(rng), vn = hypot(b1.v[0], b1.v[1]);
				if (vn == 0.0)
					vn = 1.0;
				b2.v[0] = s * b1.v[0] / vn;
				b2.v[1] = s * b1.v[1] / vn;
				double v1 = hypot(b1.v[0], b1.v[1]), v2 = hypot(b2.v[0], b2.v[1]);
				for (int k = 0; k < 2; ++k) {
					b1.a[k] = v1 > 0.0 ? -bq_mu_roll * bq_g * b1.v[k] / v1 : 0.0;
					b2.a[k] = v2 > 0.0 ? -bq_mu_roll * bq_g * b2.v[k] / v2 : 0.0;
				}
			} else if (kind < 0.25) {
				// The other ball at rest (the usual shot: a moving ball towards a resting one).
				b2.v[0] = b2.v[1] = b2.a[0] = b2.a[1] = 0.0;
			} else {
				bq_motion(rng, &b2);
			}
		}
		double P[2], V[2], A[2];
		for (int k = 0; k < 2; ++k) {
			P[k] = b1.p[k] - b2.p[k];
			V[k] = b1.v[k] - b2.v[k];
			A[k] = 0.5 * (b1.a[k] - b2.a[k]);
		}
		double *c = coeffs + 5 * i;
		c[0] = A[0] * A[0] + A[1] * A[1];
		c[1] = 2.0 * (A[0] * V[0] + A[1] * V[1]);
		c[2] = V[0] * V[0] + V[1] * V[1] + 2.0 * (A[0] * P[0] + A[1] * P[1]);
		c[3] = 2.0 * (V[0] * P[0] + V[1] * P[1]);
		c[4] = P[0] * P[0] + P[1] * P[1] - 4.0 * bq_r * bq_r;
	}
}
