// Inline 3D vector math used throughout the library (no allocation, no libm beyond sqrt).
#ifndef POOL_VEC3_H
#define POOL_VEC3_H

#include <math.h>

#include "pool/base.h"

static inline pool_vec3 pool_v3(double x, double y, double z) {
	pool_vec3 r = {x, y, z};
	return r;
}
static inline pool_vec3 pool_v3_add(pool_vec3 a, pool_vec3 b) { return pool_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline pool_vec3 pool_v3_sub(pool_vec3 a, pool_vec3 b) { return pool_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline pool_vec3 pool_v3_scale(pool_vec3 a, double s) { return pool_v3(a.x * s, a.y * s, a.z * s); }
/// a + s b
static inline pool_vec3 pool_v3_madd(pool_vec3 a, double s, pool_vec3 b) {
	return pool_v3(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z);
}
static inline double pool_v3_dot(pool_vec3 a, pool_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline pool_vec3 pool_v3_cross(pool_vec3 a, pool_vec3 b) {
	return pool_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double pool_v3_len(pool_vec3 a) { return sqrt(pool_v3_dot(a, a)); }

/// Speed at which point a (velocity va) closes on point b (vb) along the line between them (< 0:
/// parting); the caller makes sure they are apart.
static inline double pool_closing_speed(pool_vec3 pa, pool_vec3 va, pool_vec3 pb, pool_vec3 vb) {
	const pool_vec3 d = pool_v3_sub(pa, pb);
	return -pool_v3_dot(d, pool_v3_sub(va, vb)) / pool_v3_len(d);
}
/// The squared length of v's part across d (d nonzero): |v x d|^2 / d.d, never negative.
/// Written as v.v - (v.d)^2 / d.d, the difference of two equal numbers for v along d rounds to
/// either sign (+-1e-36 for 2e-11 m/s), and a relative path's curvature, |v_t|^2 / |d|, would
/// bend a pair together by nothing but rounding (soak seed 23, cluster shot 168914).
static inline double pool_v3_across2(pool_vec3 v, pool_vec3 d) {
	const pool_vec3 c = pool_v3_cross(v, d); // |v x d| = |v across d| |d|
	return pool_v3_dot(c, c) / pool_v3_dot(d, d);
}
/// k x a with k = (0, 0, 1).
static inline pool_vec3 pool_v3_kcross(pool_vec3 a) { return pool_v3(-a.y, a.x, 0.0); }
/// Horizontal part (z dropped).
static inline pool_vec3 pool_v3_xy(pool_vec3 a) { return pool_v3(a.x, a.y, 0.0); }
static inline int pool_v3_finite(pool_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

#endif
