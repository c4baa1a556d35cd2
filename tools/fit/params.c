// The parameters pool-fit can free, how --fit names them, and where their values go.
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "fit.h"

#define DEG (3.14159265358979323846 / 180.0)

// Ranges are the library's own (docs/physics.md), narrowed where the library's limit is a
// singularity: a tip offset of 0.9 R is already far beyond a miscue (about 0.5 R), and an
// elevation of 86 degrees is a vertical masse.
const fit_param_info fit_shot_params[FIT_SHOT_PARAMS] = {
	// The cue speed's limit: well above a break's 14 m/s, and its ball speed (up to 1.6 times the
	// cue's) below the library's POOL_MAX_SPEED. Inside the vector: the launch speed (fit.h).
	[FIT_SPEED] = {"speed", "m/s", 1.0, 1e-3, 50.0, false},
	[FIT_PHI] = {"phi", "deg", 0.01, -1e9, 1e9, true},
	[FIT_THETA] = {"theta", "deg", 0.01, 0.0, 86.0 * DEG, true},
	[FIT_A] = {"a", "m", 1e-3, -1.0, 1.0, false}, // and a^2 + b^2 <= (FIT_TIP_LIMIT R)^2
	[FIT_B] = {"b", "m", 1e-3, -1.0, 1.0, false},
	[FIT_T0] = {"t0", "s", 1e-3, -1e9, 1e9, false},
};

const fit_param_info fit_table_params[FIT_TABLE_PARAMS] = {
	[FIT_MU_SLIDE] = {"mu_slide", "1", 0.01, 0.0, 10.0, false},
	[FIT_MU_ROLL] = {"mu_roll", "1", 1e-3, 0.0, 10.0, false},
	[FIT_MU_SPIN] = {"mu_spin", "1", 1e-3, 0.0, 10.0, false},
	[FIT_MU_BALL] = {"mu_ball", "1", 0.01, 0.0, 10.0, false},
	[FIT_E_BALL] = {"e_ball", "1", 0.01, 0.0, 1.0, false},
	[FIT_MU_CUSHION] = {"mu_cushion", "1", 0.01, 0.0, 10.0, false},
	[FIT_E_CUSHION] = {"e_cushion", "1", 0.01, 0.0, 1.0, false},
	[FIT_MU_TABLE] = {"mu_table", "1", 0.01, 0.0, 10.0, false},
	[FIT_E_TABLE] = {"e_table", "1", 0.01, 0.0, 1.0, false},
	[FIT_THROW_A] = {"throw_a", "1", 1e-3, 0.0, 10.0, false},
	[FIT_THROW_B] = {"throw_b", "1", 0.01, 0.0, 10.0, false},
	[FIT_THROW_C] = {"throw_c", "s/m", 0.1, 0.0, 100.0, false},
	[FIT_CUE_END_MASS] = {"cue_end_mass", "kg", 1e-3, 1e-4, 10.0, false},
	[FIT_E_CUSHION_MATHAVAN] = {"e_cushion_mathavan", "1", 0.01, 0.0, 1.0, false},
	[FIT_MU_CUSHION_MATHAVAN] = {"mu_cushion_mathavan", "1", 0.01, 0.0, 10.0, false},
};

double *fit_table_field(pool_params *p, int k) {
	switch (k) {
	case FIT_MU_SLIDE: return &p->mu_slide;
	case FIT_MU_ROLL: return &p->mu_roll;
	case FIT_MU_SPIN: return &p->mu_spin;
	case FIT_MU_BALL: return &p->mu_ball;
	case FIT_E_BALL: return &p->e_ball;
	case FIT_MU_CUSHION: return &p->mu_cushion;
	case FIT_E_CUSHION: return &p->e_cushion;
	case FIT_MU_TABLE: return &p->mu_table;
	case FIT_E_TABLE: return &p->e_table;
	case FIT_THROW_A: return &p->throw_a;
	case FIT_THROW_B: return &p->throw_b;
	case FIT_THROW_C: return &p->throw_c;
	case FIT_E_CUSHION_MATHAVAN: return &p->e_cushion_mathavan;
	case FIT_MU_CUSHION_MATHAVAN: return &p->mu_cushion_mathavan;
	default: return &p->cue_end_mass;
	}
}

const char *fit_table_param_needs(int k, const pool_sim_def *def) {
	const pool_models *m = &def->models;
	switch (k) {
	case FIT_MU_BALL:
		return m->ball_ball_friction == POOL_BALL_FRICTION_CONSTANT ? NULL : "\"ball_ball_friction\": \"constant\"";
	case FIT_THROW_A:
	case FIT_THROW_B:
	case FIT_THROW_C:
		return m->ball_ball_friction == POOL_BALL_FRICTION_ALCIATORE ? NULL : "\"ball_ball_friction\": \"alciatore\"";
	case FIT_MU_CUSHION:
	case FIT_E_CUSHION: // Petit's law: every rail impact under it, and a ball in flight under any
		return m->cushion == POOL_CUSHION_PETIT || def->airborne ? NULL : "\"cushion\": \"petit\"";
	case FIT_E_CUSHION_MATHAVAN:
	case FIT_MU_CUSHION_MATHAVAN:
		return m->cushion == POOL_CUSHION_MATHAVAN2010 ? NULL : "\"cushion\": \"mathavan2010\"";
	case FIT_CUE_END_MASS:
		return m->squirt == POOL_SQUIRT_ENDMASS ? NULL : "\"squirt\": \"endmass\"";
	default:
		return NULL;
	}
}

double fit_shown(const fit_param_info *info, double value) { return info->degrees ? value / DEG : value; }

// ---- --fit ------------------------------------------------------------------------------------

typedef struct fit_group {
	const char *name;
	const char *members;
} fit_group;

// "strike" leaves theta out: on the cloth an elevation acts like a little draw and a little less
// speed (docs/commands.md "pool-fit"), so it is free only when asked for.
static const fit_group groups[] = {
	{"strike", "speed,phi,a,b"},
	{"cue", "speed,phi,theta,a,b"},
	{"cloth", "mu_slide,mu_roll,mu_spin"},
};

/// Marks one name (a parameter or a group); 0 or a usage error.
static int mark(bool *free_shot, bool *free_table, const char *name, size_t n, int depth) {
	for (size_t g = 0; depth == 0 && g < sizeof groups / sizeof groups[0]; ++g)
		if (strlen(groups[g].name) == n && strncmp(groups[g].name, name, n) == 0) {
			for (const char *m = groups[g].members;;) {
				const char *comma = strchr(m, ',');
				size_t len = comma ? (size_t)(comma - m) : strlen(m);
				mark(free_shot, free_table, m, len, 1);
				if (!comma)
					return 0;
				m = comma + 1;
			}
		}
	for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
		if (strlen(fit_shot_params[k].name) == n && strncmp(fit_shot_params[k].name, name, n) == 0) {
			free_shot[k] = true;
			return 0;
		}
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		if (strlen(fit_table_params[k].name) == n && strncmp(fit_table_params[k].name, name, n) == 0) {
			free_table[k] = true;
			return 0;
		}
	char shown[128];
	snprintf(shown, sizeof shown, "%.*s", (int)(n < 100 ? n : 100), name);
	return pool_cli_usage_error(FIT_PROGRAM, "--fit: '%s' is not a parameter (speed, phi, theta, a, b, t0, "
	                            "mu_slide, mu_roll, mu_spin, mu_ball, e_ball, mu_cushion, e_cushion, mu_table, "
	                            "e_table, throw_a, throw_b, throw_c, cue_end_mass, e_cushion_mathavan, mu_cushion_mathavan) or a "
	                            "group (strike, cue, cloth)",
	                            pool_cli_arg(shown));
}

int fit_parse_spec(const char *spec, bool free_shot[FIT_SHOT_PARAMS], bool free_table[FIT_TABLE_PARAMS]) {
	memset(free_shot, 0, FIT_SHOT_PARAMS * sizeof *free_shot);
	memset(free_table, 0, FIT_TABLE_PARAMS * sizeof *free_table);
	if (!spec[0])
		return pool_cli_usage_error(FIT_PROGRAM, "%s", "--fit: empty list of parameters");
	for (const char *p = spec;;) {
		const char *comma = strchr(p, ',');
		size_t n = comma ? (size_t)(comma - p) : strlen(p);
		if (n == 0)
			return pool_cli_usage_error(FIT_PROGRAM, "--fit: '%s' has an empty name", pool_cli_arg(spec));
		int status = mark(free_shot, free_table, p, n, 0);
		if (status)
			return status;
		if (!comma)
			return 0;
		p = comma + 1;
	}
}

int fit_problem_setup(fit_problem *pb, const char *spec) {
	int status = fit_parse_spec(spec, pb->free_shot, pb->free_table);
	if (status)
		return status;
	// A parameter the shot's laws never read does nothing: its column of the Jacobian would be zero.
	for (int s = 0; s < pb->shot_count; ++s)
		for (int k = 0; k < FIT_TABLE_PARAMS; ++k) {
			const char *needs = pb->free_table[k] ? fit_table_param_needs(k, &pb->shots[s].scenario.def) : NULL;
			if (needs)
				return pool_cli_usage_error(FIT_PROGRAM, "--fit: %s is not used by the laws of %s: it needs "
				                            "\"models\": {%s}", fit_table_params[k].name,
				                            pool_cli_arg(pb->shots[s].scenario_path), needs);
		}
	pb->table_free = 0;
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		pb->table_free += pb->free_table[k];
	pb->shot_free = 0;
	for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
		pb->shot_free += pb->free_shot[k];
	pb->p = pb->table_free + pb->shot_count * pb->shot_free;
	pb->n_obs = 0;
	for (int s = 0; s < pb->shot_count; ++s)
		pb->n_obs += 2 * (size_t)pb->shots[s].obs_count;
	pb->n = pb->n_obs + (size_t)pb->p;
	pb->base_params = pb->shots[0].scenario.def.params;
	pb->horizon = INFINITY;
	if ((size_t)pb->p >= pb->n_obs)
		return pool_cli_usage_error(FIT_PROGRAM, "--fit: %d parameters from %zu coordinates: the tracks need "
		                            "more observations than there are parameters", pb->p, pb->n_obs);
	return 0;
}

const fit_param_info *fit_param_of(const fit_problem *pb, int j, int *shot, int *index) {
	if (j < pb->table_free) {
		int k = -1;
		for (int seen = -1; seen < j;)
			seen += pb->free_table[++k];
		*shot = -1;
		*index = k;
		return &fit_table_params[k];
	}
	j -= pb->table_free;
	*shot = j / pb->shot_free;
	int k = -1;
	for (int seen = -1; seen < j % pb->shot_free;)
		seen += pb->free_shot[++k];
	*index = k;
	return &fit_shot_params[k];
}

static double clamp(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

double fit_launch_gain(const pool_params *params, double theta, double a, double b) {
	pool_strike unit = {1.0, 0.0, theta, a, b};
	pool_vec3 vel, omega;
	if (pool_strike_velocities(params, &unit, &vel, &omega, NULL) != POOL_OK)
		return NAN; // outside the clamped ranges only
	return sqrt(vel.x * vel.x + vel.y * vel.y + vel.z * vel.z);
}

/// The shot's values under x as the vector holds them (the launch speed in FIT_SPEED when the
/// speed is free), the fixed ones from the start.
static void internal_values(const fit_problem *pb, const double *x, int shot, double v[FIT_SHOT_PARAMS]) {
	memcpy(v, pb->shots[shot].start, sizeof pb->shots[shot].start);
	int j = pb->table_free + shot * pb->shot_free;
	for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
		if (pb->free_shot[k])
			v[k] = x[j++];
}

/// Clamped to the ranges, a and b radially.
static void clamp_values(const pool_params *params, double v[FIT_SHOT_PARAMS]) {
	for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
		v[k] = clamp(v[k], fit_shot_params[k].lo, fit_shot_params[k].hi);
	double limit = FIT_TIP_LIMIT * params->ball_radius, r = hypot(v[FIT_A], v[FIT_B]);
	if (r > limit) {
		v[FIT_A] *= limit / r;
		v[FIT_B] *= limit / r;
	}
}

void fit_start_vector(const fit_problem *pb, double *x) {
	int j = 0;
	pool_params start = pb->base_params;
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		if (pb->free_table[k])
			x[j++] = *fit_table_field(&start, k);
	for (int s = 0; s < pb->shot_count; ++s) {
		double v[FIT_SHOT_PARAMS];
		memcpy(v, pb->shots[s].start, sizeof v);
		clamp_values(&pb->shots[s].scenario.def.params, v);
		if (!pb->cue_speed)
			v[FIT_SPEED] *= fit_launch_gain(&pb->shots[s].scenario.def.params, v[FIT_THETA], v[FIT_A], v[FIT_B]);
		for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
			if (pb->free_shot[k])
				x[j++] = v[k];
	}
}

void fit_shot_values(const fit_problem *pb, const double *x, int shot, double v[FIT_SHOT_PARAMS]) {
	const pool_params *params = &pb->shots[shot].scenario.def.params;
	internal_values(pb, x, shot, v);
	clamp_values(params, v);
	if (pb->free_shot[FIT_SPEED] && !pb->cue_speed)
		v[FIT_SPEED] /= fit_launch_gain(params, v[FIT_THETA], v[FIT_A], v[FIT_B]);
}

void fit_table_values(const fit_problem *pb, const double *x, pool_params *params) {
	int j = 0;
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		if (pb->free_table[k]) {
			*fit_table_field(params, k) = clamp(x[j++], fit_table_params[k].lo, fit_table_params[k].hi);
		}
}

void fit_clamp(const fit_problem *pb, const double *x, double *out) {
	memmove(out, x, (size_t)pb->p * sizeof *x);
	int j = 0;
	for (int k = 0; k < FIT_TABLE_PARAMS; ++k)
		if (pb->free_table[k]) {
			out[j] = clamp(out[j], fit_table_params[k].lo, fit_table_params[k].hi);
			++j;
		}
	for (int s = 0; s < pb->shot_count; ++s) {
		double v[FIT_SHOT_PARAMS];
		internal_values(pb, out, s, v);
		clamp_values(&pb->shots[s].scenario.def.params, v);
		for (int k = 0; k < FIT_SHOT_PARAMS; ++k)
			if (pb->free_shot[k])
				out[j++] = v[k];
	}
}

// The struck ball's first observations: it moves in a straight line until it meets something, so
// its direction is that of its displacement, and its speed follows from the sliding law
// d(t) = v0 t - mu_slide g t^2 / 2 (docs/physics.md), fitted over the first frames.
#define GUESS_WINDOW 0.1   // s after the strike: before a typical first collision
#define GUESS_MIN_MOVE 0.01 // m: less is not a direction
bool fit_guess_from_tracks(const fit_shot *shot, const pool_params *params, double *phi, double *speed) {
	int index = -1;
	for (int k = 0; k < shot->scenario.ball_count; ++k)
		if (shot->scenario.balls[k].id == shot->ball)
			index = k;
	if (index < 0)
		return false;
	const pool_vec3 p0 = shot->scenario.balls[index].pos;
	double t0 = shot->start[FIT_T0], stt = 0.0, std = 0.0, dx = 0.0, dy = 0.0, decel = params->mu_slide * params->g;
	int used = 0;
	for (long i = 0; i < shot->obs_count; ++i) {
		const fit_observation *o = &shot->obs[i];
		double t = o->t - t0;
		if (o->ball != index || t <= 0.0)
			continue;
		if (t > GUESS_WINDOW)
			break;
		double ex = o->x - p0.x, ey = o->y - p0.y, d = sqrt(ex * ex + ey * ey);
		stt += t * t;
		std += t * (d + 0.5 * decel * t * t);
		dx = ex;
		dy = ey;
		++used;
	}
	if (used < 2 || sqrt(dx * dx + dy * dy) < GUESS_MIN_MOVE)
		return false;
	*phi = atan2(dy, dx);
	// A centre strike gives the ball v0 = 2 V / (1 + m / M) (docs/physics.md "Cue strike").
	*speed = std / stt * (1.0 + params->ball_mass / params->cue_mass) / 2.0;
	return true;
}
