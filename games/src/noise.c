// Gaussian noise on the cue parameters (pool/noise.h): presets, specs and a counter-based normal
// generator (splitmix64 mixing, Box-Muller), so every deviate is a pure function of its seed,
// sample and index.
#include "pool/noise.h"

#include "rules.h"

#define BAD POOL_ERR_INVALID_ARGUMENT

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define POOL_NOISE_PI 3.14159265358979323846
#define POOL_NOISE_DEG (POOL_NOISE_PI / 180.0)

const char *pool_noise_preset_names(void) { return "none, fastfiz"; }

pool_result pool_noise_preset(const char *name, pool_noise *noise) {
	if (!name || !noise)
		return POOL_ERR_INVALID_ARGUMENT;
	if (strcmp(name, "none") == 0) {
		*noise = (pool_noise){0.0, 0.0, 0.0, 0.0, 0.0};
		return POOL_OK;
	}
	if (strcmp(name, "fastfiz") == 0) {
		// The noise of the Computational Pool tournaments (FastFiz): sd of a and b 0.5 mm, theta
		// 0.1 deg, phi 0.125 deg, speed 0.075 m/s.
		*noise = (pool_noise){.speed = 0.075, .phi = 0.125 * POOL_NOISE_DEG, .theta = 0.1 * POOL_NOISE_DEG,
		                      .a = 0.0005, .b = 0.0005};
		return POOL_OK;
	}
	return POOL_ERR_INVALID_ARGUMENT;
}

// The spec echoed in a message: printable ASCII only (a terminal must not act on the input).
static const char *printable(char *text) {
	for (char *c = text; *c; ++c)
		if (*c < 0x20 || *c > 0x7e)
			*c = '?';
	return text;
}

pool_result pool_noise_validate(const pool_noise *noise, pool_error *error) {
	if (!noise)
		return pool_game_fail(error, BAD, "noise: missing");
	const double v[5] = {noise->speed, noise->phi, noise->theta, noise->a, noise->b};
	static const char *const names[5] = {"speed", "phi", "theta", "a", "b"};
	for (int k = 0; k < 5; ++k)
		if (!(isfinite(v[k]) && v[k] >= 0.0))
			return pool_game_fail(error, BAD, "noise: %s: the standard deviation must be finite and >= 0", names[k]);
	if (error)
		error->message[0] = '\0';
	return POOL_OK;
}

pool_result pool_noise_parse(const char *spec, pool_noise *noise, pool_error *error) {
	if (!spec || !noise)
		return pool_game_fail(error, BAD, "noise: missing");
	if (pool_noise_preset(spec, noise) == POOL_OK)
		return error ? (error->message[0] = '\0', POOL_OK) : POOL_OK;
	pool_noise out = {0.0, 0.0, 0.0, 0.0, 0.0};
	static const char *const names[5] = {"speed", "phi", "theta", "a", "b"};
	bool seen[5] = {false, false, false, false, false};
	const char *p = spec;
	if (!*p)
		return pool_game_fail(error, BAD, "noise: empty (a preset: %s, or NAME=SD pairs such as phi=0.2,speed=0.05)",
		            pool_noise_preset_names());
	for (;;) {
		const char *end = strchr(p, ',');
		const size_t n = end ? (size_t)(end - p) : strlen(p);
		char item[64];
		memcpy(item, p, n < sizeof item ? n : sizeof item - 1);
		item[n < sizeof item ? n : sizeof item - 1] = '\0';
		if (n == 0 || n >= sizeof item)
			return pool_game_fail(error, BAD, "noise: '%s' is not a preset (%s) or NAME=SD", printable(item),
			                      pool_noise_preset_names());
		char *eq = strchr(item, '=');
		if (!eq)
			return pool_game_fail(error, BAD, "noise: '%s' is not a preset (%s) or NAME=SD", printable(item),
			                      pool_noise_preset_names());
		*eq = '\0';
		int k = -1;
		for (int j = 0; j < 5; ++j)
			if (strcmp(item, names[j]) == 0)
				k = j;
		if (k < 0)
			return pool_game_fail(error, BAD, "noise: '%s': unknown parameter (speed, phi, theta, a, b)", printable(item));
		if (seen[k])
			return pool_game_fail(error, BAD, "noise: %s is given twice", names[k]);
		seen[k] = true;
		char *stop = NULL;
		errno = 0;
		const double sd = strtod(eq + 1, &stop);
		if (errno || stop == eq + 1 || *stop || !isfinite(sd) || sd < 0.0 || sd > 1e9)
			return pool_game_fail(error, BAD, "noise: %s: '%s' is not a standard deviation >= 0", names[k],
			                      printable(eq + 1));
		double *field[5] = {&out.speed, &out.phi, &out.theta, &out.a, &out.b};
		*field[k] = k == 1 || k == 2 ? sd * POOL_NOISE_DEG : sd;
		if (!end)
			break;
		p = end + 1;
	}
	*noise = out;
	if (error)
		error->message[0] = '\0';
	return POOL_OK;
}

// splitmix64's finaliser (Steele, Lea and Flood 2014): a bijection of 64-bit words whose outputs
// pass BigCrush for consecutive inputs.
static uint64_t mix(uint64_t z) {
	z += 0x9E3779B97F4A7C15ull;
	z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
	z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
	return z ^ (z >> 31);
}

double pool_noise_normal(uint64_t seed, uint64_t sample, uint32_t k) {
	// One pair of uniforms per pair of deviates (Box-Muller gives two normals from two uniforms).
	const uint64_t pair = k >> 1;
	const uint64_t h = mix(mix(mix(seed) ^ sample) ^ pair);
	const uint64_t g = mix(h);
	// u1 in (0, 1] (log(u1) finite), u2 in [0, 1), each from the top 53 bits.
	const double u1 = ((double)(h >> 11) + 1.0) * (1.0 / 9007199254740992.0);
	const double u2 = (double)(g >> 11) * (1.0 / 9007199254740992.0);
	const double r = sqrt(-2.0 * log(u1));
	const double angle = 2.0 * POOL_NOISE_PI * u2;
	return (k & 1u) ? r * sin(angle) : r * cos(angle);
}

static double noisy(double nominal, double sd, uint64_t seed, uint64_t sample, uint32_t k) {
	return sd > 0.0 ? nominal + sd * pool_noise_normal(seed, sample, k) : nominal;
}

pool_strike pool_noise_apply(const pool_noise *noise, uint64_t seed, uint64_t sample, const pool_strike *nominal) {
	pool_strike s = *nominal;
	if (!noise)
		return s;
	s.speed = noisy(nominal->speed, noise->speed, seed, sample, 0);
	s.phi = noisy(nominal->phi, noise->phi, seed, sample, 1);
	s.theta = fabs(noisy(nominal->theta, noise->theta, seed, sample, 2));
	s.a = noisy(nominal->a, noise->a, seed, sample, 3);
	s.b = noisy(nominal->b, noise->b, seed, sample, 4);
	return s;
}
