// Table presets, default parameters and their validation (docs/physics.md defaults table).
#include "pool/table.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "error.h"

#define POOL_DEG (3.14159265358979323846 / 180.0)
#define POOL_INCH 0.0254

// A WPA table of the given playing surface (docs/physics.md "Table geometry" names the sources):
// nose 63.5 % of the ball's diameter, mouths at the WPA minimum (4.5 in, 5 in), cut angles
// 142 and 104 degrees, jaw radii of a measured table (pooltool's 7 ft table: 20.95 mm corners,
// 7.95 mm sides), shelves and holes of Alciatore's TP 3.5 / 3.6 pockets (1.125 in and 2.75 in
// corners, 0.1875 in and 3 in sides).
static pool_table_def wpa(double length, double width) {
	pool_table_def t;
	memset(&t, 0, sizeof t);
	t.length = length;
	t.width = width;
	t.cushion_height = 0.03629;
	t.corner_mouth = 0.1143;
	t.side_mouth = 0.127;
	t.pockets = POOL_POCKETS_JAWS;
	t.corner_cut_angle = 142.0 * POOL_DEG;
	t.side_cut_angle = 104.0 * POOL_DEG;
	t.corner_jaw_radius = 0.02095;
	t.side_jaw_radius = 0.00795;
	t.corner_shelf = 1.125 * POOL_INCH;
	t.side_shelf = 0.1875 * POOL_INCH;
	t.corner_hole_radius = 2.75 * POOL_INCH;
	t.side_hole_radius = 3.0 * POOL_INCH;
	return t;
}

// WPBSA playing area 3569 x 1778 mm. The pocket templates are not public: mouths, cut angles,
// jaws and holes are chosen from published descriptions (docs/physics.md), scaled to the 52.5 mm
// ball; the nose at 63.5 % of the ball's diameter, as on pool tables.
static pool_table_def snooker(void) {
	pool_table_def t = wpa(3.569, 1.778);
	t.cushion_height = 0.635 * 0.0525;
	t.corner_mouth = 0.086;
	t.side_mouth = 0.085;
	t.corner_cut_angle = 142.0 * POOL_DEG;
	t.side_cut_angle = 102.0 * POOL_DEG;
	t.corner_jaw_radius = 0.05;
	t.side_jaw_radius = 0.03;
	t.corner_shelf = 0.03;
	t.side_shelf = 0.02;
	t.corner_hole_radius = 0.05;
	t.side_hole_radius = 0.05;
	return t;
}

// UMB carom table: playing area 2840 x 1420 mm, nose 37 mm, no pockets.
static pool_table_def carom(void) {
	pool_table_def t;
	memset(&t, 0, sizeof t);
	t.length = 2.84;
	t.width = 1.42;
	t.cushion_height = 0.037;
	t.pockets = POOL_POCKETS_NONE;
	return t;
}

pool_table_def pool_default_table_def(void) { return wpa(2.54, 1.27); }

pool_result pool_table_preset(const char *name, pool_table_def *table) {
	if (!name || !table)
		return POOL_ERR_INVALID_ARGUMENT;
	if (strcmp(name, "wpa-9ft") == 0)
		*table = wpa(2.54, 1.27);
	else if (strcmp(name, "wpa-8ft") == 0)
		*table = wpa(92 * POOL_INCH, 46 * POOL_INCH);
	else if (strcmp(name, "wpa-7ft") == 0)
		*table = wpa(78 * POOL_INCH, 39 * POOL_INCH);
	else if (strcmp(name, "snooker") == 0)
		*table = snooker();
	else if (strcmp(name, "carom") == 0)
		*table = carom();
	else
		return POOL_ERR_UNKNOWN_PRESET;
	return POOL_OK;
}

static const char *const pockets_names[] = {"mouth_lines", "jaws", "none"};

const char *pool_pockets_model_name(pool_pockets_model model) {
	return model >= POOL_POCKETS_MOUTH_LINES && model <= POOL_POCKETS_NONE ? pockets_names[model] : "unknown";
}

int pool_pockets_model_from_name(const char *name) {
	for (int k = 0; name && k < 3; ++k)
		if (strcmp(name, pockets_names[k]) == 0)
			return k;
	return -1;
}

pool_result pool_params_preset(const char *name, pool_params *params) {
	pool_table_def t;
	if (!params)
		return POOL_ERR_INVALID_ARGUMENT;
	const pool_result r = pool_table_preset(name, &t);
	if (r)
		return r;
	*params = pool_default_params();
	if (strcmp(name, "snooker") == 0) {
		// WPBSA balls: 52.5 mm, about 142 g (a set within 3 g). The snooker cloth Mathavan et al.
		// measured (docs/validation.md): rolling 0.124-0.126 m/s^2 (mu_roll 0.0127), sliding
		// 1.75-2.40 m/s^2 (mu_slide 0.2 in the middle).
		params->ball_radius = 0.02625;
		params->ball_mass = 0.142;
		params->mu_roll = 0.0127;
	} else if (strcmp(name, "carom") == 0) {
		// UMB balls: 61 to 61.5 mm, 205 to 220 g. No published measurement of heated carom cloth
		// was found: the pool cloth's friction stays.
		params->ball_radius = 0.03075;
		params->ball_mass = 0.21;
	}
	return POOL_OK;
}

pool_params pool_default_params(void) {
	pool_params p;
	p.g = 9.81;
	p.mu_slide = 0.2;
	p.mu_roll = 0.01;
	p.mu_spin = 0.0127;
	p.mu_ball = 0.06;
	p.e_ball = 0.95;
	p.mu_cushion = 0.2;
	p.e_cushion = 0.85;
	p.mu_table = 0.2;
	p.e_table = 0.5;
	p.ball_radius = 0.028575;
	p.ball_mass = 0.17;
	p.cue_mass = 0.54;
	// Alciatore TP A.14's fit of Marlow's ball-ball friction against slip speed.
	p.throw_a = 9.951e-3;
	p.throw_b = 0.108;
	p.throw_c = 1.088;
	// A standard maple shaft: with a 0.17 kg ball a half-radius offset squirts 2.5 degrees
	// (TP A.31's formula), within the 2-3 degrees Alciatore's cue test machine reports for
	// standard shafts at that offset.
	p.cue_end_mass = 0.008;
	// Mathavan, Jackson & Parkin 2010 fitted their model to their measured rebounds with these two
	// (a rolling ball keeps 0.91 of its speed at right angles on their snooker cushion); the law
	// reads them rather than e_cushion and mu_cushion, the effective values of Petit's law,
	// which leaves the cloth's part of the impact out (docs/physics.md "Models").
	p.e_cushion_mathavan = 0.98;
	p.mu_cushion_mathavan = 0.14;
	return p;
}

// Range checks shared by the validators; each names the field in the message.
static pool_result positive(double x, const char *field, pool_error *error) {
	if (!isfinite(x))
		return pool_error_set(error, POOL_ERR_NON_FINITE, "%s: must be finite", field);
	if (!(x > 0.0))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "%s: must be > 0", field);
	return POOL_OK;
}

static pool_result non_negative(double x, const char *field, pool_error *error) {
	if (!isfinite(x))
		return pool_error_set(error, POOL_ERR_NON_FINITE, "%s: must be finite", field);
	if (!(x >= 0.0))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "%s: must be >= 0", field);
	return POOL_OK;
}

static pool_result unit_interval(double x, const char *field, pool_error *error) {
	if (!isfinite(x))
		return pool_error_set(error, POOL_ERR_NON_FINITE, "%s: must be finite", field);
	if (!(x >= 0.0 && x <= 1.0))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "%s: must be in [0, 1]", field);
	return POOL_OK;
}

pool_result pool_table_def_validate(const pool_table_def *t, pool_error *error) {
	pool_result r;
	if (!t)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "table: missing");
	if ((r = positive(t->length, "table.length", error)) ||
	    (r = positive(t->width, "table.width", error)) ||
	    (r = positive(t->cushion_height, "table.cushion_height", error)))
		return r;
	if (!(t->pockets >= POOL_POCKETS_MOUTH_LINES && t->pockets <= POOL_POCKETS_NONE))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "table.pockets: unknown pocket model %d", (int)t->pockets);
	if (t->pockets == POOL_POCKETS_NONE)
		return pool_error_ok(error); // no mouth: the pocket fields are not read
	if ((r = non_negative(t->corner_mouth, "table.corner_mouth", error)) ||
	    (r = non_negative(t->side_mouth, "table.side_mouth", error)))
		return r;
	if (t->side_mouth >= t->length)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "table.side_mouth: must be < table.length");
	if (t->corner_mouth / sqrt(2.0) >= 0.5 * fmin(t->length, t->width))
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "table.corner_mouth: must be < width / sqrt(2) and length / sqrt(2)");
	if (t->pockets != POOL_POCKETS_JAWS)
		return pool_error_ok(error);
	// The jaws' geometry; whether it can be built (jaws tangent to nose and facing, facings
	// reaching the holes, mouths and throats wider than a ball) is checked with the ball
	// (pool_sim_create: table_shape.c).
	const struct {
		double value, lo, hi;
		const char *field;
	} angles[] = {{t->corner_cut_angle, 45.0 * POOL_DEG, 180.0 * POOL_DEG, "table.corner_cut_angle"},
	              {t->side_cut_angle, 0.0, 180.0 * POOL_DEG, "table.side_cut_angle"}};
	for (int k = 0; k < 2; ++k) {
		if (!isfinite(angles[k].value))
			return pool_error_set(error, POOL_ERR_NON_FINITE, "%s: must be finite", angles[k].field);
		if (!(angles[k].value > angles[k].lo && angles[k].value < angles[k].hi))
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "%s: must be between %g and %g degrees", angles[k].field,
			                      angles[k].lo / POOL_DEG, angles[k].hi / POOL_DEG);
	}
	if ((r = non_negative(t->corner_jaw_radius, "table.corner_jaw_radius", error)) ||
	    (r = non_negative(t->side_jaw_radius, "table.side_jaw_radius", error)) ||
	    (r = non_negative(t->corner_shelf, "table.corner_shelf", error)) ||
	    (r = non_negative(t->side_shelf, "table.side_shelf", error)) ||
	    (r = positive(t->corner_hole_radius, "table.corner_hole_radius", error)) ||
	    (r = positive(t->side_hole_radius, "table.side_hole_radius", error)))
		return r;
	return pool_error_ok(error);
}

// 0.4 m R^2 and 2 m R are normal numbers (neither underflows nor overflows).
static bool normal_mass_radius(double m, double R) {
	const double inertia = 0.4 * m * R * R, mass_radius = 2.0 * m * R;
	return inertia >= DBL_MIN && inertia <= DBL_MAX && mass_radius >= DBL_MIN && mass_radius <= DBL_MAX;
}

pool_result pool_params_validate(const pool_params *p, pool_error *error) {
	pool_result r;
	if (!p)
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT, "params: missing");
	if ((r = positive(p->g, "params.g", error)) ||
	    (r = non_negative(p->mu_slide, "params.mu_slide", error)) ||
	    (r = non_negative(p->mu_roll, "params.mu_roll", error)) ||
	    (r = non_negative(p->mu_spin, "params.mu_spin", error)) ||
	    (r = non_negative(p->mu_ball, "params.mu_ball", error)) ||
	    (r = unit_interval(p->e_ball, "params.e_ball", error)) ||
	    (r = non_negative(p->mu_cushion, "params.mu_cushion", error)) ||
	    (r = unit_interval(p->e_cushion, "params.e_cushion", error)) ||
	    (r = non_negative(p->mu_table, "params.mu_table", error)) ||
	    (r = unit_interval(p->e_table, "params.e_table", error)) ||
	    (r = positive(p->ball_radius, "params.ball_radius", error)) ||
	    (r = positive(p->ball_mass, "params.ball_mass", error)) ||
	    (r = positive(p->cue_mass, "params.cue_mass", error)) ||
	    (r = non_negative(p->throw_a, "params.throw_a", error)) ||
	    (r = non_negative(p->throw_b, "params.throw_b", error)) ||
	    (r = non_negative(p->throw_c, "params.throw_c", error)) ||
	    (r = positive(p->cue_end_mass, "params.cue_end_mass", error)) ||
	    (r = unit_interval(p->e_cushion_mathavan, "params.e_cushion_mathavan", error)) ||
	    (r = non_negative(p->mu_cushion_mathavan, "params.mu_cushion_mathavan", error)))
		return r;
	// The strike and collision laws divide by m R^2 and 2 m R: when those underflow (a subnormal
	// mass such as 4.9e-324 kg) or overflow, spins come out NaN (found by test_scenario_fuzz).
	if (!normal_mass_radius(p->ball_mass, p->ball_radius)) {
		// Name the factor out of range on its own: if the radius fails even with the default
		// mass, the radius; else the mass (alone or with the radius).
		if (!normal_mass_radius(pool_default_params().ball_mass, p->ball_radius))
			return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
			                      "params.ball_radius: %g m is out of range (0.4 m R^2 or 2 m R is not a normal number)",
			                      p->ball_radius);
		return pool_error_set(error, POOL_ERR_INVALID_ARGUMENT,
		                      "params.ball_mass: %g kg with ball_radius %g m is out of range "
		                      "(0.4 m R^2 or 2 m R is not a normal number)",
		                      p->ball_mass, p->ball_radius);
	}
	return pool_error_ok(error);
}
