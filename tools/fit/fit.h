// pool-fit's pieces (tools/pool_fit.c): observed tracks (tracks.c), the parameters that can be
// fitted and how they enter a shot (params.c), the simulated residuals and their Jacobian
// (residuals.c), the nonlinear least squares with GSL (solve.c), and the outputs (report.c: JSON
// and text; svg.c: observed against fitted tracks). docs/commands.md "pool-fit".
#ifndef POOL_TOOLS_FIT_H
#define POOL_TOOLS_FIT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pool/pool.h"
#include "pool/scenario.h"

#define FIT_PROGRAM "pool-fit"

// ---- observations -----------------------------------------------------------------------------

/// One observed position: ball (layout index) at time t (s from the strike, as the tracks say).
typedef struct fit_observation {
	double t;
	int ball;   ///< index in the shot's layout
	double x, y;
	long line;  ///< line of the tracks file, for messages
} fit_observation;

/// Reads a tracks CSV (header naming the columns t, id, x, y in any order; other columns are
/// ignored; a row whose x or y is empty is a frame where the ball was not seen). Every id must be
/// a ball of layout. The observations come out sorted by time (stable). Returns 0, or
/// POOL_EXIT_BAD_INPUT / POOL_EXIT_INTERNAL with the message ("FILE: line 3, column x: ...") in err.
int fit_tracks_parse(const char *file, const char *text, size_t length, const pool_scenario *layout,
                     fit_observation **out, long *count, char *err, size_t err_size);

/// What a camera at rate frames/s recording for duration s sees of a shot that has run: each
/// ball on the table at each frame t = k / rate, its x and y plus sigma * normal(ctx) each (a
/// pocketed ball is no longer seen). Observations in frame order, balls in the sim's order
/// (line: the row's line in a CSV with a header). Returns 0, or -1 when out of memory.
int fit_camera(const pool_sim *sim, double rate, double duration, double sigma, double (*normal)(void *ctx),
               void *ctx, fit_observation **out, long *count);

// ---- parameters -------------------------------------------------------------------------------

/// Parameters of each shot: the five cue parameters and the tracks' time offset t0 (the strike
/// happened at tracks time t0).
enum { FIT_SPEED, FIT_PHI, FIT_THETA, FIT_A, FIT_B, FIT_T0, FIT_SHOT_PARAMS };

/// Table parameters shared by all shots (pool_params fields, docs/physics.md).
enum {
	FIT_MU_SLIDE, FIT_MU_ROLL, FIT_MU_SPIN, FIT_MU_BALL, FIT_E_BALL, FIT_MU_CUSHION, FIT_E_CUSHION,
	FIT_MU_TABLE, FIT_E_TABLE, FIT_THROW_A, FIT_THROW_B, FIT_THROW_C, FIT_CUE_END_MASS, FIT_E_CUSHION_MATHAVAN,
	FIT_MU_CUSHION_MATHAVAN, FIT_TABLE_PARAMS
};

/// What a parameter is: its name, unit as written (degrees for phi and theta), and the range the
/// library accepts.
typedef struct fit_param_info {
	const char *name;
	const char *unit;  ///< as written in outputs
	double scale;      ///< a typical change of the parameter (internal units), for difference steps
	double lo, hi;     ///< admissible values (internal units)
	bool degrees;      ///< radians inside, degrees outside
} fit_param_info;

extern const fit_param_info fit_shot_params[FIT_SHOT_PARAMS];
extern const fit_param_info fit_table_params[FIT_TABLE_PARAMS];

/// The value of table parameter k in params (and a pointer to it).
double *fit_table_field(pool_params *params, int k);

/// NULL when table parameter k acts in a simulation under def's models, else the model it needs
/// written as a scenario selects it ("\"cushion\": \"petit\""): a parameter its laws never read
/// would leave a column of zeros in the Jacobian.
const char *fit_table_param_needs(int k, const pool_sim_def *def);

/// One observed shot: its scenario (layout, table, models, starting strike) and tracks.
typedef struct fit_shot {
	const char *scenario_path;
	const char *tracks_path;
	pool_scenario scenario;  ///< its strike (if any) is a starting guess; the struck ball is strike_ball
	int32_t ball;            ///< id of the struck ball
	fit_observation *obs;    ///< sorted by time
	long obs_count;
	double start[FIT_SHOT_PARAMS]; ///< starting values (internal units)
} fit_shot;

/// The position noise of the tracks (m per coordinate), from the second differences of each
/// ball's positions over evenly spaced frames (robust: their median); NAN with too few.
double fit_track_noise(const fit_shot *shots, int count);

/// How each step of the least squares solves its linear system (least_squares.c).
typedef enum fit_linear_kind {
	FIT_LINEAR_AUTO = 0, ///< dense up to FIT_DENSE_MAX_PARAMS parameters, else normal equations by blocks
	FIT_LINEAR_DENSE,    ///< QR of the dense n x p Jacobian (gsl_multifit_nlinear)
	FIT_LINEAR_BLOCKS,   ///< Cholesky of J^T J built shot by shot (gsl_multilarge_nlinear)
} fit_linear_kind;

/// Parameters up to which FIT_LINEAR_AUTO factorises the dense Jacobian: one shot's strike and a
/// few table parameters, where QR's robustness costs nothing.
#define FIT_DENSE_MAX_PARAMS 16

/// The whole problem: the shots, which parameters are free, the parameter vector's layout.
/// x = [free table parameters..., shot 0's free parameters..., shot 1's ...].
typedef struct fit_problem {
	fit_shot *shots;
	int shot_count;
	bool free_shot[FIT_SHOT_PARAMS];
	bool free_table[FIT_TABLE_PARAMS];
	int table_free;            ///< number of free table parameters
	int shot_free;             ///< number of free parameters per shot
	int p;                     ///< table_free + shot_count * shot_free
	pool_params base_params;   ///< the first shot's params: the fixed table parameters and the start
	size_t n_obs;              ///< residual rows from observations (2 per observation)
	size_t n;                  ///< n_obs + one penalty row per shot and per free table parameter
	long threads;              ///< worker threads for the simulations
	const double *anchor;      ///< where the current minimisation started (p), for the tether of
	                           ///< fit_penalty_rows; NULL for none
	bool cue_speed;            ///< the vector's speed slots hold the cue speed, not the launch speed
	                           ///< (the profile intervals, profile.c)
	double horizon;            ///< s of tracks time: later observations count for nothing (their rows
	                           ///< are 0) and the shots are simulated only so far; INFINITY for all
	fit_linear_kind linear;    ///< how each step's linear system is solved
} fit_problem;

/// Parses --fit into the free sets alone; 0 or a usage error (printed).
int fit_parse_spec(const char *spec, bool free_shot[FIT_SHOT_PARAMS], bool free_table[FIT_TABLE_PARAMS]);

/// Parses --fit (names and groups, comma-separated: "strike" = speed,phi,a,b; "cloth" =
/// mu_slide,mu_roll,mu_spin; or any parameter name) into the free sets and sizes the problem.
/// Model parameters need their model in every shot. Returns 0 or a usage error (printed).
int fit_problem_setup(fit_problem *pb, const char *spec);

/// Which parameter x[j] is: its info, and the shot it belongs to (-1 for a table parameter).
const fit_param_info *fit_param_of(const fit_problem *pb, int j, int *shot, int *index);

/// The largest tip offset sqrt(a^2 + b^2) tried, in ball radii: far beyond a miscue (about
/// 0.5 R), short of the library's limit R where the impulse's formula is singular.
#define FIT_TIP_LIMIT 0.9

/// When the speed is free, the vector holds the ball's launch speed F/m instead of the cue's
/// (docs/physics.md "Cue strike"): the tracks show the launch speed, which the cue speed gives
/// only through the tip offsets (F = 2 m V / (1 + m/M + 5/(2 R^2) |Q x d|^2)), so a fit in cue
/// speed would have to follow a curved valley of equal launch speeds whenever a or b moves, and
/// at a = 0 a change of a's sign is invisible to first order. The launch speed per m/s of cue
/// speed under these tip offsets and elevation.
double fit_launch_gain(const pool_params *params, double theta, double a, double b);

/// The starting vector (internal units).
void fit_start_vector(const fit_problem *pb, double *x);

/// The shot's strike (cue speed, angles in radians, offsets) and t0 under x, clamped to the
/// ranges; the table parameters under x, clamped, into *params (the others untouched).
void fit_shot_values(const fit_problem *pb, const double *x, int shot, double values[FIT_SHOT_PARAMS]);
void fit_table_values(const fit_problem *pb, const double *x, pool_params *params);

/// The first guess of a shot's phi and speed from the struck ball's first observed positions (a
/// straight line through them before anything can have hit it); false when there are too few.
bool fit_guess_from_tracks(const fit_shot *shot, const pool_params *params, double *phi, double *speed);

// ---- synthetic shots (trials and benchmarks) ---------------------------------------------------

#define FIT_SYNTHETIC_BALLS 3

/// What made a synthetic shot.
typedef struct fit_synthetic {
	pool_ball_state balls[FIT_SYNTHETIC_BALLS]; ///< the layout (the shot's scenario points here)
	pool_strike strike;
	pool_params params;
} fit_synthetic;

/// True values of the free table parameters, each uniform in its measured range
/// (docs/validation.md); the others stay as *p has them.
void fit_random_table(uint64_t seed, const bool *free_table, pool_params *p);

/// Shot `index` of `seed`: the cue ball, an object ball 0.3 to 1.2 m away hit with a cut of up to
/// 70 % of a full ball's offset, a third ball anywhere, a strike of 1 to 3 m/s with tip offsets
/// within 0.4 R, on a table with the parameters `table` and the laws `models`; recorded at rate frames/s with noise of
/// sd sigma; its start the default table, the direction half a degree and the speed 10 % off (at
/// random), no spin. *truth must outlive *shot. Returns 0, or -1 (the library failed).
int fit_synthetic_shot(uint64_t seed, long index, const pool_params *table, const pool_models *models,
                       double rate, double sigma, fit_synthetic *truth, fit_shot *shot);

// ---- residuals --------------------------------------------------------------------------------

/// A simulation per worker, reused for every evaluation it runs.
typedef struct fit_worker {
	pool_sim *sim;
	pool_ball_state *states; ///< room for the largest layout
} fit_worker;

/// What one simulated shot gave: the residual rows of its observations (2 per observation:
/// simulated minus observed x and y, m) and its signature, a hash of its collision sequence
/// (ball-ball, cushion, pocket and off-table events with their balls, rails and pockets).
/// Returns POOL_OK, or the library's error (a refused strike is impossible: x is clamped to the
/// admissible ranges first).
pool_result fit_shot_residuals(const fit_problem *pb, int shot, const double *x, fit_worker *w,
                               double *rows, uint64_t *signature);

/// The penalty rows (n - n_obs of them): how far x lies outside the admissible ranges, scaled so
/// that leaving them costs more than any track could gain, zero inside; plus a faint tether to
/// pb->anchor (residuals.c, FIT_RIDGE).
void fit_penalty_rows(const fit_problem *pb, const double *x, double *rows);

/// x clamped into the admissible ranges (speed > 0, 0 <= theta <= 86 deg,
/// a^2 + b^2 <= (FIT_TIP_LIMIT R)^2, friction >= 0, restitution in [0, 1]); out may be x.
void fit_clamp(const fit_problem *pb, const double *x, double *clamped);

/// Every residual row of x (all shots on the workers, then the penalties).
pool_result fit_residuals(const fit_problem *pb, const double *x, fit_worker *workers, double *f,
                          uint64_t *signatures);

/// The Jacobian by blocks. A shot's residual rows move only with the table's free parameters and
/// the shot's own strike, so row i of shot s is stored as width = table_free + shot_free numbers:
/// the table's columns, then shot s's (fit_jacobian_column). The penalty rows (one per parameter)
/// are p x p. Storage and every product are linear in the number of shots; a dense n x p matrix
/// would make each step's factorisation cost n p^2, quadratic in them (docs/planning.md).
typedef struct fit_jacobian_blocks {
	double *rows;    ///< n_obs x width, row-major
	double *penalty; ///< p x p, row-major
} fit_jacobian_blocks;

/// The numbers stored per residual row (table_free + shot_free), and the block column of x[j].
int fit_jacobian_width(const fit_problem *pb);
int fit_jacobian_column(const fit_problem *pb, int j);

/// The Jacobian at x by differences that do not cross an event change: a central difference where
/// both sides keep the collision sequence of x (signatures, from fit_residuals at x, which also
/// gave the rows f), one-sided where only one does, and a smaller step where neither does. Each
/// parameter moves only the shots it belongs to (a table parameter: all of them), so only those
/// are simulated again: 2 (table_free + shot_free) simulations per shot.
pool_result fit_jacobian(const fit_problem *pb, const double *x, const double *f, const uint64_t *signatures,
                         fit_worker *workers, fit_jacobian_blocks *J);

/// The dense Jacobian (n x p, row-major) of the blocks.
void fit_jacobian_dense(const fit_problem *pb, const fit_jacobian_blocks *J, double *dense);

/// The normal equations of the blocks: JTJ = J^T J (p x p, row-major, both triangles) and
/// g = J^T f (p), in n_obs width^2 operations. Either output may be NULL; scratch: room for p
/// indices.
void fit_jacobian_normal(const fit_problem *pb, const fit_jacobian_blocks *J, const double *f, double *JTJ,
                         double *g, size_t *scratch);

/// Creates count workers; frees them.
int fit_workers_create(const fit_problem *pb, long count, fit_worker **out);
void fit_workers_free(fit_worker *w, long count);

// ---- the fit ----------------------------------------------------------------------------------

/// One fitted parameter.
typedef struct fit_estimate {
	double value, initial, se, ci_low, ci_high; ///< internal units
} fit_estimate;

/// The solution.
typedef struct fit_solution {
	int p;
	double *x;            ///< fitted vector
	fit_estimate *est;    ///< p estimates
	double *correlation;  ///< p x p
	double rss;           ///< m^2, sum of squared track residuals
	double rms;           ///< m, sqrt(rss / observations rows)
	double sigma;         ///< m, the position noise used for the errors (given, or sqrt(rss / dof))
	bool sigma_given;     ///< --sigma gave it
	long dof;             ///< residual rows - p
	int iterations;       ///< of the best start
	int starts;           ///< starts tried
	int best_start;
	int alternatives;     ///< other minima within the 95 % likelihood ratio of the best, which the
	                      ///< intervals span
	bool converged;
	bool profiled;        ///< the intervals come from the profile of the cost (else from se)
	double *shot_rms;     ///< m, per shot
	double track_noise;   ///< m, the tracks' own noise (fit_track_noise)
	double seconds;       ///< wall time of the fit
} fit_solution;

/// How the 95 % intervals are found.
typedef enum fit_interval_kind {
	FIT_INTERVALS_AUTO = 0,  ///< profile up to FIT_PROFILE_MAX_PARAMS parameters, else wald
	FIT_INTERVALS_WALD,      ///< value +- t se, from the covariance at the minimum
	FIT_INTERVALS_PROFILE,   ///< where the cost, minimised over the others, rises by t^2 sigma^2
} fit_interval_kind;

/// Parameters up to which FIT_INTERVALS_AUTO profiles (each costs about 14 fits of the others).
#define FIT_PROFILE_MAX_PARAMS 12

/// Options of the solver.
typedef struct fit_options {
	fit_interval_kind profile;
	int starts;        ///< starting points: the given one and the track guess (over a growing
	                   ///< horizon), then starts near the best minimum (over all the tracks)
	int max_iterations;
	double sigma;      ///< m, known noise of the positions; 0 = estimate it from the residual
	unsigned long seed; ///< of the perturbed starts
	int retries;       ///< more staged starts, from random points near the start, while the best
	                   ///< fit's rms is above FIT_RETRY_RATIO times the tracks' own noise
	bool no_axis_starts; ///< skip the starts along the covariance's longest axes (solve.c)
	bool quiet;
} fit_options;

/// Fits by nonlinear least squares (gsl_multifit_nlinear, Levenberg-Marquardt): the given starts
/// each over a growing horizon (the first 0.25 s of the tracks, then 1.3 times as much, until all
/// of them count), then starts near the best minimum over all the tracks; keeps the lowest
/// residual, with standard errors from the covariance there, and widens each 95 % interval to
/// span the intervals of other minima that fit as well (fit_solution.alternatives).
/// Returns 0, or POOL_EXIT_INTERNAL / POOL_EXIT_BAD_INPUT with the message printed.
int fit_solve(const fit_problem *pb, const fit_options *o, fit_solution *out);
void fit_solution_free(fit_solution *s);

// ---- outputs ----------------------------------------------------------------------------------

/// The libpool-fit/1 document, the text summary, and the picture of observed against fitted
/// tracks (one table per shot). malloc'd; NULL when out of memory.
char *fit_report_json(const fit_problem *pb, const fit_solution *s);
char *fit_report_text(const fit_problem *pb, const fit_solution *s);
char *fit_svg(const fit_problem *pb, const fit_solution *s);

/// The value of a parameter as written in outputs (degrees for angles).
double fit_shown(const fit_param_info *info, double value);

#endif
