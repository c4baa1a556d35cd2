// Random frictional-contact LCPs with the structure of a LINK step (docs/physics.md "LINK"), for
// test_lemke and tools/bench_lemke.c. Header only (static functions), C11 + libm.
//
// A cluster of `balls` balls (m = 0.17 kg, R = 0.028575 m, I = 2/5 m R^2) and K contacts, each
// between two balls or a ball and a fixed body (cloth, cushion), with a random unit normal n (from
// the second body to the first), a random tangent basis (t1, t2) and eta = 14 friction directions
// d_k = cos(2 pi k / 14) t1 + sin(2 pi k / 14) t2 (k and k + 7 are a +/- pair). J maps a force u
// at the contact to the wrenches (u, r_a x u) on the first ball, r_a = -R n, and (-u, r_b x -u)
// on the second, r_b = +R n. With G_i = J^T u_i for every direction u_i (the 14 K friction
// directions, then the K normals) and W = M^-1 (diagonal),
//     A = | G_D W G_D^T   G_D W G_N^T   E |   b = | G_D v_free |   unknowns  | dt beta |
//         | G_N W G_D^T   G_N W G_N^T   0 |       | G_N v_free |             | dt fn   |
//         | -E^T          diag(mu)      0 |       | 0          |             | lambda  |
// of size n = 16 K: friction block contact-major (contact c's direction k at 14 c + k), then the
// K normals, then the K lambdas. v_free = v + dt g, random v (|v_i| <= 1 m/s, |omega_i| <= 30
// rad/s), so normal velocities of both signs occur.
#ifndef POOL_TEST_LEMKE_FRICTION_LCP_H
#define POOL_TEST_LEMKE_FRICTION_LCP_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define FLCP_ETA 14
#define FLCP_MAX_BALLS 64
#define FLCP_PI 3.14159265358979323846

/// Degenerate variants (bit flags).
enum {
	FLCP_MU_ZERO = 1,     ///< every mu = 0 (frictionless)
	FLCP_B_ZERO = 2,      ///< v = 0 and no gravity: b = 0
	FLCP_REPEATED = 4,    ///< every second contact repeats the one before it exactly
	FLCP_SAME_NORMAL = 8, ///< every contact has the same normal and tangent basis (+z)
	FLCP_GHOST = 16,      ///< every third contact joins two fixed bodies: zero rows (J = 0)
};

typedef struct flcp_rng {
	uint64_t s;
} flcp_rng;

// splitmix64: deterministic on every platform.
static inline uint64_t flcp_next(flcp_rng *r) {
	uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

/// Uniform in [lo, hi).
static inline double flcp_uniform(flcp_rng *r, double lo, double hi) {
	return lo + (hi - lo) * (double)(flcp_next(r) >> 11) * 0x1p-53;
}

static inline void flcp_unit(flcp_rng *r, double u[3]) {
	for (;;) {
		double x = flcp_uniform(r, -1, 1), y = flcp_uniform(r, -1, 1), z = flcp_uniform(r, -1, 1);
		double s = x * x + y * y + z * z;
		if (s > 1e-4 && s <= 1.0) {
			s = sqrt(s);
			u[0] = x / s, u[1] = y / s, u[2] = z / s;
			return;
		}
	}
}

static inline void flcp_cross(const double a[3], const double b[3], double c[3]) {
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

/// Balls for a cluster of K contacts: 1 + K / 3 (about three contacts per ball, counting cloth
/// and cushions: a K = 50 cluster has 17 balls), at most FLCP_MAX_BALLS.
static inline int flcp_balls_for(int K) { return 1 + K / 3 < FLCP_MAX_BALLS ? 1 + K / 3 : FLCP_MAX_BALLS; }

/// One direction's wrench rows: up to two balls, 6 entries each (force, torque).
typedef struct flcp_dir {
	int ball[2];
	double g[2][6];
} flcp_dir;

/// Fills A (n x n, row-major, n = 16 K) and b (n) with a random friction LCP of K contacts among
/// `balls` balls (1..FLCP_MAX_BALLS); dirs is scratch of 15 K entries. mu_out (K, optional)
/// receives the friction coefficients. v_change: each velocity component v_l is multiplied by
/// 1 + v_change sin(l + 1) (the next step of the same cluster: same A, a nearby b).
static inline void flcp_generate(int K, int balls, uint64_t seed, int flags, double v_change, double *A, double *b,
                                 flcp_dir *dirs, double *mu_out) {
	const double m = 0.17, R = 0.028575, I = 0.4 * m * R * R, dt = 1e-3, g = -9.81;
	const int eta = FLCP_ETA, n = K * (eta + 2);
	flcp_rng rng = {seed * 0x2545F4914F6CDD1Dull + 12345u};
	double v[FLCP_MAX_BALLS][6];
	for (int i = 0; i < balls; ++i) {
		for (int c = 0; c < 3; ++c)
			v[i][c] = (flags & FLCP_B_ZERO) ? 0.0 : flcp_uniform(&rng, -1, 1);
		for (int c = 3; c < 6; ++c)
			v[i][c] = (flags & FLCP_B_ZERO) ? 0.0 : flcp_uniform(&rng, -30, 30);
		if (!(flags & FLCP_B_ZERO))
			v[i][2] += dt * g;
		for (int c = 0; c < 6; ++c)
			v[i][c] *= 1.0 + v_change * sin(6.0 * i + c + 1.0);
	}
	memset(A, 0, (size_t)n * (size_t)n * sizeof *A);
	memset(b, 0, (size_t)n * sizeof *b);
	int na = 0, nb = -1;
	double nrm[3] = {0, 0, 1}, t1[3] = {1, 0, 0}, t2[3] = {0, 1, 0}, mu = 0.0;
	for (int c = 0; c < K; ++c) {
		int repeat = (flags & FLCP_REPEATED) && (c % 2 == 1);
		if (!repeat) {
			na = (int)(flcp_next(&rng) % (uint64_t)balls);
			nb = -1;
			if (balls > 1 && flcp_uniform(&rng, 0, 1) < 0.7) {
				nb = (int)(flcp_next(&rng) % (uint64_t)(balls - 1));
				if (nb >= na)
					++nb;
			}
			if ((flags & FLCP_GHOST) && c % 3 == 2)
				na = -1, nb = -1;
			if (!(flags & FLCP_SAME_NORMAL)) {
				double aux[3];
				flcp_unit(&rng, nrm);
				flcp_unit(&rng, aux);
				flcp_cross(nrm, aux, t1);
				double s = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
				for (int i = 0; i < 3; ++i)
					t1[i] /= s;
				flcp_cross(nrm, t1, t2);
			}
			mu = (flags & FLCP_MU_ZERO) ? 0.0 : flcp_uniform(&rng, 0, 1);
		}
		if (mu_out)
			mu_out[c] = mu;
		for (int k = 0; k <= eta; ++k) { // k < eta: friction direction k; k == eta: the normal
			double u[3], nxu[3];
			for (int i = 0; i < 3; ++i)
				u[i] = k == eta ? nrm[i] : cos(2 * FLCP_PI * k / eta) * t1[i] + sin(2 * FLCP_PI * k / eta) * t2[i];
			flcp_cross(nrm, u, nxu);
			flcp_dir *d = &dirs[k == eta ? eta * K + c : eta * c + k];
			d->ball[0] = na;
			d->ball[1] = nb;
			for (int i = 0; i < 3; ++i) {
				d->g[0][i] = u[i];
				d->g[0][3 + i] = -R * nxu[i];
				d->g[1][i] = -u[i];
				d->g[1][3 + i] = -R * nxu[i];
			}
		}
		A[(size_t)(15 * K + c) * (size_t)n + (size_t)(14 * K + c)] = mu;
		for (int k = 0; k < eta; ++k) {
			A[(size_t)(eta * c + k) * (size_t)n + (size_t)(15 * K + c)] = 1.0;
			A[(size_t)(15 * K + c) * (size_t)n + (size_t)(eta * c + k)] = -1.0;
		}
	}
	const double w[6] = {1 / m, 1 / m, 1 / m, 1 / I, 1 / I, 1 / I};
	int nd = 15 * K;
	for (int i = 0; i < nd; ++i) {
		const flcp_dir *di = &dirs[i];
		for (int s = 0; s < 2; ++s)
			if (di->ball[s] >= 0)
				for (int l = 0; l < 6; ++l)
					b[i] += di->g[s][l] * v[di->ball[s]][l];
		for (int j = 0; j < nd; ++j) {
			const flcp_dir *dj = &dirs[j];
			double sum = 0.0;
			for (int s = 0; s < 2; ++s)
				for (int t = 0; t < 2; ++t)
					if (di->ball[s] >= 0 && di->ball[s] == dj->ball[t])
						for (int l = 0; l < 6; ++l)
							sum += di->g[s][l] * w[l] * dj->g[t][l];
			A[(size_t)i * (size_t)n + (size_t)j] = sum;
		}
	}
}

#endif
