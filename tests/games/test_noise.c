// Cue noise (pool/noise.h): the presets' values, specs and their messages, the deviates'
// distribution (moments and a Kolmogorov-Smirnov bound for N(0, 1)), independence of the five
// parameters, reproducibility, and the strike the noise makes.
#include "game_fixture.h"

#include <stdlib.h>
#include <string.h>

#include "pool/noise.h"

static void test_presets(void **state) {
	(void)state;
	pool_noise n;
	assert_int_equal(pool_noise_preset("fastfiz", &n), POOL_OK);
	// The Computational Pool tournaments' values (docs/interfaces.md "Shot planning").
	assert_true(n.speed == 0.075 && n.a == 0.0005 && n.b == 0.0005);
	assert_true(fabs(n.phi - 0.125 * FIX_DEG) < 1e-18 && fabs(n.theta - 0.1 * FIX_DEG) < 1e-18);
	assert_int_equal(pool_noise_preset("none", &n), POOL_OK);
	assert_true(n.speed == 0 && n.phi == 0 && n.theta == 0 && n.a == 0 && n.b == 0);
	assert_int_equal(pool_noise_preset("gaussian", &n), POOL_ERR_INVALID_ARGUMENT);
}

static void test_specs(void **state) {
	(void)state;
	pool_noise n;
	pool_error err;
	assert_int_equal(pool_noise_parse("phi=0.2,speed=0.05", &n, &err), POOL_OK);
	assert_true(n.speed == 0.05 && fabs(n.phi - 0.2 * FIX_DEG) < 1e-18 && n.theta == 0 && n.a == 0);
	assert_int_equal(pool_noise_parse("fastfiz", &n, &err), POOL_OK);
	assert_true(n.speed == 0.075);
	static const struct {
		const char *spec, *message;
	} bad[] = {
		{"", "noise: empty (a preset: none, fastfiz, or NAME=SD pairs such as phi=0.2,speed=0.05)"},
		{"spin=1", "noise: 'spin': unknown parameter (speed, phi, theta, a, b)"},
		{"phi=-1", "noise: phi: '-1' is not a standard deviation >= 0"},
		{"phi=x", "noise: phi: 'x' is not a standard deviation >= 0"},
		{"phi=1,phi=2", "noise: phi is given twice"},
		{"fast", "noise: 'fast' is not a preset (none, fastfiz) or NAME=SD"},
		{"a=nan", "noise: a: 'nan' is not a standard deviation >= 0"},
		{"b=1,", "noise: '' is not a preset (none, fastfiz) or NAME=SD"},
		{"\x1b[2J=1", "noise: '?[2J': unknown parameter (speed, phi, theta, a, b)"},
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
		assert_int_equal(pool_noise_parse(bad[i].spec, &n, &err), POOL_ERR_INVALID_ARGUMENT);
		if (strcmp(err.message, bad[i].message) != 0)
			fail_msg("spec \"%s\": \"%s\", expected \"%s\"", bad[i].spec, err.message, bad[i].message);
	}
	n = (pool_noise){.speed = -1};
	assert_int_equal(pool_noise_validate(&n, &err), POOL_ERR_INVALID_ARGUMENT);
	assert_string_equal(err.message, "noise: speed: the standard deviation must be finite and >= 0");
}

static int compare_double(const void *a, const void *b) {
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

// 200,000 deviates: mean, variance, skewness and kurtosis of N(0, 1) within 5 standard errors,
// and the Kolmogorov-Smirnov distance below its 0.1 % critical value (1.95 / sqrt(N)).
static void test_deviates_are_standard_normal(void **state) {
	(void)state;
	enum { N = 200000 };
	double *z = malloc(N * sizeof *z);
	assert_non_null(z);
	double s1 = 0, s2 = 0, s3 = 0, s4 = 0;
	for (int i = 0; i < N; ++i) {
		z[i] = pool_noise_normal(7, (uint64_t)(i / 5), (uint32_t)(i % 5));
		s1 += z[i], s2 += z[i] * z[i], s3 += z[i] * z[i] * z[i], s4 += z[i] * z[i] * z[i] * z[i];
	}
	const double mean = s1 / N, var = s2 / N, skew = s3 / N, kurt = s4 / N;
	assert_true(fabs(mean) < 5.0 * sqrt(1.0 / N));
	assert_true(fabs(var - 1.0) < 5.0 * sqrt(2.0 / N));
	assert_true(fabs(skew) < 5.0 * sqrt(15.0 / N));
	assert_true(fabs(kurt - 3.0) < 5.0 * sqrt(96.0 / N));
	qsort(z, N, sizeof *z, compare_double);
	double d = 0.0;
	for (int i = 0; i < N; ++i) {
		const double cdf = 0.5 * erfc(-z[i] / sqrt(2.0));
		d = fmax(d, fmax(fabs(cdf - (double)i / N), fabs(cdf - (double)(i + 1) / N)));
	}
	print_message("%d deviates: mean %.4f, variance %.4f, skewness %.4f, kurtosis %.4f, KS distance %.5f\n", N,
	              mean, var, skew, kurt, d);
	assert_true(d < 1.95 / sqrt((double)N));
	free(z);
}

// The five deviates of a sample, and neighbouring samples, are uncorrelated; the same seed and
// sample give the same value, another seed another one.
static void test_deviates_are_independent_and_reproducible(void **state) {
	(void)state;
	enum { N = 100000 };
	double c[5][5] = {{0}};
	double lag = 0.0;
	for (int i = 0; i < N; ++i) {
		double z[5];
		for (int k = 0; k < 5; ++k)
			z[k] = pool_noise_normal(1, (uint64_t)i, (uint32_t)k);
		for (int j = 0; j < 5; ++j)
			for (int k = 0; k < 5; ++k)
				c[j][k] += z[j] * z[k] / N;
		lag += z[0] * pool_noise_normal(1, (uint64_t)i + 1, 0) / N;
	}
	for (int j = 0; j < 5; ++j)
		for (int k = 0; k < j; ++k)
			assert_true(fabs(c[j][k]) < 5.0 / sqrt((double)N));
	assert_true(fabs(lag) < 5.0 / sqrt((double)N));
	assert_true(pool_noise_normal(3, 41, 2) == pool_noise_normal(3, 41, 2));
	assert_true(pool_noise_normal(3, 41, 2) != pool_noise_normal(4, 41, 2));
}

static void test_apply(void **state) {
	(void)state;
	const pool_strike nominal = {.speed = 2.0, .phi = 0.5, .theta = 0.0, .a = 0.001, .b = -0.002};
	pool_noise none;
	pool_noise_preset("none", &none);
	pool_strike s = pool_noise_apply(&none, 1, 0, &nominal);
	assert_memory_equal(&s, &nominal, sizeof s);
	pool_noise ff;
	pool_noise_preset("fastfiz", &ff);
	s = pool_noise_apply(&ff, 9, 17, &nominal);
	assert_true(s.speed == nominal.speed + ff.speed * pool_noise_normal(9, 17, 0));
	assert_true(s.phi == nominal.phi + ff.phi * pool_noise_normal(9, 17, 1));
	assert_true(s.theta == fabs(ff.theta * pool_noise_normal(9, 17, 2))); // folded: never below level
	assert_true(s.a == nominal.a + ff.a * pool_noise_normal(9, 17, 3));
	assert_true(s.b == nominal.b + ff.b * pool_noise_normal(9, 17, 4));
	// Only the noisy parameter moves.
	pool_noise only_speed = {.speed = 0.1};
	s = pool_noise_apply(&only_speed, 9, 17, &nominal);
	assert_true(s.phi == nominal.phi && s.a == nominal.a && s.b == nominal.b && s.speed != nominal.speed);
}

int main(void) {
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_presets),
		cmocka_unit_test(test_specs),
		cmocka_unit_test(test_deviates_are_standard_normal),
		cmocka_unit_test(test_deviates_are_independent_and_reproducible),
		cmocka_unit_test(test_apply),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
