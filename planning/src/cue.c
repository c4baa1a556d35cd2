// Can the cue stick reach the ball? It lies along the strike's direction, behind the cue ball,
// rising at the elevation theta; other balls and the rail must stay clear of it.
#include <math.h>

#include "aim_internal.h"

// The cue: 58 in long, its shaft tapering from a 13 mm tip to a 30 mm butt (common playing cues;
// WPA sets no dimensions). A ball farther behind the cue ball than the cue's length is out of its
// way (the player's body is not modelled).
#define AIM_CUE_LENGTH 1.47
#define AIM_CUE_TIP_RADIUS 0.0065
#define AIM_CUE_BUTT_RADIUS 0.015
// m above the cloth: the top of the cushion and rail the cue must pass over. WPA fixes only the
// nose (63.5 % of the ball's diameter, 36 mm); a K-66 cushion rises about 9 mm behind its nose to
// the rail. Assumed, not measured: it decides how close to a rail a ball may be shot level.
#define AIM_RAIL_TOP 0.045
// A "level" strike (theta = 0 in the strike's model) is played with the butt raised a little over
// the rail: the cue's line is taken at this elevation when the strike's is lower.
#define AIM_NATURAL_ELEVATION (4.0 * AIM_DEG)
// The elevations tried when a level cue is blocked: a player raises the butt to reach over a
// ball or the rail (planar shots then curve a little: the simulation sees it); beyond the last
// the shot is a masse and not searched.
static const double elevations_deg[] = {5.0, 10.0, 15.0, 20.0, 25.0, 30.0};
#define AIM_MAX_ELEVATION (30.0 * AIM_DEG)

static double shaft_radius(double s) {
	return AIM_CUE_TIP_RADIUS + (AIM_CUE_BUTT_RADIUS - AIM_CUE_TIP_RADIUS) * s / AIM_CUE_LENGTH;
}

/// Whether the cue at (phi, theta) with tip offsets (a, b) clears the rail and every other ball.
static bool clear(const aim_search *s, double phi, double theta, double a, double b) {
	const aim_table *t = &s->table;
	const pool_ball_state *cue = &s->def->balls[s->cue];
	const double R = t->radius;
	// The cue's axis passes through the tip's contact point Q = a r + b k - c j (docs/physics.md
	// "Cue strike") and runs back along -d = -cos(theta) j + sin(theta) k.
	const double jx = cos(phi), jy = sin(phi), c = sqrt(fmax(R * R - a * a - b * b, 0.0));
	const double rx = jy, ry = -jx; // r = j x k
	const double qx = cue->pos.x + a * rx - c * jx, qy = cue->pos.y + a * ry - c * jy, qz = R + b;
	theta = fmax(theta, AIM_NATURAL_ELEVATION);
	const double dx = -cos(theta) * jx, dy = -cos(theta) * jy, dz = sin(theta);
	// The rail: where the cue's shadow leaves the rectangle of the nose lines, its underside must
	// be above the rail's top (it only rises from there).
	double exit = INFINITY;
	if (dx < 0.0)
		exit = fmin(exit, -qx / dx);
	if (dx > 0.0)
		exit = fmin(exit, (t->length - qx) / dx);
	if (dy < 0.0)
		exit = fmin(exit, -qy / dy);
	if (dy > 0.0)
		exit = fmin(exit, (t->width - qy) / dy);
	if (exit < AIM_CUE_LENGTH && qz + exit * dz - shaft_radius(exit) < AIM_RAIL_TOP)
		return false;
	for (int k = 0; k < s->def->ball_count; ++k) {
		if (k == s->cue)
			continue;
		const pool_vec3 *p = &s->def->balls[k].pos;
		const double px = p->x - qx, py = p->y - qy, pz = R - qz;
		double along = px * dx + py * dy + pz * dz; // |d| = 1
		along = fmin(fmax(along, 0.0), AIM_CUE_LENGTH);
		const double ex = px - along * dx, ey = py - along * dy, ez = pz - along * dz;
		if (sqrt(ex * ex + ey * ey + ez * ez) < R + shaft_radius(along))
			return false;
	}
	return true;
}

double aim_cue_elevation(const aim_search *s, double phi, double a, double b, double theta_min) {
	if (clear(s, phi, theta_min, a, b))
		return theta_min;
	for (size_t k = 0; k < sizeof elevations_deg / sizeof elevations_deg[0]; ++k) {
		double theta = elevations_deg[k] * AIM_DEG;
		if (theta > theta_min && theta <= AIM_MAX_ELEVATION && clear(s, phi, theta, a, b))
			return theta;
	}
	return -1.0;
}
