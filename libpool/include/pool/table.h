// libpool: table geometry and physical parameters (docs/physics.md, "Frame, units, defaults").
#ifndef POOL_TABLE_H
#define POOL_TABLE_H

#include "pool/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Pocket model of a table (docs/physics.md "Table geometry"); values are stable.
typedef enum pool_pockets_model {
	POOL_POCKETS_MOUTH_LINES = 0, ///< "mouth_lines": the 2012 thesis model, pockets are gaps in four nose lines
	POOL_POCKETS_JAWS = 1,        ///< "jaws": nose segments, facings, rounded jaws and holes (the default)
	POOL_POCKETS_NONE = 2,        ///< "none": four cushions and no pocket (carom)
} pool_pockets_model;

/// "mouth_lines", "jaws", "none" ("unknown" out of range).
POOL_API const char *pool_pockets_model_name(pool_pockets_model model);

/// The model of that name, or -1 when the name is unknown (or NULL).
POOL_API int pool_pockets_model_from_name(const char *name);

/// Geometry of the playing surface. Cushion noses run along the lines x = 0, x = length, y = 0,
/// y = width at height cushion_height; with POOL_POCKETS_JAWS each pocket ends them in facings at
/// the cut angle, rounded into jaws, with a hole behind a shelf (docs/physics.md "Table geometry").
/// A struct filled by hand with only the first five fields (the rest zero) is the thesis model.
typedef struct pool_table_def {
	double length;         ///< m, playing surface along x
	double width;          ///< m, playing surface along y
	double cushion_height; ///< m, height of the cushion nose above the cloth
	double corner_mouth;   ///< m, corner pocket mouth measured across the corner between the virtual corners
	double side_mouth;     ///< m, side pocket mouth along its rail between the virtual corners
	pool_pockets_model pockets; ///< pocket model; the fields below are read with POOL_POCKETS_JAWS only
	double corner_cut_angle;    ///< rad, inside the cushion between nose and facing at a corner pocket
	double side_cut_angle;      ///< rad, the same at a side pocket
	double corner_jaw_radius;   ///< m, horizontal radius rounding nose into facing at a corner pocket (>= 0)
	double side_jaw_radius;     ///< m, the same at a side pocket
	double corner_shelf;        ///< m, from the mouth line back to the nearest edge of a corner hole
	double side_shelf;          ///< m, the same at a side pocket
	double corner_hole_radius;  ///< m, radius of a corner pocket's hole in the slate
	double side_hole_radius;    ///< m, the same at a side pocket
} pool_table_def;

/// WPA 9 ft table (2.54 x 1.27 m, nose 0.03629 m, mouths 0.1143 / 0.127 m), pockets "jaws".
POOL_API pool_table_def pool_default_table_def(void);

/// Table preset by name: "wpa-9ft", "wpa-8ft", "wpa-7ft", "snooker", "carom" (docs/physics.md
/// "Table geometry" gives their numbers and sources). Snooker and carom tables are played with
/// their own balls and cloth: pool_params_preset.
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

/// The balls and cloth a table preset is played with: the defaults for the WPA tables, snooker
/// balls (52.5 mm) and cloth for "snooker", carom balls (61.5 mm) and cloth for "carom".
POOL_API pool_result pool_params_preset(const char *name, pool_params *params);

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
