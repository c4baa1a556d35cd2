// libpool: table geometry and physical parameters (docs/physics.md, "Frame, units, defaults").
#ifndef POOL_TABLE_H
#define POOL_TABLE_H

#include "pool/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Geometry of the playing surface. Cushion noses are the lines x = 0, x = length, y = 0,
/// y = width at height cushion_height.
typedef struct pool_table_def {
	double length;         ///< m, playing surface along x
	double width;          ///< m, playing surface along y
	double cushion_height; ///< m, height of the cushion nose above the cloth
	double corner_mouth;   ///< m, corner pocket mouth measured jaw to jaw across the corner
	double side_mouth;     ///< m, side pocket mouth along its rail
} pool_table_def;

/// WPA 9 ft table (2.54 x 1.27 m, nose 0.03629 m, mouths 0.1143 / 0.127 m).
POOL_API pool_table_def pool_default_table_def(void);

/// Table preset by name: "wpa-9ft", "wpa-8ft", "wpa-7ft".
POOL_API pool_result pool_table_preset(const char *name, pool_table_def *table);

/// Physical parameters, names and defaults as in docs/physics.md.
typedef struct pool_params {
	double g;           ///< m/s^2, gravity
	double mu_slide;    ///< 1, cloth sliding friction
	double mu_roll;     ///< 1, cloth rolling resistance
	double mu_spin;     ///< 1, cloth spin friction
	double mu_ball;     ///< 1, ball-ball friction
	double e_ball;      ///< 1, ball-ball restitution
	double mu_cushion;  ///< 1, ball-cushion friction
	double e_cushion;   ///< 1, ball-cushion restitution
	double mu_table;    ///< 1, ball-cloth impact friction
	double e_table;     ///< 1, ball-cloth restitution
	double ball_radius; ///< m
	double ball_mass;   ///< kg
	double cue_mass;    ///< kg
	// Parameters of the optional models (docs/physics.md "Models"; used only when selected).
	double throw_a;      ///< 1, ball_ball_friction "alciatore": mu(v) = throw_a + throw_b exp(-throw_c v)
	double throw_b;      ///< 1, see throw_a
	double throw_c;      ///< s/m, see throw_a
	double cue_end_mass; ///< kg, squirt "endmass": the cue's effective end mass (Alciatore TP A.31)
	double e_cushion_mathavan;  ///< 1, cushion "mathavan2010": Stronge's restitution at the nose (Mathavan 2010's fit)
	double mu_cushion_mathavan; ///< 1, cushion "mathavan2010": ball-nose sliding friction (Mathavan 2010's fit)
} pool_params;

/// docs/physics.md defaults.
POOL_API pool_params pool_default_params(void);

/// Horizontal distance (m) from a nose line at which a ball of radius R on the cloth touches it:
/// sqrt(R^2 - (h - R)^2) (docs/validation.md 8). The contact lines of the playing area are this far
/// inside the nose lines.
POOL_API double pool_table_contact_distance(const pool_table_def *table, double ball_radius);

/// Checks ranges (positive sizes, non-negative friction, restitution in [0, 1], finite);
/// the message names the field, e.g. "params.mu_slide: must be >= 0".
POOL_API pool_result pool_table_def_validate(const pool_table_def *table, pool_error *error);

/// Checks ranges of every parameter; the message names the field.
POOL_API pool_result pool_params_validate(const pool_params *params, pool_error *error);

#ifdef __cplusplus
}
#endif

#endif
