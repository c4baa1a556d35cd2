// Unit tests of libpool's quartic solver: published hard cases, the billiards degenerate cases,
// random polynomials with known roots, random grazing ball-pair contacts (double roots), the fast
// path's safety checks and polish (called directly), and pool_quartic_smallest_root_in.
//
// Accuracy criterion (docs/quartic.md): a root r is right when |x - r| <= 1e3 kappa u |r|, with
// u = 2^-53 and kappa = sum |a_i| |r|^i / (|r| |p'(r)|), the reference being the roots of the
// rounded (double) coefficients. Ill-conditioned cases (kappa u > 1e-9, or a complex pair with
// |Im| / |z| < 1e-3) only have to give a sane answer; they are reported, not judged.
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <pool/quartic.h>

#include "quartic_fast.h" // internal: the fast path is tested directly (its checks, its accuracy)

static const double tq_u = 0x1p-53;

// The published cases, in the repository's tests/data.
#ifndef POOL_QUARTIC_CASES_FILE
#define POOL_QUARTIC_CASES_FILE POOL_TEST_DATA_DIR "/quartic_public_cases.json"
#endif

// --- A tiny JSON reader for quartic_public_cases.json (no JSON library in libpool) ---

typedef struct tq_case {
	char id[64];
	double coeffs[5];
	int n_real;
	double real[4];
	double cond[4]; // INFINITY where the file has null (a multiple root)
	int n_complex;
	double complex_roots[4][2];
	bool has_smallest;
	double smallest;
} tq_case;

typedef struct tq_json {
	const char *p;
	bool err;
} tq_json;

static void tq_ws(tq_json *j) {
	while (*j->p == ' ' || *j->p == '\n' || *j->p == '\r' || *j->p == '\t')
		++j->p;
}

static bool tq_eat(tq_json *j, char c) {
	tq_ws(j);
	if (*j->p == c) {
		++j->p;
		return true;
	}
	return false;
}

static void tq_expect(tq_json *j, char c) {
	if (!tq_eat(j, c))
		j->err = true;
}

static void tq_string(tq_json *j, char *out, size_t cap) {
	size_t n = 0;
	tq_expect(j, '"');
	while (!j->err && *j->p && *j->p != '"') {
		if (*j->p == '\\' && j->p[1])
			++j->p;
		if (out && n + 1 < cap)
			out[n++] = *j->p;
		++j->p;
	}
	if (out)
		out[n] = '\0';
	if (*j->p != '"')
		j->err = true;
	else
		++j->p;
}

// A number, or null (returns false, value untouched).
static bool tq_number(tq_json *j, double *v) {
	tq_ws(j);
	if (strncmp(j->p, "null", 4) == 0) {
		j->p += 4;
		return false;
	}
	char *end;
	*v = strtod(j->p, &end);
	if (end == j->p)
		j->err = true;
	j->p = end;
	return true;
}

static void tq_skip_value(tq_json *j) {
	tq_ws(j);
	char c = *j->p;
	if (c == '"') {
		tq_string(j, NULL, 0);
	} else if (c == '[' || c == '{') {
		char close = c == '[' ? ']' : '}';
		++j->p;
		if (tq_eat(j, close))
			return;
		do {
			if (c == '{') {
				tq_string(j, NULL, 0);
				tq_expect(j, ':');
			}
			tq_skip_value(j);
		} while (!j->err && tq_eat(j, ','));
		tq_expect(j, close);
	} else if (strncmp(j->p, "true", 4) == 0 || strncmp(j->p, "null", 4) == 0) {
		j->p += 4;
	} else if (strncmp(j->p, "false", 5) == 0) {
		j->p += 5;
	} else {
		double v;
		tq_number(j, &v);
	}
}

// An array of up to cap numbers (null -> INFINITY); returns how many.
static int tq_numbers(tq_json *j, double *out, int cap) {
	int n = 0;
	tq_expect(j, '[');
	if (tq_eat(j, ']'))
		return 0;
	do {
		double v = INFINITY;
		tq_number(j, &v);
		if (n < cap)
			out[n] = v;
		++n;
	} while (!j->err && tq_eat(j, ','));
	tq_expect(j, ']');
	if (n > cap)
		j->err = true;
	return n;
}

static void tq_parse_case(tq_json *j, tq_case *c) {
	memset(c, 0, sizeof *c);
	tq_expect(j, '{');
	do {
		char key[64];
		tq_string(j, key, sizeof key);
		tq_expect(j, ':');
		if (strcmp(key, "id") == 0) {
			tq_string(j, c->id, sizeof c->id);
		} else if (strcmp(key, "coeffs") == 0) {
			if (tq_numbers(j, c->coeffs, 5) != 5)
				j->err = true;
		} else if (strcmp(key, "real_roots") == 0) {
			c->n_real = tq_numbers(j, c->real, 4);
		} else if (strcmp(key, "real_root_cond") == 0) {
			tq_numbers(j, c->cond, 4);
		} else if (strcmp(key, "complex_roots") == 0) {
			tq_expect(j, '[');
			if (!tq_eat(j, ']')) {
				do {
					double z[2];
					if (tq_numbers(j, z, 2) != 2 || c->n_complex >= 4)
						j->err = true;
					else {
						c->complex_roots[c->n_complex][0] = z[0];
						c->complex_roots[c->n_complex][1] = z[1];
						++c->n_complex;
					}
				} while (!j->err && tq_eat(j, ','));
				tq_expect(j, ']');
			}
		} else if (strcmp(key, "smallest_nonnegative_root") == 0) {
			c->has_smallest = tq_number(j, &c->smallest);
		} else {
			tq_skip_value(j);
		}
	} while (!j->err && tq_eat(j, ','));
	tq_expect(j, '}');
}

// The whole file, NUL-terminated (free it); *size_out its length.
static char *tq_read_file(const char *path, long *size_out) {
	FILE *f = fopen(path, "rb");
	if (!f)
		fail_msg("cannot open %s", path);
	fseek(f, 0, SEEK_END);
	long size = ftell(f);
	fseek(f, 0, SEEK_SET);
	assert_true(size >= 0);
	char *text = malloc((size_t)size + 1);
	assert_non_null(text);
	assert_int_equal(fread(text, 1, (size_t)size, f), (size_t)size);
	text[size] = '\0';
	fclose(f);
	*size_out = size;
	return text;
}

static int tq_load_cases(tq_case *cases, int cap) {
	long size;
	char *text = tq_read_file(POOL_QUARTIC_CASES_FILE, &size);
	tq_json j = {text, false};
	int n = 0;
	tq_expect(&j, '[');
	do {
		assert_true(n < cap);
		tq_parse_case(&j, &cases[n++]);
	} while (!j.err && tq_eat(&j, ','));
	tq_expect(&j, ']');
	assert_false(j.err);
	free(text);
	return n;
}

// --- Helpers ---

// Condition number of root r of c (a4 first), evaluated in long double.
static double tq_kappa(const double c[5], long double r, long double *abs_err_per_u) {
	long double s = 0.0L, d = 0.0L, ar = fabsl(r);
	for (int i = 0; i < 5; ++i) {
		int k = 4 - i; // power of c[i]
		s += fabsl(c[i]) * powl(ar, k);
		if (k > 0)
			d += k * (long double)c[i] * powl(r, k - 1);
	}
	if (abs_err_per_u)
		*abs_err_per_u = s / fabsl(d);
	return r == 0.0L ? 0.0 : (double)(s / (ar * fabsl(d)));
}

static bool tq_close(double x, double r, double kappa) {
	return fabs(x - r) <= 1e3 * kappa * tq_u * fabs(r) + DBL_TRUE_MIN;
}

static int tq_solve(double a4, double a3, double a2, double a1, double a0, double roots[4]) {
	const double c[5] = {a4, a3, a2, a1, a0};
	return pool_quartic_real_roots(c, roots);
}

// --- Published hard cases ---

// docs/quartic.md's criterion, and nothing else, decides which cases are judged: a real root with
// kappa u > 1e-9 (or no condition number: a multiple root, null in the file), or a complex pair
// with |Im| / |z| < 1e-3.
static bool tq_case_ill_by_kappa(const tq_case *tc) {
	for (int k = 0; k < tc->n_real; ++k)
		if (!(tc->cond[k] * tq_u <= 1e-9))
			return true;
	return false;
}

static bool tq_case_ill_by_pair(const tq_case *tc) {
	for (int k = 0; k < tc->n_complex; ++k)
		if (fabs(tc->complex_roots[k][1]) < 1e-3 * hypot(tc->complex_roots[k][0], tc->complex_roots[k][1]))
			return true;
	return false;
}

static void test_public_cases(void **state) {
	(void)state;
	tq_case cases[64];
	int n = tq_load_cases(cases, 64);
	// The file as docs/quartic.md describes it: 37 cases, of which the criterion leaves 18 to judge;
	// 10 are ill by kappa, 13 by a nearly real complex pair (4 by both). A change of the data or of
	// the criterion shows up here instead of silently judging fewer cases.
	assert_int_equal(n, 37);
	int well = 0, ill = 0, ill_kappa = 0, ill_pair = 0;
	for (int i = 0; i < n; ++i) {
		const tq_case *tc = &cases[i];
		assert_true(tc->n_real + 2 * tc->n_complex == 4 || tc->coeffs[0] == 0.0);
		bool by_kappa = tq_case_ill_by_kappa(tc), by_pair = tq_case_ill_by_pair(tc);
		ill_kappa += by_kappa;
		ill_pair += by_pair;
		double roots[4] = {NAN, NAN, NAN, NAN};
		int m = pool_quartic_real_roots(tc->coeffs, roots);
		assert_true(m >= 0 && m <= 4);
		for (int k = 0; k < m; ++k) {
			assert_true(isfinite(roots[k]));
			if (k > 0)
				assert_true(roots[k - 1] <= roots[k]);
		}
		double first = NAN;
		int has_first = pool_quartic_smallest_root_in(tc->coeffs, 0.0, INFINITY, &first) == 0;
		if (has_first)
			assert_true(first >= 0.0 && isfinite(first));
		if (by_kappa || by_pair) {
			++ill;
			print_message("  ill-conditioned %-14s (%s%s) expected %d real roots, got %d\n", tc->id, by_kappa ? "kappa" : "",
			              by_pair ? (by_kappa ? ", near-real pair" : "near-real pair") : "", tc->n_real, m);
			continue;
		}
		++well;
		if (m != tc->n_real)
			fail_msg("%s: %d real roots, expected %d", tc->id, m, tc->n_real);
		for (int k = 0; k < m; ++k)
			if (!tq_close(roots[k], tc->real[k], tc->cond[k]))
				fail_msg("%s: root %d is %.17g, expected %.17g (kappa %g)", tc->id, k, roots[k], tc->real[k], tc->cond[k]);
		assert_int_equal(has_first, tc->has_smallest);
		if (has_first) {
			int k = 0;
			while (k < tc->n_real && tc->real[k] != tc->smallest)
				++k;
			assert_true(k < tc->n_real);
			if (!tq_close(first, tc->smallest, tc->cond[k]))
				fail_msg("%s: smallest non-negative root %.17g, expected %.17g", tc->id, first, tc->smallest);
		}
	}
	print_message("  public cases: %d well-conditioned all right, %d ill-conditioned reported (%d by kappa, %d by a "
	              "nearly real pair)\n",
	              well, ill, ill_kappa, ill_pair);
	assert_int_equal(well + ill, n);
	assert_int_equal(well, 18);
	assert_int_equal(ill, 19);
	assert_int_equal(ill_kappa, 10);
	assert_int_equal(ill_pair, 13);
}

// --- Billiards degenerate cases ---

static void test_equal_accelerations(void **state) {
	(void)state;
	double r[4];
	// a4 = a3 = 0: the quadratic (x - 1)(x - 2).
	assert_int_equal(tq_solve(0.0, 0.0, 1.0, -3.0, 2.0, r), 2);
	assert_true(fabs(r[0] - 1.0) < 1e-15 && fabs(r[1] - 2.0) < 1e-15);
	// Two balls rolling the same way, 0.5 m apart along x, relative speed 2 m/s, lateral offset
	// 0: A = 0, so |P0 + V0 t|^2 = 4R^2 is a quadratic; first contact when the gap closes.
	const double R = 0.028575;
	double px = -0.5, vx = 2.0;
	double c[5] = {0.0, 0.0, vx * vx, 2.0 * vx * px, px * px - 4.0 * R * R};
	int n = pool_quartic_real_roots(c, r);
	assert_int_equal(n, 2);
	double t_hit = (0.5 - 2.0 * R) / 2.0, t_leave = (0.5 + 2.0 * R) / 2.0;
	assert_true(fabs(r[0] - t_hit) < 1e-15 && fabs(r[1] - t_leave) < 1e-15);
	double t;
	assert_int_equal(pool_quartic_smallest_root_in(c, 0.0, 10.0, &t), 0);
	assert_true(fabs(t - t_hit) < 1e-15);
	// Moving apart: no root in the future.
	c[3] = -c[3];
	assert_true(pool_quartic_smallest_root_in(c, 0.0, 10.0, &t) < 0);
	// Equal velocities too: a constant; no roots, never four zeros.
	const double still[5] = {0.0, 0.0, 0.0, 0.0, 0.25};
	assert_int_equal(pool_quartic_real_roots(still, r), 0);
	assert_true(pool_quartic_smallest_root_in(still, 0.0, 10.0, &t) < 0);
}

static void test_tiny_leading_coefficient(void **state) {
	(void)state;
	// (x - 1)(x - 2)(x - 3) plus 1e-14 x^4: the cubic's roots barely move, and a fourth root
	// near -1e14 appears; that root is real and reported, it is outside any time window.
	const double c[5] = {1e-14, 1.0, -6.0, 11.0, -6.0};
	double r[4];
	int n = pool_quartic_real_roots(c, r);
	assert_int_equal(n, 4);
	assert_true(r[0] < -9e13 && r[0] > -1.1e14);
	for (int k = 1; k < 4; ++k) {
		// Reference: Newton on the exact coefficients in long double from the cubic's root.
		long double x = k;
		for (int it = 0; it < 20; ++it) {
			long double f = 0.0L, d = 0.0L;
			for (int i = 0; i < 5; ++i) {
				d = d * x + f;
				f = f * x + c[i];
			}
			x -= f / d;
		}
		double kappa = tq_kappa(c, x, NULL);
		assert_true(tq_close(r[k], (double)x, kappa));
	}
	double t;
	assert_int_equal(pool_quartic_smallest_root_in(c, 0.0, 10.0, &t), 0);
	assert_true(fabs(t - 1.0) < 1e-13);
	// Even tinier (the ball-pair case of equal accelerations up to rounding): still fine.
	const double c2[5] = {4.8e-35, 2.7e-17, 5.5577796127467147, 2.1034568596630869, -0.19589780863296691};
	n = pool_quartic_real_roots(c2, r);
	assert_true(n >= 2);
	assert_int_equal(pool_quartic_smallest_root_in(c2, 0.0, 10.0, &t), 0);
	double q = (-c2[3] + sqrt(c2[3] * c2[3] - 4.0 * c2[2] * c2[4])) / (2.0 * c2[2]);
	assert_true(fabs(t - q) < 1e-14);
}

static void test_zero_constant_term(void **state) {
	(void)state;
	double r[4], t;
	// x (x + 2)(x + 1)(x - 1): the root 0 must be exactly 0.
	assert_int_equal(tq_solve(1.0, 2.0, -1.0, -2.0, 0.0, r), 4);
	assert_true(r[2] == 0.0 && !signbit(r[2]));
	assert_true(fabs(r[0] + 2.0) < 1e-15 && fabs(r[1] + 1.0) < 1e-15 && fabs(r[3] - 1.0) < 1e-15);
	const double c[5] = {1.0, 2.0, -1.0, -2.0, 0.0};
	assert_int_equal(pool_quartic_smallest_root_in(c, 0.0, 5.0, &t), 0);
	assert_true(t == 0.0);
	// x^2 (x - 1)(x - 2): a double root at exactly 0.
	assert_int_equal(tq_solve(1.0, -3.0, 2.0, 0.0, 0.0, r), 4);
	assert_true(r[0] == 0.0 && r[1] == 0.0);
	// Touching balls moving apart: a0 = 0, a1 > 0; the root at now is 0, not -1e-17.
	assert_int_equal(tq_solve(0.0, 0.0, 4.0, 0.3, 0.0, r), 2);
	assert_true(r[1] == 0.0);
	// a0 = +-1e-300: the root near 0 is -a0 / a1 (to first order, exactly here), not 0, not lost.
	for (int s = -1; s <= 1; s += 2) {
		double a0 = s * 1e-300;
		int n = tq_solve(1.0, 2.0, -1.0, -2.0, a0, r);
		assert_int_equal(n, 4);
		double expect = a0 / 2.0;
		assert_true(fabs(r[2] - expect) <= 1e-15 * fabs(expect));
		const double cs[5] = {1.0, 2.0, -1.0, -2.0, a0};
		assert_int_equal(pool_quartic_smallest_root_in(cs, 0.0, 5.0, &t), 0);
		if (s > 0)
			assert_true(fabs(t - expect) <= 1e-15 * expect);
		else
			assert_true(fabs(t - 1.0) < 1e-15);
	}
}

static void test_near_double_roots(void **state) {
	(void)state;
	double r[4], t;
	// (x - 0.3)^2 (x + 1)(x - 2) with rounded coefficients: the pair at 0.3 may come out as two
	// close reals or a complex pair with a tiny imaginary part; either way a root pair at 0.3.
	long double rr = 0.3L;
	long double p2 = 1.0L, p1 = -2.0L * rr, p0 = rr * rr;      // (x - r)^2
	long double q2 = 1.0L, q1 = -1.0L, q0 = -2.0L;             // (x + 1)(x - 2)
	double c[5] = {(double)(p2 * q2), (double)(p2 * q1 + p1 * q2), (double)(p2 * q0 + p1 * q1 + p0 * q2),
	               (double)(p1 * q0 + p0 * q1), (double)(p0 * q0)};
	int n = pool_quartic_real_roots(c, r);
	assert_int_equal(n, 4);
	assert_true(fabs(r[0] + 1.0) < 1e-14 && fabs(r[3] - 2.0) < 1e-14);
	assert_true(fabs(r[1] - 0.3) < 1e-7 && fabs(r[2] - 0.3) < 1e-7);
	// Grazing contact: a ball passes another at exactly 2R centre distance while decelerating,
	// x(t) = -1 + 2 t - 0.1 t^2 along the line, offset 2R: |p|^2 - 4R^2 = x(t)^2, a double root.
	const double R = 0.028575, x0 = -1.0, v = 2.0, a = -0.1, y0 = 2.0 * R;
	double g[5] = {a * a, 2.0 * a * v, v * v + 2.0 * a * x0, 2.0 * v * x0, x0 * x0 + y0 * y0 - 4.0 * R * R};
	double t1 = (-v + sqrt(v * v - 4.0 * a * x0)) / (2.0 * a);
	n = pool_quartic_real_roots(g, r);
	assert_true(n >= 2);
	bool pair = false;
	for (int k = 0; k + 1 < n; ++k)
		pair |= fabs(r[k] - t1) < 1e-7 && fabs(r[k + 1] - t1) < 1e-7;
	assert_true(pair);
	assert_int_equal(pool_quartic_smallest_root_in(g, 0.0, 10.0, &t), 0);
	assert_true(fabs(t - t1) < 1e-7);
	// The same without acceleration (quadratic): (t - 1)^2 with a0 = 1 + 4R^2 - 4R^2 rounded.
	double h[5] = {0.0, 0.0, 1.0, -2.0, 1.0 + y0 * y0 - 4.0 * R * R};
	n = pool_quartic_real_roots(h, r);
	assert_int_equal(n, 2);
	assert_true(fabs(r[0] - 1.0) < 1e-7 && fabs(r[1] - 1.0) < 1e-7);
	// Exact multiple roots: (x - 1000)^4 and (x - 1)^2 (x + 1)^2.
	assert_int_equal(tq_solve(1.0, -4000.0, 6e6, -4e9, 1e12, r), 4);
	for (int k = 0; k < 4; ++k)
		assert_true(fabs(r[k] - 1000.0) < 1e-3);
	assert_int_equal(tq_solve(1.0, 0.0, -2.0, 0.0, 1.0, r), 4);
	assert_true(r[0] == -1.0 && r[1] == -1.0 && r[2] == 1.0 && r[3] == 1.0);
}

static void test_lower_degrees(void **state) {
	(void)state;
	double r[4];
	assert_int_equal(tq_solve(0.0, 0.0, 0.0, 2.0, -1.0, r), 1);
	assert_true(r[0] == 0.5);
	assert_int_equal(tq_solve(0.0, 0.0, 1.0, 0.0, -4.0, r), 2);
	assert_true(r[0] == -2.0 && r[1] == 2.0);
	assert_int_equal(tq_solve(0.0, 0.0, 1.0, 0.0, 4.0, r), 0);
	assert_int_equal(tq_solve(0.0, 0.0, -1.0, 2.0, -1.0, r), 2); // -(x - 1)^2
	assert_true(r[0] == 1.0 && r[1] == 1.0);
	assert_int_equal(tq_solve(0.0, 1.0, -6.0, 11.0, -6.0, r), 3);
	for (int k = 0; k < 3; ++k)
		assert_true(fabs(r[k] - (k + 1)) < 1e-14);
	assert_int_equal(tq_solve(0.0, -2.0, 0.0, 0.0, 16.0, r), 1); // -2 x^3 + 16: x = 2
	assert_true(fabs(r[0] - 2.0) < 1e-15);
	assert_int_equal(tq_solve(0.0, 1.0, 0.0, 1.0, 0.0, r), 1); // x (x^2 + 1)
	assert_true(r[0] == 0.0);
	assert_int_equal(tq_solve(1.0, 0.0, 0.0, 0.0, 0.0, r), 4); // x^4
	for (int k = 0; k < 4; ++k)
		assert_true(r[k] == 0.0);
	assert_int_equal(tq_solve(1.0, 0.0, 0.0, 0.0, -16.0, r), 2);
	assert_true(fabs(r[0] + 2.0) < 1e-15 && fabs(r[1] - 2.0) < 1e-15);
	assert_int_equal(tq_solve(1.0, 0.0, 0.0, 0.0, 16.0, r), 0);
}

static void test_zero_constant_and_bad_input(void **state) {
	(void)state;
	double r[4] = {0}, t = 42.0;
	assert_int_equal(tq_solve(0.0, 0.0, 0.0, 0.0, 0.0, r), 0);
	assert_int_equal(tq_solve(0.0, 0.0, 0.0, 0.0, 3.0, r), 0);
	assert_int_equal(tq_solve(-0.0, 0.0, -0.0, 0.0, -3.0, r), 0);
	const double bad[] = {NAN, INFINITY, -INFINITY};
	for (int b = 0; b < 3; ++b)
		for (int i = 0; i < 5; ++i) {
			double c[5] = {1.0, -10.0, 35.0, -50.0, 24.0};
			c[i] = bad[b];
			assert_int_equal(pool_quartic_real_roots(c, r), 0);
			assert_true(pool_quartic_smallest_root_in(c, 0.0, 10.0, &t) < 0);
		}
	const double ok[5] = {1.0, -10.0, 35.0, -50.0, 24.0};
	assert_true(pool_quartic_smallest_root_in(ok, NAN, 10.0, &t) < 0);
	assert_true(pool_quartic_smallest_root_in(ok, 0.0, NAN, &t) < 0);
	assert_true(pool_quartic_smallest_root_in(ok, 5.0, 0.0, &t) < 0);
	assert_int_equal(pool_quartic_real_roots(NULL, r), 0);
	// Extreme but finite magnitudes: no overflow, no crash, roots right.
	assert_int_equal(tq_solve(1e-300, 1.0, -3.0, 2.0, 0.0, r), 4); // huge root near -1e300
	assert_true(r[0] < -9e299 && r[1] == 0.0 && fabs(r[2] - 1.0) < 1e-15 && fabs(r[3] - 2.0) < 1e-15);
	assert_int_equal(tq_solve(1e300, -3e300, 2e300, 0.0, 0.0, r), 4);
	assert_true(r[0] == 0.0 && r[1] == 0.0 && fabs(r[2] - 1.0) < 1e-15 && fabs(r[3] - 2.0) < 1e-15);
	assert_int_equal(tq_solve(DBL_MAX, DBL_MAX, -DBL_MAX, -DBL_MAX, 0.0, r), 4);
	// Monomials with extreme coefficients: only the exact zero roots.
	assert_int_equal(tq_solve(0.0, 0.0, 0.0, 1e100, 0.0, r), 1);
	assert_true(r[0] == 0.0);
	assert_int_equal(tq_solve(1e-200, 0.0, 0.0, 0.0, 0.0, r), 4);
	assert_true(r[0] == 0.0 && r[3] == 0.0);
	// A subnormal leading coefficient: its root (-2e323) is beyond the double range and dropped.
	assert_int_equal(tq_solve(DBL_TRUE_MIN, 1.0, -6.0, 11.0, -6.0, r), 3);
	for (int k = 0; k < 3; ++k)
		assert_true(fabs(r[k] - (k + 1)) < 1e-14);
	// Roots 1e-30 .. 1e30 apart (Orellana & De Michele's case 24 scaled up): all four found.
	assert_int_equal(tq_solve(1e-300, 1.0, -6.0, 11.0, -6.0, r), 4);
	assert_true(fabs(r[0] / -1e300 - 1.0) < 1e-14);
	for (int k = 1; k < 4; ++k)
		assert_true(fabs(r[k] - k) < 1e-14);
}

// --- Random polynomials with known roots ---

static uint64_t tq_rng = 0x9E3779B97F4A7C15ULL;

static double tq_uniform(void) {
	tq_rng ^= tq_rng >> 12;
	tq_rng ^= tq_rng << 25;
	tq_rng ^= tq_rng >> 27;
	return (double)((tq_rng * 2685821657736338717ULL) >> 11) * 0x1p-53;
}

static double tq_log_uniform(double lo_exp10, double hi_exp10) {
	return pow(10.0, lo_exp10 + (hi_exp10 - lo_exp10) * tq_uniform());
}

static double tq_signed(double m) {
	return tq_uniform() < 0.5 ? -m : m;
}

// Coefficients (a4 first) of lead * prod of factors, each factor x - r or
// x^2 - 2 re x + (re^2 + im^2): built in long double, rounded once to double at the end.
static void tq_expand(long double lead, int n_real, const long double *real, int n_pairs, const long double (*pairs)[2],
                      double out[5]) {
	long double p[5] = {lead, 0, 0, 0, 0}; // p[k]: coefficient of x^(deg - k), built up
	int deg = 0;
	for (int i = 0; i < n_real; ++i) {
		for (int k = deg + 1; k >= 1; --k)
			p[k] -= real[i] * p[k - 1];
		++deg;
	}
	for (int i = 0; i < n_pairs; ++i) {
		long double s = 2.0L * pairs[i][0], q = pairs[i][0] * pairs[i][0] + pairs[i][1] * pairs[i][1];
		for (int k = deg + 2; k >= 1; --k)
			p[k] = p[k] - s * p[k - 1] + (k >= 2 ? q * p[k - 2] : 0.0L);
		deg += 2;
	}
	for (int k = 0; k < 5; ++k)
		out[k] = (double)p[k];
}

// True when a complex pair lies within 1e-3 (relative) of the real axis: its real part is then
// nearly a double root, too ill-conditioned to judge the root count by.
static bool tq_near_real(int n_pairs, const long double (*pairs)[2]) {
	bool near_real = false;
	for (int i = 0; i < n_pairs; ++i)
		near_real |= fabsl(pairs[i][1]) < 1e-3L * hypotl(pairs[i][0], pairs[i][1]);
	return near_real;
}

// Cluster criteria for tq_reference, on neighbouring sorted reference roots lo <= hi.
// Random products: two starting points polished into one root.
static bool tq_same_root(long double lo, long double hi) {
	return hi == lo;
}

// Clustered products: polished into one root, clustered beyond what the reference resolves.
static bool tq_unresolved_roots(long double lo, long double hi) {
	return !(hi - lo > 1e-12L * fabsl(hi));
}

// Reference for a product with known real roots real[0..n_real): each polished by Newton in
// long double on the ROUNDED coefficients c (so the reference is the exact root of what the
// solver sees), with its condition number, sorted ascending together. Returns true when the case
// is ill-conditioned: a root with kappa u > 1e-9 or moved more than 1e-6 relative by the polish,
// or two neighbouring roots that `clustered` judges one.
static bool tq_reference(const double c[5], int n_real, const long double *real,
                         bool (*clustered)(long double lo, long double hi), long double ref[4], double kap[4]) {
	bool ill = false;
	for (int i = 0; i < n_real; ++i) {
		long double x = real[i];
		for (int it = 0; it < 30; ++it) {
			long double f = 0.0L, d = 0.0L;
			for (int k = 0; k < 5; ++k) {
				d = d * x + f;
				f = f * x + c[k];
			}
			if (d == 0.0L)
				break;
			x -= f / d;
		}
		ref[i] = x;
		kap[i] = tq_kappa(c, x, NULL);
		if (!(kap[i] * tq_u <= 1e-9) || fabsl(x - real[i]) > 1e-6L * fabsl(real[i]))
			ill = true;
	}
	// Sort the reference (insertion) with its condition numbers.
	for (int i = 1; i < n_real; ++i)
		for (int j = i; j > 0 && ref[j - 1] > ref[j]; --j) {
			long double tr = ref[j];
			ref[j] = ref[j - 1];
			ref[j - 1] = tr;
			double tk = kap[j];
			kap[j] = kap[j - 1];
			kap[j - 1] = tk;
		}
	for (int i = 1; i < n_real; ++i)
		if (clustered(ref[i - 1], ref[i]))
			ill = true;
	return ill;
}

static void test_random_products(void **state) {
	(void)state;
	int checked = 0, skipped = 0;
	for (int iter = 0; iter < 6000; ++iter) {
		int n_pairs = iter % 3; // 4 real roots, 2 real + a complex pair, 2 complex pairs
		int n_real = 4 - 2 * n_pairs;
		double scale = tq_log_uniform(-4.0, 4.0); // overall root scale
		long double real[4], pairs[2][2];
		for (int i = 0; i < n_real; ++i)
			real[i] = tq_signed(scale * tq_log_uniform(-3.0, 3.0));
		for (int i = 0; i < n_pairs; ++i) {
			pairs[i][0] = tq_signed(scale * tq_log_uniform(-3.0, 3.0));
			pairs[i][1] = scale * tq_log_uniform(-3.0, 3.0);
		}
		bool near_real = tq_near_real(n_pairs, (const long double(*)[2])pairs);
		long double lead = tq_signed(tq_log_uniform(-6.0, 6.0));
		double c[5];
		tq_expand(lead, n_real, real, n_pairs, (const long double(*)[2])pairs, c);
		// Reference: the known real roots polished by Newton on the ROUNDED coefficients.
		long double ref[4];
		double kap[4];
		bool ill = tq_reference(c, n_real, real, tq_same_root, ref, kap) || near_real;
		double r[4];
		int n = pool_quartic_real_roots(c, r);
		assert_true(n >= 0 && n <= 4);
		if (ill) {
			++skipped;
			continue;
		}
		++checked;
		if (n != n_real)
			fail_msg("case %d: %d real roots, expected %d (coeffs %.17g %.17g %.17g %.17g %.17g)", iter, n, n_real, c[0],
			         c[1], c[2], c[3], c[4]);
		for (int i = 0; i < n; ++i)
			if (!tq_close(r[i], (double)ref[i], kap[i]))
				fail_msg("case %d: root %.17g, expected %.17Lg (kappa %g)", iter, r[i], ref[i], kap[i]);
		// The window solver agrees with the full solver on a window whose ends are away from roots.
		double lo = tq_signed(scale * tq_log_uniform(-3.0, 3.0)), hi = lo + scale * tq_log_uniform(-3.0, 3.0);
		bool clear = true;
		for (int i = 0; i < n; ++i)
			clear &= fabs(r[i] - lo) > 1e-9 * fabs(r[i]) && fabs(r[i] - hi) > 1e-9 * fabs(r[i]);
		if (!clear)
			continue;
		int first = -1;
		for (int i = 0; i < n && first < 0; ++i)
			if (r[i] >= lo && r[i] <= hi)
				first = i;
		double t;
		int got = pool_quartic_smallest_root_in(c, lo, hi, &t);
		if (first < 0) {
			assert_true(got < 0);
		} else {
			assert_int_equal(got, 0);
			if (!tq_close(t, (double)ref[first], kap[first]))
				fail_msg("case %d: window [%g, %g] root %.17g, expected %.17Lg", iter, lo, hi, t, ref[first]);
		}
	}
	print_message("  random products: %d well-conditioned checked, %d ill-conditioned skipped\n", checked, skipped);
	assert_true(checked > 4000);
}

// Clustered roots, the cases where an algebraic solver's root count is at risk (the fast path
// must then decline, or be right): near-double real roots (relative gaps 1e-1 ... 1e-9), complex
// pairs close to the real axis (|Im| / |z| 1e-1 ... 1e-7), two nearby complex pairs, a real root
// next to a complex pair, and root magnitudes spread over 1e-8 ... 1e8. Judged as in
// test_random_products: every well-conditioned case gets the right count and accurate roots.
static void test_clustered_products(void **state) {
	(void)state;
	int checked = 0, skipped = 0;
	for (int iter = 0; iter < 40000; ++iter) {
		int kind = iter % 4;
		double scale = tq_log_uniform(-4.0, 4.0);
		long double real[4], pairs[2][2];
		int n_real = 0, n_pairs = 0;
		double gap = tq_log_uniform(-9.0, -1.0);
		long double base = tq_signed(scale * tq_log_uniform(-2.0, 2.0));
		if (kind == 0) { // near-double real pair and two more real roots or a complex pair
			real[n_real++] = base;
			real[n_real++] = base * (1.0L + tq_signed(gap));
			if (tq_uniform() < 0.5) {
				real[n_real++] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
				real[n_real++] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
			} else {
				pairs[n_pairs][0] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
				pairs[n_pairs][1] = scale * tq_log_uniform(-4.0, 4.0);
				++n_pairs;
			}
		} else if (kind == 1) { // complex pair near the real axis
			pairs[n_pairs][0] = base;
			pairs[n_pairs][1] = fabsl(base) * tq_log_uniform(-7.0, -1.0);
			++n_pairs;
			real[n_real++] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
			real[n_real++] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
		} else if (kind == 2) { // two nearby complex pairs
			long double im = fabsl(base) * tq_log_uniform(-3.0, 1.0);
			pairs[0][0] = base;
			pairs[0][1] = im;
			pairs[1][0] = base * (1.0L + tq_signed(gap));
			pairs[1][1] = im * (1.0L + gap * tq_uniform());
			n_pairs = 2;
		} else { // a real root next to a complex pair, one more real root
			long double im = fabsl(base) * tq_log_uniform(-4.0, 0.0);
			pairs[0][0] = base;
			pairs[0][1] = im;
			n_pairs = 1;
			real[n_real++] = base + tq_signed(im * tq_log_uniform(-2.0, 1.0));
			real[n_real++] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
		}
		bool near_real = tq_near_real(n_pairs, (const long double(*)[2])pairs);
		double c[5];
		tq_expand(tq_signed(tq_log_uniform(-6.0, 6.0)), n_real, real, n_pairs, (const long double(*)[2])pairs, c);
		long double ref[4];
		double kap[4];
		bool ill = tq_reference(c, n_real, real, tq_unresolved_roots, ref, kap) || near_real;
		double r[4];
		int n = pool_quartic_real_roots(c, r);
		assert_true(n >= 0 && n <= 4);
		for (int i = 1; i < n; ++i)
			assert_true(r[i - 1] <= r[i]);
		if (ill) {
			++skipped;
			continue;
		}
		++checked;
		if (n != n_real)
			fail_msg("case %d (kind %d): %d real roots, expected %d (coeffs %.17g %.17g %.17g %.17g %.17g)", iter, kind, n,
			         n_real, c[0], c[1], c[2], c[3], c[4]);
		for (int i = 0; i < n; ++i)
			if (!tq_close(r[i], (double)ref[i], kap[i]))
				fail_msg("case %d (kind %d): root %.17g, expected %.17Lg (kappa %g)", iter, kind, r[i], ref[i], kap[i]);
		// The window solver finds the smallest non-negative root.
		int first = -1;
		for (int i = 0; i < n && first < 0; ++i)
			if (r[i] >= 0.0)
				first = i;
		double t;
		int got = pool_quartic_smallest_root_in(c, 0.0, INFINITY, &t);
		if (first < 0) {
			assert_true(got < 0);
		} else {
			assert_int_equal(got, 0);
			if (!tq_close(t, (double)ref[first], kap[first]))
				fail_msg("case %d: window root %.17g, expected %.17Lg", iter, t, ref[first]);
		}
	}
	print_message("  clustered products: %d well-conditioned checked, %d ill-conditioned skipped\n", checked, skipped);
	assert_true(checked > 20000);
}

// Arbitrary bit patterns and magnitudes: never a crash or hang, 0 to 4 finite sorted roots, and a
// window root inside its window.
static void test_arbitrary_input(void **state) {
	(void)state;
	for (int i = 0; i < 200000; ++i) {
		double c[5];
		for (int k = 0; k < 5; ++k) {
			if (i % 2 == 0) {
				uint64_t bits = tq_rng = tq_rng * 6364136223846793005ULL + 1442695040888963407ULL;
				memcpy(&c[k], &bits, sizeof c[k]);
			} else {
				c[k] = tq_uniform() < 0.125 ? 0.0 : tq_signed(pow(10.0, -300.0 + 600.0 * tq_uniform()));
			}
		}
		double r[4], t;
		int n = pool_quartic_real_roots(c, r);
		assert_true(n >= 0 && n <= 4);
		for (int k = 0; k < n; ++k) {
			assert_true(isfinite(r[k]));
			if (k > 0)
				assert_true(r[k - 1] <= r[k]);
		}
		if (pool_quartic_smallest_root_in(c, -1e10, 1e10, &t) == 0)
			assert_true(t >= -1e10 && t <= 1e10);
	}
}

// --- Grazing ball-pair contacts (double roots) ---

// One ball passes another at exactly 2R centre distance: the relative path p(t) = P + V t + A t^2
// touches the circle |p| = 2R at t0 > 0, so g(t) = |p(t)|^2 - 4R^2 has an exact double root at t0.
// Built in the frame where the contact normal is x and the relative velocity at contact is y (g is
// invariant under rotation, so this loses nothing): with tau = t - t0,
//   p = (2R + ax tau^2, s tau + ay tau^2),  g = tau^2 (|A|^2 tau^2 + 2 s ay tau + s^2 + 4R ax),
// a grazing contact from outside when g''(t0) / 2 = s^2 + 4R ax > 0. The coefficients
//   a4 = |A|^2, a3 = 2 A.V, a2 = |V|^2 + 2 A.P, a1 = 2 P.V, a0 = |P|^2 - 4R^2
// are computed in long double and rounded once, as the engine's would be. Cases where the
// long-double sums cancel by more than 64 (their own rounding could then reach u * S) or where
// another root lies in [0, 1.01 t0] or within 1 % of t0 (not a first contact, or a near-triple
// root) are regenerated; 10 % have A = 0 exactly (two balls rolling the same way: a quadratic).
//
// Tolerance. Rounding the coefficients changes g by e(t) with |e| <= u S(t), S = sum |a_k| t^k,
// and the isolation solver reports a critical point with |p| <= 16 u S as a double root. So every
// root the solvers can report near t0 is a root of g + e with |e| <= eta S, eta = 32 u (twice the
// solver's own threshold), and |e'| <= eta S1, S1 = sum k |a_k| t^(k-1). Near t0,
// g = (g''/2) d^2 with d = t - t0, so (g''/2) d^2 - eta S1 |d| - eta S <= 0 gives
//   |d| <= 2 eta S1 / g'' + sqrt(2 eta S / g''),
// the sqrt(kappa u) of a double root: about 1e-9 .. 1e-6 s here. (Measured: at most 0.2 of it.)
static void test_grazing_ball_pairs(void **state) {
	(void)state;
	tq_rng = 0x243F6A8885A308D3ULL; // independent of the tests before
	const long double R = 0.028575L;
	int checked = 0, quadratic = 0;
	double worst = 0.0;
	while (checked < 30000) {
		long double t0 = tq_log_uniform(-2.0, 1.0);       // 0.01 .. 10 s
		long double s = tq_signed(tq_log_uniform(-1.3, 0.9)); // 0.05 .. 8 m/s past each other
		long double ax = 0.0L, ay = 0.0L;
		if (tq_uniform() >= 0.1) {
			ax = tq_signed(tq_log_uniform(-3.0, 0.6)); // up to 4 m/s^2 (sliding friction of both)
			ay = tq_signed(tq_log_uniform(-3.0, 0.6));
		}
		long double q0 = s * s + 4.0L * R * ax; // g''(t0) / 2
		if (!(q0 > 0.0L))
			continue;
		long double P[2] = {2.0L * R + ax * t0 * t0, -s * t0 + ay * t0 * t0};
		long double V[2] = {-2.0L * ax * t0, s - 2.0L * ay * t0};
		long double A[2] = {ax, ay};
		long double c[5], mag[5]; // coefficients (a4 first) and the sums of their terms' magnitudes
		c[0] = A[0] * A[0] + A[1] * A[1];
		mag[0] = c[0];
		c[1] = 2.0L * (A[0] * V[0] + A[1] * V[1]);
		mag[1] = 2.0L * (fabsl(A[0] * V[0]) + fabsl(A[1] * V[1]));
		c[2] = V[0] * V[0] + V[1] * V[1] + 2.0L * (A[0] * P[0] + A[1] * P[1]);
		mag[2] = V[0] * V[0] + V[1] * V[1] + 2.0L * (fabsl(A[0] * P[0]) + fabsl(A[1] * P[1]));
		c[3] = 2.0L * (P[0] * V[0] + P[1] * V[1]);
		mag[3] = 2.0L * (fabsl(P[0] * V[0]) + fabsl(P[1] * V[1]));
		c[4] = P[0] * P[0] + P[1] * P[1] - 4.0L * R * R;
		mag[4] = P[0] * P[0] + P[1] * P[1] + 4.0L * R * R;
		// The other two roots: t0 + tau with |A|^2 tau^2 + 2 s ay tau + q0 = 0.
		bool other_near = false;
		long double disc = s * s * ay * ay - c[0] * q0;
		if (c[0] != 0.0L && disc >= 0.0L)
			for (int k = -1; k <= 1; k += 2) {
				long double tr = t0 + (-s * ay + k * sqrtl(disc)) / c[0];
				other_near |= (tr >= 0.0L && tr <= 1.01L * t0) || fabsl(tr - t0) < 0.01L * t0;
			}
		long double S = 0.0L, S1 = 0.0L, M = 0.0L;
		for (int k = 0; k < 5; ++k) {
			S += fabsl(c[k]) * powl(t0, 4 - k);
			M += mag[k] * powl(t0, 4 - k);
			if (k < 4)
				S1 += (4 - k) * fabsl(c[k]) * powl(t0, 3 - k);
		}
		if (other_near || M > 64.0L * S)
			continue;
		double cd[5];
		for (int k = 0; k < 5; ++k)
			cd[k] = (double)c[k];
		quadratic += cd[0] == 0.0;
		++checked;
		const double eta = 32.0 * tq_u;
		double tol = (double)(eta * S1 / q0 + sqrtl(eta * S / q0)); // g'' = 2 q0
		double r[4];
		int n = pool_quartic_real_roots(cd, r);
		int near = 0;
		for (int i = 0; i < n; ++i)
			if (fabs(r[i] - (double)t0) <= tol) {
				++near;
				worst = fmax(worst, fabs(r[i] - (double)t0) / tol);
			}
		if (near != 2)
			fail_msg("grazing case %d: %d roots within %.3g of the double root %.17Lg (of %d real roots; coeffs %a %a %a %a %a)",
			         checked, near, tol, t0, n, cd[0], cd[1], cd[2], cd[3], cd[4]);
		// The collision window [0, 20 s]: the graze is the first contact.
		double t;
		if (pool_quartic_smallest_root_in(cd, 0.0, 20.0, &t) != 0 || !(fabs(t - (double)t0) <= tol))
			fail_msg("grazing case %d: window root %.17g, expected the double root %.17Lg within %.3g (coeffs %a %a %a %a %a)",
			         checked, t, t0, tol, cd[0], cd[1], cd[2], cd[3], cd[4]);
	}
	print_message("  grazing ball pairs: %d double roots found by both solvers (%d quadratics), worst distance %.2f of the "
	              "tolerance\n",
	              checked, quadratic, worst);
}

// --- The fast path (quartic_fast.c) directly: its safety checks and its polish ---

// Roots a and b closer than the fast path's near-multiple threshold (1e-7 relative).
static bool tq_fast_too_close(double a, double b) {
	return !(fabs(b - a) > 1e-7 * fmax(fabs(a), fabs(b)));
}

// Near-double roots: a real pair at base with relative gap 1e-15 .. 1e-7 (10 %: 0, an exact double
// root of the unrounded product), kind 0 in one Ferrari factor with two other real roots, kind 1
// with a complex pair (the pair at base is then necessarily one factor), kind 2 split across the
// two factors (roots of both signs around it), kind 3 a complex pair with |Im| / |z| 1e-15 .. 1e-6.
// The number of real roots at base is ambiguous at the fast path's accuracy (the factor's
// discriminant is within its error of 0, or two roots within 1e-7), so the fast path must decline
// almost always; when it does answer, the answer must be one the documented checks let through:
// - no two roots closer than 1e-7 relative (the near-multiple reject);
// - the pair at base reported as two real roots, never dropped as "complex" (a lost grazing
//   contact), and the right number of real roots (the discriminant margin).
// Nearly coincident complex pairs (|Im| >= |Re| / 2, relative distance 1e-15 .. 1e-6 or 0): the
// two factors have nearly common roots, the Jacobian of Newton's iteration on their coefficients
// (their resultant) nearly vanishes, and the iteration cannot converge to rounding: it must
// decline (0 of 100,000 such cases accepted when written; without the convergence check 37 %).
// Catches: the margin removed (pairs lost), the near-multiple reject removed (close roots
// accepted), the convergence check removed (coincident pairs accepted).
static void test_fast_path_declines(void **state) {
	(void)state;
	tq_rng = 0x13198A2E03707344ULL;
	int total = 0, accepted = 0;
	for (int iter = 0; iter < 20000; ++iter) {
		int kind = iter % 4;
		double scale = tq_log_uniform(-3.0, 3.0);
		long double base = tq_signed(scale * tq_log_uniform(-1.0, 1.0));
		double gap = tq_uniform() < 0.1 ? 0.0 : tq_log_uniform(-15.0, kind == 3 ? -6.0 : -7.0);
		long double real[4], pairs[2][2];
		int n_real = 0, n_pairs = 0, others = 0; // others: index of the first root not at base
		if (kind == 3) {
			pairs[n_pairs][0] = base;
			pairs[n_pairs][1] = fabsl(base) * gap;
			++n_pairs;
		} else {
			real[n_real++] = base;
			real[n_real++] = base * (1.0L + tq_signed(gap));
			others = 2;
		}
		if (kind == 2) {
			real[n_real++] = -base * tq_log_uniform(-2.0, 1.5);
			real[n_real++] = base * tq_log_uniform(-2.0, 1.5);
		} else if (kind == 1 || (kind == 3 && tq_uniform() < 0.5)) {
			pairs[n_pairs][0] = tq_signed(scale * tq_log_uniform(-2.0, 2.0));
			pairs[n_pairs][1] = scale * tq_log_uniform(-2.0, 2.0);
			++n_pairs;
		} else {
			real[n_real++] = tq_signed(scale * tq_log_uniform(-2.0, 2.0));
			real[n_real++] = tq_signed(scale * tq_log_uniform(-2.0, 2.0));
		}
		// Another root within 1e-3 of base would make the pair's window below ambiguous: skip.
		bool crowded = false;
		for (int i = others; i < n_real; ++i)
			crowded |= fabsl(real[i] - base) < 1e-3L * fabsl(base);
		for (int i = kind == 3 ? 1 : 0; i < n_pairs; ++i)
			crowded |= fabsl(pairs[i][0] - base) < 1e-3L * fabsl(base);
		if (crowded)
			continue;
		double c[5];
		tq_expand(tq_signed(tq_log_uniform(-3.0, 3.0)), n_real, real, n_pairs, (const long double(*)[2])pairs, c);
		++total;
		double r[4];
		int n = pool_quartic_fast_real_roots(c, r);
		if (n < 0)
			continue;
		++accepted;
		int expect = kind == 3 ? n_real + 2 : n_real, at_base = 0;
		for (int i = 0; i < n; ++i) {
			if (i > 0 && tq_fast_too_close(r[i - 1], r[i]))
				fail_msg("near-double case %d (kind %d): fast path accepted roots %.17g and %.17g, closer than 1e-7", iter, kind,
				         r[i - 1], r[i]);
			at_base += fabs(r[i] - (double)base) <= 1e-4 * fabs((double)base);
		}
		if (at_base != 2 || n != expect)
			fail_msg("near-double case %d (kind %d, gap %g): fast path reported %d real roots (%d at %.17Lg), expected %d "
			         "(2 there) or a decline (coeffs %.17g %.17g %.17g %.17g %.17g)",
			         iter, kind, gap, n, at_base, base, expect, c[0], c[1], c[2], c[3], c[4]);
	}
	print_message("  fast path on near-double roots: %d of %d answered (all consistent), the rest declined\n", accepted, total);
	assert_true(total > 19000);
	assert_true(accepted < total / 100); // declining is the rule here

	for (int iter = 0; iter < 4000; ++iter) {
		double scale = tq_log_uniform(-3.0, 3.0);
		long double base = tq_signed(scale * tq_log_uniform(-1.0, 1.0));
		long double im = fabsl(base) * tq_log_uniform(-0.3, 1.0);
		double gap = tq_uniform() < 0.1 ? 0.0 : tq_log_uniform(-15.0, -6.0);
		long double pairs[2][2] = {{base, im}, {base * (1.0L + tq_signed(gap)), im * (1.0L + gap * tq_uniform())}};
		double c[5], r[4];
		tq_expand(tq_signed(tq_log_uniform(-3.0, 3.0)), 0, NULL, 2, (const long double(*)[2])pairs, c);
		int n = pool_quartic_fast_real_roots(c, r);
		if (n != -1)
			fail_msg("coincident complex pairs %d (gap %g): fast path returned %d, expected a decline (coeffs %.17g %.17g %.17g "
			         "%.17g %.17g)",
			         iter, gap, n, c[0], c[1], c[2], c[3], c[4]);
	}
}

// Roots spread over up to 27 orders of magnitude: a huge root H (1e12 .. 3e17, inside the fast
// path's 2^60 root-scale limit), a moderate one M of the same sign (0.1 .. 300), and two tiny real
// roots or a tiny complex pair (1e-9 .. 1e-5). Ferrari's factors then carry rounding errors of the
// scale of H M in the tiny roots' factor: unpolished, those roots are off by up to ~1e9 kappa u;
// the Newton polish on p brings every root within docs/quartic.md's 1e3 kappa u. Plus general random
// products (as test_random_products). Every accepted answer is judged (count and accuracy) against
// the roots of the rounded coefficients; the fast path must answer the well-conditioned ones.
// Catches: the polish removed. Not caught: keeping the polish but ignoring its verdict (its reject
// when the first Newton step exceeds 1e-6 or 3 steps do not converge); on every family tried that
// only lets through answers for ill-conditioned clusters (a real root beside a nearly real pair)
// that are within kappa u anyway, so no test here can call them wrong.
static void test_fast_path_accuracy(void **state) {
	(void)state;
	tq_rng = 0xA4093822299F31D0ULL;
	int checked = 0, accepted = 0;
	for (int iter = 0; iter < 24000; ++iter) {
		long double real[4], pairs[1][2];
		int n_real = 0, n_pairs = 0;
		if (iter % 3 != 2) {
			double side = tq_signed(1.0);
			real[n_real++] = side * tq_log_uniform(12.0, 17.5);
			real[n_real++] = side * tq_log_uniform(-1.0, 2.5);
			if (iter % 3 == 0) {
				real[n_real++] = tq_signed(tq_log_uniform(-9.0, -5.0));
				real[n_real++] = tq_signed(tq_log_uniform(-9.0, -5.0));
			} else {
				pairs[0][0] = tq_signed(tq_log_uniform(-9.0, -5.0));
				pairs[0][1] = tq_log_uniform(-9.0, -5.0);
				n_pairs = 1;
			}
		} else {
			double scale = tq_log_uniform(-4.0, 4.0);
			for (int i = 0; i < 4; ++i)
				real[n_real++] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
			if (tq_uniform() < 0.5) {
				n_real = 2;
				pairs[0][0] = tq_signed(scale * tq_log_uniform(-4.0, 4.0));
				pairs[0][1] = scale * tq_log_uniform(-4.0, 4.0);
				n_pairs = 1;
			}
		}
		bool near_real = tq_near_real(n_pairs, (const long double(*)[2])pairs);
		double c[5];
		tq_expand(tq_signed(tq_log_uniform(-3.0, 3.0)), n_real, real, n_pairs, (const long double(*)[2])pairs, c);
		long double ref[4];
		double kap[4];
		if (tq_reference(c, n_real, real, tq_unresolved_roots, ref, kap) || near_real)
			continue;
		++checked;
		double r[4];
		int n = pool_quartic_fast_real_roots(c, r);
		if (n < 0)
			continue;
		++accepted;
		if (n != n_real)
			fail_msg("fast path case %d: %d real roots, expected %d (coeffs %.17g %.17g %.17g %.17g %.17g)", iter, n, n_real,
			         c[0], c[1], c[2], c[3], c[4]);
		for (int i = 0; i < n; ++i)
			if (!tq_close(r[i], (double)ref[i], kap[i]))
				fail_msg("fast path case %d: root %.17g, expected %.17Lg (kappa %g, error %.3g kappa u)", iter, r[i], ref[i],
				         kap[i], (double)(fabsl(r[i] - ref[i]) / (kap[i] * tq_u * fabsl(ref[i]))));
	}
	print_message("  fast path accuracy: %d of %d well-conditioned cases answered, all within 1e3 kappa u\n", accepted, checked);
	assert_true(checked > 20000);
	assert_true(accepted > checked * 95 / 100);
}

// --- A tiny non-zero constant term in a window (touching balls, up to rounding) ---

// a0 = tiny > 0 with a1 < 0: a root -a0 / a1 > 0 just after 0 (to first order; the next order,
// a0^2 a2 / a1^3, is below the last bit here). smallest_root_in on [0, hi] must return it, not 0
// and not the next root, for every degree, for a0 down to the subnormal range (where the root
// itself is subnormal and its precision that of the subnormal format) and for |a1| large or small;
// real_roots must report it too. With a1 > 0 the tiny root is negative: the window returns the
// next root.
static void test_tiny_constant_term_window(void **state) {
	(void)state;
	const double a0s[] = {1e-300, 1e-200, 1e-30, DBL_MIN, 1e-310, 8.0 * DBL_TRUE_MIN};
	const double a1s[] = {-2.0, -1e-3, -1e3};
	// a4..a2 of x^3 (x + 2) - x^2 ..., chosen so the other roots are of order 0.1 .. 30.
	const double heads[4][3] = {{1.0, 2.0, -1.0}, {0.0, 1.0, -1.0}, {0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}};
	for (int h = 0; h < 4; ++h)
		for (size_t i = 0; i < sizeof a0s / sizeof a0s[0]; ++i)
			for (size_t k = 0; k < sizeof a1s / sizeof a1s[0]; ++k) {
				double a0 = a0s[i], a1 = a1s[k];
				double c[5] = {heads[h][0], heads[h][1], heads[h][2], a1, a0};
				double expect = -a0 / a1; // exact to rounding: one division
				double tol = 4.0 * tq_u * expect + DBL_TRUE_MIN;
				double t = -1.0;
				if (pool_quartic_smallest_root_in(c, 0.0, 100.0, &t) != 0 || !(fabs(t - expect) <= tol))
					fail_msg("degree %d, a0 %g, a1 %g: window root %.17g, expected %.17g", 4 - h, a0, a1, t, expect);
				double r[4];
				int n = pool_quartic_real_roots(c, r), found = 0;
				for (int j = 0; j < n; ++j)
					found += fabs(r[j] - expect) <= tol;
				if (found != 1)
					fail_msg("degree %d, a0 %g, a1 %g: real_roots has the root %.17g %d times", 4 - h, a0, a1, expect, found);
				// a1 > 0: the tiny root -a0 / a1 < 0 is outside [0, hi].
				c[3] = -a1;
				if (pool_quartic_smallest_root_in(c, 0.0, 100.0, &t) == 0 && !(t > 1e-3))
					fail_msg("degree %d, a0 %g, a1 %g: window root %.17g, the tiny root is negative", 4 - h, a0, -a1, t);
			}
}

// --- pool_quartic_smallest_root_in ---

static void test_smallest_root_in(void **state) {
	(void)state;
	const double c[5] = {1.0, -10.0, 35.0, -50.0, 24.0}; // roots 1, 2, 3, 4
	double t = -1.0;
	assert_int_equal(pool_quartic_smallest_root_in(c, 0.0, 10.0, &t), 0);
	assert_true(fabs(t - 1.0) < 1e-14);
	assert_int_equal(pool_quartic_smallest_root_in(c, 1.5, 10.0, &t), 0);
	assert_true(fabs(t - 2.0) < 1e-14);
	assert_true(pool_quartic_smallest_root_in(c, 2.5, 2.9, &t) < 0);
	assert_true(pool_quartic_smallest_root_in(c, 4.5, INFINITY, &t) < 0);
	assert_true(pool_quartic_smallest_root_in(c, -INFINITY, 0.5, &t) < 0);
	assert_int_equal(pool_quartic_smallest_root_in(c, -INFINITY, INFINITY, &t), 0);
	assert_true(fabs(t - 1.0) < 1e-14);
	// A root exactly at lo, and a window that is a single point.
	assert_int_equal(pool_quartic_smallest_root_in(c, 3.0, 10.0, &t), 0);
	assert_true(t == 3.0);
	assert_int_equal(pool_quartic_smallest_root_in(c, 4.0, 4.0, &t), 0);
	assert_true(t == 4.0);
	// A root exactly at hi.
	assert_int_equal(pool_quartic_smallest_root_in(c, 2.5, 3.0, &t), 0);
	assert_true(t == 3.0);
	// No real roots at all.
	const double none[5] = {1.0, 0.0, 1.0, 0.0, 1.0};
	assert_true(pool_quartic_smallest_root_in(none, -10.0, 10.0, &t) < 0);
	// Collision of two balls, one at rest, the other rolling towards it from 1 m away at 3 m/s:
	// A = (-mu g / 2, 0), contact when 1 - 3 t + mu g t^2 / 2 = 2R (the quartic's first root).
	const double R = 0.028575, mu_g = 0.01 * 9.81;
	double P = -1.0, V = 3.0, A = -0.5 * mu_g;
	double q[5] = {A * A, 2.0 * A * V, V * V + 2.0 * A * P, 2.0 * V * P, P * P - 4.0 * R * R};
	double gap = 1.0 - 2.0 * R; // solve V t + A t^2 = gap (A < 0): smaller root
	double expect = (V - sqrt(V * V + 4.0 * A * gap)) / (-2.0 * A);
	assert_int_equal(pool_quartic_smallest_root_in(q, 0.0, 10.0, &t), 0);
	assert_true(fabs(t - expect) < 1e-14);
}

// --- Roots spread over many orders of magnitude (issue 9, item 10) ---

// The reported case: roots 1.0786e-5, 1.0786e-3, 3.2497e17 and 2.6425e88 (89 orders of
// magnitude). The isolation solver returned 6.52e27 for the third root: Halley's iteration from
// the far end of the bracket [2.2e17, 2.0e88], where one term of p dominates, shrinks x by a
// constant factor per step and ran out of iterations. Every root must be within docs/quartic.md's
// 1e3 kappa u of the roots of the (rounded) coefficients, and the window solver must find each.
static void test_wide_spread_reproducer(void **state) {
	(void)state;
	const double c[5] = {1, -2.642533277403521e88, 8.587567587234047e105, -9.355376507443547e102, 9.991015323651916e97};
	const long double approx[4] = {1.0786e-5L, 1.0786e-3L, 3.2497e17L, 2.6425e88L};
	long double ref[4];
	double kap[4];
	(void)tq_reference(c, 4, approx, tq_same_root, ref, kap); // (approx has 5 digits: "moved" > 1e-6)
	for (int i = 0; i < 4; ++i) {
		assert_true(fabsl(ref[i] - approx[i]) < 1e-4L * approx[i]); // polished into the intended root
		assert_true(kap[i] * tq_u <= 1e-9);                          // and it is well-conditioned
	}
	double r[4];
	int n = pool_quartic_real_roots(c, r);
	assert_int_equal(n, 4);
	for (int i = 0; i < 4; ++i)
		if (!tq_close(r[i], (double)ref[i], kap[i]))
			fail_msg("root %d: %.17g, expected %.17Lg (kappa %g)", i, r[i], ref[i], kap[i]);
	// Each root alone in a window [r / 2, 2 r], and the window [1, 1e30] (the third root).
	for (int i = 0; i < 4; ++i) {
		double t = -1.0;
		assert_int_equal(pool_quartic_smallest_root_in(c, 0.5 * (double)ref[i], 2.0 * (double)ref[i], &t), 0);
		if (!tq_close(t, (double)ref[i], kap[i]))
			fail_msg("window root %d: %.17g, expected %.17Lg", i, t, ref[i]);
	}
	double t = -1.0;
	assert_int_equal(pool_quartic_smallest_root_in(c, 1.0, 1e30, &t), 0);
	assert_true(tq_close(t, (double)ref[2], kap[2]));
}

// A random product whose roots spread over up to `span` decimal orders of magnitude: the smallest
// and largest real-root (or pair) magnitudes at the ends of a window of span orders placed at
// random inside [10^lo10, 10^hi10], the others log-uniform inside it; 4 real roots, 2 real and a
// complex pair (any argument), or two pairs; leading coefficient log-uniform in 10^[-lead10,
// lead10]. Cases with a coefficient that overflows, underflows or is subnormal, or a root outside
// the normal double range, are regenerated (out of the solver's range by definition). Returns the
// number of real roots; *near_real tells a pair within 1e-3 (relative) of the real axis.
static int tq_spread_case(int iter, double span, double lo10, double hi10, double lead10, long double real[4],
                          double c[5], bool *near_real) {
	for (;;) {
		int n_pairs = iter % 3, n_real = 4 - 2 * n_pairs, n_mags = n_real + n_pairs;
		double w = span * tq_uniform();
		double a = lo10 + (hi10 - lo10 - w) * tq_uniform(), b = a + w; // magnitudes 10^[a, b]
		long double mags[4];
		for (int i = 0; i < n_mags; ++i)
			mags[i] = powl(10.0L, a + (b - a) * tq_uniform());
		mags[0] = powl(10.0L, a);
		mags[1] = powl(10.0L, b);
		long double pairs[2][2];
		for (int i = 0; i < n_real; ++i)
			real[i] = tq_signed(1.0) * mags[i];
		for (int i = 0; i < n_pairs; ++i) {
			long double arg = 3.14159265358979323846L * tq_uniform();
			pairs[i][0] = mags[n_real + i] * cosl(arg);
			pairs[i][1] = mags[n_real + i] * sinl(arg);
		}
		*near_real = tq_near_real(n_pairs, (const long double(*)[2])pairs);
		tq_expand(tq_signed(tq_log_uniform(-lead10, lead10)), n_real, real, n_pairs, (const long double(*)[2])pairs, c);
		bool ok = true;
		for (int k = 0; k < 5; ++k)
			ok &= isfinite(c[k]) && fabs(c[k]) >= DBL_MIN;
		for (int i = 0; i < n_mags; ++i)
			ok &= mags[i] >= 0x1p53L * DBL_MIN && mags[i] <= 0.25L * DBL_MAX;
		if (ok)
			return n_real;
	}
}

// Random products with roots spread over up to 300 orders of magnitude anywhere in the double
// range (and leading coefficients 1e-20 .. 1e20), then over up to 600 orders around 1 (every
// root magnitude the double range allows, coefficients up to its limits). Reference: the known
// roots polished by Newton in long double on the rounded coefficients (tq_reference). Judged by
// docs/quartic.md's criterion: every well-conditioned case (no root with kappa u > 1e-9, no pair
// within 1e-3 of the real axis) has the right number of real roots, each within 1e3 kappa u (the
// largest error seen is about 3 kappa u), and the window solver finds each root alone in
// [r / 2, 2 r]. Without the fixes: wrong roots from about 60 orders on (the iteration running
// out), lost roots and wrong ones from about 300 orders (values in the subnormal range).
static void test_wide_spread_products(void **state) {
	(void)state;
	tq_rng = 0x452821E638D01377ULL;
	int checked = 0, skipped = 0;
	double worst = 0.0;
	for (int iter = 0; iter < 24000; ++iter) {
		bool full = iter >= 16000;
		long double real[4], ref[4];
		double c[5], kap[4];
		bool near_real;
		int n_real = full ? tq_spread_case(iter, 600.0, -300.0, 300.0, 0.0, real, c, &near_real)
		                  : tq_spread_case(iter, 300.0, -300.0, 300.0, 20.0, real, c, &near_real);
		bool ill = tq_reference(c, n_real, real, tq_same_root, ref, kap) || near_real;
		double r[4];
		int n = pool_quartic_real_roots(c, r);
		assert_true(n >= 0 && n <= 4);
		if (ill) {
			++skipped;
			continue;
		}
		++checked;
		if (n != n_real)
			fail_msg("spread case %d: %d real roots, expected %d (coeffs %.17g %.17g %.17g %.17g %.17g)", iter, n, n_real, c[0],
			         c[1], c[2], c[3], c[4]);
		for (int i = 0; i < n; ++i) {
			double e = fabs(r[i] - (double)ref[i]) / (kap[i] * tq_u * fabs((double)ref[i]));
			worst = fmax(worst, e);
			if (!tq_close(r[i], (double)ref[i], kap[i]))
				fail_msg("spread case %d: root %.17g, expected %.17Lg (kappa %g, error %.3g kappa u; coeffs %.17g %.17g %.17g "
				         "%.17g %.17g)",
				         iter, r[i], ref[i], kap[i], e, c[0], c[1], c[2], c[3], c[4]);
		}
		for (int i = 0; i < n; ++i) {
			double x = (double)ref[i], lo = x > 0.0 ? 0.5 * x : 2.0 * x, hi = x > 0.0 ? 2.0 * x : 0.5 * x;
			if ((i > 0 && r[i - 1] >= lo) || (i + 1 < n && r[i + 1] <= hi))
				continue; // another root in the window
			double t = -1.0;
			if (pool_quartic_smallest_root_in(c, lo, hi, &t) != 0 || !tq_close(t, x, kap[i]))
				fail_msg("spread case %d: window [%g, %g] root %.17g, expected %.17g", iter, lo, hi, t, x);
		}
	}
	print_message("  wide spreads: %d well-conditioned checked (worst %.3g kappa u), %d ill-conditioned skipped\n", checked,
	              worst, skipped);
	assert_true(checked > 23000);
}

// The fast path on spreads inside its range (root scale 2^-60 .. 2^60): two large real roots
// (1e10 .. 1e17) and two tiny real roots or a tiny complex pair (1e-45 .. 1e-18). The tiny roots'
// factor then has |al| below u |a|: Ferrari's al = a / 2 + e and Newton's correction for it are
// rounding noise, while the corrections pass the convergence test. Without the residual check the
// fast path gave a wrong root count (2 of 4 real roots: a "complex" factor) in 14 of these 11,996
// well-conditioned cases. Every answer it gives must have the right count and accuracy.
static void test_fast_path_wide_spread(void **state) {
	(void)state;
	tq_rng = 0xBE5466CF34E90C6CULL;
	int checked = 0, accepted = 0;
	for (int iter = 0; iter < 12000; ++iter) {
		long double real[4], pairs[1][2];
		int n_real = 0, n_pairs = 0;
		real[n_real++] = tq_signed(tq_log_uniform(10.0, 17.0));
		real[n_real++] = tq_signed(tq_log_uniform(10.0, 17.0));
		if (iter % 2 == 0) {
			real[n_real++] = tq_signed(tq_log_uniform(-45.0, -18.0));
			real[n_real++] = tq_signed(tq_log_uniform(-45.0, -18.0));
		} else {
			long double m = tq_log_uniform(-45.0, -18.0), arg = 3.14159265358979323846L * tq_uniform();
			pairs[0][0] = m * cosl(arg);
			pairs[0][1] = m * sinl(arg);
			n_pairs = 1;
		}
		bool near_real = tq_near_real(n_pairs, (const long double(*)[2])pairs);
		double c[5];
		tq_expand(tq_signed(tq_log_uniform(-3.0, 3.0)), n_real, real, n_pairs, (const long double(*)[2])pairs, c);
		long double ref[4];
		double kap[4];
		if (tq_reference(c, n_real, real, tq_unresolved_roots, ref, kap) || near_real)
			continue;
		++checked;
		double r[4];
		int n = pool_quartic_fast_real_roots(c, r);
		if (n < 0)
			continue;
		++accepted;
		if (n != n_real)
			fail_msg("fast path spread case %d: %d real roots, expected %d (coeffs %.17g %.17g %.17g %.17g %.17g)", iter, n,
			         n_real, c[0], c[1], c[2], c[3], c[4]);
		for (int i = 0; i < n; ++i)
			if (!tq_close(r[i], (double)ref[i], kap[i]))
				fail_msg("fast path spread case %d: root %.17g, expected %.17Lg (kappa %g)", iter, r[i], ref[i], kap[i]);
	}
	print_message("  fast path on wide spreads: %d of %d well-conditioned cases answered, all right\n", accepted, checked);
	assert_true(checked > 10000);
}

// Subnormal roots (|r| < DBL_MIN): a root 1e-323 .. 1e-308 with three others of moderate size
// (1e-3 .. 1e3), or the second one anywhere in 1e-300 .. 1e-8; the constant term is then
// subnormal or close to it and carries few bits, so only an absolute accuracy is promised
// (pool/quartic.h): within DBL_MIN of the root of the rounded coefficients (Newton in long double),
// for real_roots and for the window [-1e-300, 1e-300]; the count is right whenever the other roots
// are well-conditioned.
static void test_subnormal_roots(void **state) {
	(void)state;
	tq_rng = 0x3F84D5B5B5470917ULL;
	int checked = 0;
	double worst = 0.0;
	for (int iter = 0; iter < 20000; ++iter) {
		long double real[4];
		real[0] = tq_signed(1.0) * powl(10.0L, -323.0L + 15.0L * tq_uniform());
		for (int i = 1; i < 4; ++i)
			real[i] = tq_signed(tq_log_uniform(-3.0, 3.0));
		if (iter % 2)
			real[1] = tq_signed(tq_log_uniform(-300.0, -8.0));
		double c[5];
		tq_expand(tq_signed(tq_log_uniform(-3.0, 3.0)), 4, real, 0, NULL, c);
		if (c[4] == 0.0)
			continue; // the constant term underflowed: the tiny root is then exactly 0
		long double x = real[0];
		for (int it = 0; it < 60; ++it) {
			long double f = 0.0L, d = 0.0L;
			for (int k = 0; k < 5; ++k) {
				d = d * x + f;
				f = f * x + c[k];
			}
			x -= f / d;
		}
		long double ref[4];
		double kap[4];
		if (tq_reference(c, 3, real + 1, tq_same_root, ref, kap))
			continue; // the other roots ill-conditioned
		++checked;
		double r[4], t = 1.0;
		int n = pool_quartic_real_roots(c, r);
		if (n != 4)
			fail_msg("subnormal case %d: %d real roots, expected 4", iter, n);
		double best = INFINITY;
		for (int i = 0; i < n; ++i)
			best = fmin(best, fabs(r[i] - (double)x));
		worst = fmax(worst, best);
		if (!(best <= DBL_MIN))
			fail_msg("subnormal case %d: nearest root off by %g from %.17Lg", iter, best, x);
		if (pool_quartic_smallest_root_in(c, -1e-300, 1e-300, &t) != 0 || !(fabs(t - (double)x) <= DBL_MIN))
			fail_msg("subnormal case %d: window root %g, expected %.17Lg", iter, t, x);
	}
	print_message("  subnormal roots: %d cases, worst absolute error %g (DBL_MIN %g)\n", checked, worst, DBL_MIN);
	assert_true(checked > 8000); // (about half have a constant term that underflows to 0)
}

int main(void) {
	const struct CMUnitTest tests[] = {
	    cmocka_unit_test(test_public_cases),
	    cmocka_unit_test(test_equal_accelerations),
	    cmocka_unit_test(test_tiny_leading_coefficient),
	    cmocka_unit_test(test_zero_constant_term),
	    cmocka_unit_test(test_near_double_roots),
	    cmocka_unit_test(test_lower_degrees),
	    cmocka_unit_test(test_zero_constant_and_bad_input),
	    cmocka_unit_test(test_random_products),
	    cmocka_unit_test(test_clustered_products),
	    cmocka_unit_test(test_arbitrary_input),
	    cmocka_unit_test(test_grazing_ball_pairs),
	    cmocka_unit_test(test_fast_path_declines),
	    cmocka_unit_test(test_fast_path_accuracy),
	    cmocka_unit_test(test_tiny_constant_term_window),
	    cmocka_unit_test(test_smallest_root_in),
	    cmocka_unit_test(test_wide_spread_reproducer),
	    cmocka_unit_test(test_wide_spread_products),
	    cmocka_unit_test(test_fast_path_wide_spread),
	    cmocka_unit_test(test_subnormal_roots),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
