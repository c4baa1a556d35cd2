// pool-sensitivity's pieces (tools/pool_sensitivity.c): the noise and its samples (noise.c, GSL's
// generator), the named model sets (model_sets.c), the run of every sample on all cores
// (run.c, through pool-batch's shot, batch_shot.h), the statistics of the clouds (stats.c, GSL's
// statistics) and the outputs (report.c: text, JSON, CSV; svg.c: the picture).
#ifndef POOL_TOOLS_SENSITIVITY_STUDY_H
#define POOL_TOOLS_SENSITIVITY_STUDY_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pool/batch.h"
#include "pool/pool.h"
#include "pool/scenario.h"

#define SENS_PROGRAM "pool-sensitivity"

/// The cue parameters, in pool-batch's order and units (m/s, degrees, degrees, m, m).
enum { SENS_SPEED, SENS_PHI, SENS_THETA, SENS_A, SENS_B, SENS_CUE_COUNT };
extern const char *const sens_cue_names[SENS_CUE_COUNT];

/// The pockets in pool_pocket order (sw, se, nw, ne, s, n).
#define SENS_POCKET_COUNT 6

/// What is noisy: standard deviations around the scenario's strike and ball positions.
typedef struct sens_noise {
	double cue_sd[SENS_CUE_COUNT]; ///< of speed (m/s), phi, theta (degrees), a, b (m), as given
	pool_noise cue;                ///< the same in pool_noise's units (radians), as drawn
	double position_sd;            ///< m, of x and of y of every ball in position_index
	int position_count;            ///< balls whose positions are noisy
	int *position_index;           ///< their indices in the layout (owned)
} sens_noise;

/// N samples, drawn before any shot runs (so they do not depend on the threads).
typedef struct sens_samples {
	long n;
	int position_count;
	pool_batch_strike *strikes; ///< n strikes (degrees, as pool-batch reads them)
	double *positions;          ///< n * position_count * 2: x, y of each noisy ball (absolute)
} sens_samples;

/// The generator's name ("pool_noise_normal": libpool games' counter-based deviates).
const char *sens_rng_name(void);

/// Draws n samples with seed (1 .. 2^32 - 1). Sample i takes pool_noise_normal(seed, i, k): k = 0
/// to 4 for speed, phi, theta, a, b (its strike is pool_batch_noisy's: value = nominal + sd * z,
/// exactly nominal when sd is 0, theta folded to |theta|), then k = 5 + 2j and 6 + 2j for x and
/// y of noisy ball j. Returns 0, or -1 when out of memory.
int sens_draw_samples(const pool_scenario *layout, const pool_batch_strike *nominal,
                      const sens_noise *noise, long n, unsigned long seed, sens_samples *out);
void sens_samples_free(sens_samples *s);

/// A named set of models: the scenario's definition with some laws switched.
typedef struct sens_model_set {
	char name[96];
	pool_sim_def def;
} sens_model_set;

/// The names that may be joined with '+', for messages ("default, spin-blind, ...").
const char *sens_model_set_names(void);

/// Builds set `name` from the scenario's definition: "default" (the scenario as written), or
/// components joined by '+': "spin-blind" (params mu_ball = mu_cushion = 0), the library's model
/// set "thesis" (the 2012 work's laws), any model name of pool_sim_def.models ("mathavan2010",
/// "alciatore", "endmass", "petit", "constant", "none"). Returns 0, or -1 with the message in err.
int sens_model_set_parse(const char *name, const pool_sim_def *base, sens_model_set *out,
                         char *err, size_t err_size);

/// Per sample, what became of the tracked balls under one model set.
typedef struct sens_run {
	long n;
	int tracked_count;
	int8_t *stop;    ///< n: pool_stop_reason; -1 the library refused the sample, -2 it failed
	char **error;    ///< n: NULL or the refusal's message (pool-batch's wording), malloc'd
	double *pos;     ///< n * tracked * 2: final x, y
	int8_t *state;   ///< n * tracked: final pool_motion (-1 when refused)
	int8_t *pocket;  ///< n * tracked: pool_pocket the ball fell into, -1 for none
	int8_t *legal;   ///< n: with a game, 1 when the shot was legal, 0 when not, -1 refused (else NULL)
	int8_t *outcome; ///< n: with a game, the pool_game_outcome, -1 refused (else NULL)
	long refused;    ///< samples the library refused
	long failed;     ///< samples the library failed to simulate (internal errors)
} sens_run;

/// Runs every sample under def on `threads` threads (each with its own reused simulation);
/// the results depend only on the samples, not on the threads. progress: a progress line on
/// standard error for runs over 1 s. Returns 0, or -1 when out of memory.
int sens_run_samples(const pool_scenario *layout, const pool_sim_def *def, const sens_noise *noise,
                     const sens_samples *samples, const int *tracked, int tracked_count,
                     long threads, bool progress, const char *label, sens_run *out);
void sens_run_free(sens_run *r);

/// A proportion with its Wilson score interval.
typedef struct sens_proportion {
	long count, n;
	double p, low, high;
} sens_proportion;

/// With a game: how the samples of one model set fared under the rules.
typedef struct sens_game_stats {
	long samples;               ///< samples simulated
	sens_proportion legal;      ///< the shot was legal
	sens_proportion legal_pot;  ///< legal, and the shooter keeps the table or wins (a legal pot, a point)
	sens_proportion outcomes[4]; ///< continue, turn_over, win, loss
} sens_game_stats;

/// The game statistics of run r.
sens_game_stats sens_game_stats_compute(const sens_run *r);

/// The cloud of one tracked ball's final positions under one model set.
typedef struct sens_cloud {
	int32_t id;
	long samples;   ///< samples simulated (not refused)
	long on_table;  ///< of those, ball still on the table at the end: the cloud
	bool has_mean;  ///< on_table >= 1
	bool has_cov;   ///< on_table >= 2
	double mean[2];
	double cov[3];  ///< xx, xy, yy (sample covariance, n - 1)
	double ellipse_major, ellipse_minor; ///< m, semi-axes of the 95 % ellipse
	double ellipse_angle_deg;            ///< major axis from +x, counter-clockwise, (-90, 90]
	sens_proportion pocketed, off_table;
	sens_proportion pockets[SENS_POCKET_COUNT];
} sens_cloud;

/// Confidence level of the ellipse and the intervals, and its constants.
#define SENS_CONFIDENCE 0.95
/// Chi-square quantile of 2 degrees of freedom at SENS_CONFIDENCE: -2 ln(1 - 0.95). The points
/// of a bivariate normal with Mahalanobis distance^2 <= this are 95 % of it.
double sens_chi2_2dof(void);
/// The standard normal quantile z of the two-sided SENS_CONFIDENCE interval (1.95996...).
double sens_z(void);

/// Wilson score interval of count successes in n trials at SENS_CONFIDENCE.
sens_proportion sens_wilson(long count, long n);

/// The statistics of tracked ball k of run r. Returns 0, or -1 when out of memory.
int sens_cloud_compute(const sens_run *r, int k, int32_t id, sens_cloud *out);

/// The most model sets --models compares.
#define SENS_MAX_SETS 2

/// A whole study: inputs, runs and statistics, as the outputs read it.
typedef struct sens_study {
	const char *scenario_path;
	const pool_scenario *layout;
	pool_batch_strike nominal;  ///< the scenario's strike (degrees)
	sens_noise noise;
	unsigned long seed;
	sens_samples samples;
	int tracked_count;
	int *tracked;               ///< layout indices of the balls whose clouds are studied
	int set_count;
	sens_model_set sets[SENS_MAX_SETS];
	sens_run runs[SENS_MAX_SETS];
	sens_cloud *clouds;         ///< set_count * tracked_count, set-major
} sens_study;

/// The study's outputs, malloc'd NUL-terminated text (NULL when out of memory): the summary
/// printed on standard output, the JSON document (libpool-sensitivity/1), the summary CSV (one
/// row per model set and tracked ball), the per-sample CSV and the SVG picture.
char *sens_report_text(const sens_study *s);
char *sens_report_json(const sens_study *s);
char *sens_report_csv(const sens_study *s);
char *sens_samples_csv(const sens_study *s);
char *sens_svg(const sens_study *s);

/// Distance between the means of tracked ball k under the first and the second model set
/// (NaN when either has no mean).
double sens_mean_distance(const sens_study *s, int k);

#endif
