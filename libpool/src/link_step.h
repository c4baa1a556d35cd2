// One LINK step of a cluster of balls in persistent contact (docs/physics.md "LINK"): the velocity-
// level frictional-contact LCP of Anitescu & Potra / Stewart & Trinkle over the cluster's
// ball-ball, ball-cloth and ball-cushion contacts, with a polyhedral friction cone of
// POOL_LINK_ETA directions per contact, solved by lexicographic Lemke (lemke.h). The step turns
// the balls' velocities at the step's start into the mean velocities they keep over the step
// (the explicit cloth wrenches act at its midpoint, link_step.c); the positions then advance
// linearly with them (the world's linked segments), so the exact state at any instant inside a
// step is known, and the velocities at the step's end are the mean plus a tail.
#ifndef POOL_LINK_STEP_H
#define POOL_LINK_STEP_H

#include "pool/base.h"
#include "pool/ball.h"
#include "pool/sim.h"

#include "link_basis.h"

/// Friction directions per contact (docs/physics.md: eta = 14, in +/- pairs).
#define POOL_LINK_ETA 14

/// Largest eta pool_link_step_with accepts (an internal study parameter: the friction-cone
/// test runs 4 to 28).
#define POOL_LINK_ETA_MAX 64

/// m, gap at or below which a ball-ball or ball-cushion contact counts as touching (the
/// stats' `touching`, which the world uses to dissolve a cluster): a thousandth of a
/// millimetre, far above the rounding of the positions (1e-15 m at table scale) and of Lemke's
/// complementarity (1e-10 relative: a picometre of gap per step), far below anything visible. A
/// contact the step closes ends it at gap 0 exactly up to that rounding.
#define POOL_LINK_TOUCH_GAP 1e-6

/// Relative complementarity residual a step accepts (Lemke's own check is
/// POOL_LEMKE_RESIDUAL_MAX = 1e-10): the LCP is in velocity units (link_step.c), so this is a
/// velocity error of at most 1e-6 (1 + the cluster's speeds) m/s: a nanometre over a 1 ms step,
/// a tenth of POOL_LINK_REST_SPEED. The degenerate friction LCPs of touching clusters (every
/// unused friction direction of a sticking contact at w = 0) end between 1e-10 and 4e-7 in
/// floating point (the random shots of test_random_shots and test_threads).
#define POOL_LINK_RESIDUAL_MAX 1e-6

/// Compliance added to the friction directions' diagonal when a solve fails, then to the whole
/// impulse block's (link_step.c), in velocity units.
#define POOL_LINK_REGULARIZATION 1e-9

/// What one step did.
typedef struct pool_link_step_stats {
	int contacts;          ///< contacts in the LCP (ball-ball, cloth, cushion)
	int touching;          ///< ball-ball and ball-cushion contacts touching at the step's start
	                       ///< (gap <= POOL_LINK_TOUCH_GAP); 0: the cluster has come apart
	double max_contact_speed; ///< m/s, largest relative speed (normal and tangential) at a touching
	                          ///< contact, cloth contacts included, after the step
	double max_push;       ///< m/s, largest normal impulse / ball mass at a touching ball-ball or
	                       ///< ball-cushion contact over the step (0: nothing presses: the closed forms can take over)
	double max_contact_accel; ///< m/s^2, largest change the contacts (the LCP's impulses) made to a
	                          ///< ball's horizontal velocity plus R times its spin's, over the step,
	                          ///< / dt
	int pivots;            ///< Lemke pivots
	int warm;              ///< the warm start solved it
	double residual;       ///< Lemke's relative complementarity residual
	int lcp_size;          ///< unknowns of the LCP: contacts * (eta + 2)
} pool_link_step_stats;

/// Scratch memory of the steps, reused between steps and shots (no allocation once it is large
/// enough). Zero-initialise before the first use.
typedef struct pool_link_workspace {
	void *memory;
	size_t bytes;
	size_t matrix_nonzeros; ///< the LCP matrix's room: the most nonzeros a step has needed
	pool_link_bases bases; ///< warm starts: each contact's basis in the last step that solved it
	/// The table's nose curve (pockets "jaws": the cushion contacts are its parts); NULL: the
	/// rails' four nose lines with gaps at the mouths.
	const struct pool_table_shape *shape;
	/// After a successful step, per ball of the step (n of them, valid until the next step):
	double *ball_push; ///< m/s, its largest normal impulse / ball mass at a ball-ball or
	                   ///< ball-cushion contact over the step (0: nothing presses it)
	int *ball_touching; ///< its ball-ball and ball-cushion contacts touching at the step's start
	double *ball_tail;  ///< 6 per ball (v, w): its velocity at the step's end less the mean
	                    ///< velocity the step returns (half the explicit cloth wrenches)
} pool_link_workspace;

/// Frees the workspace's memory (with the allocator that made it).
void pool_link_workspace_free(pool_link_workspace *ws, const pool_allocator *alloc);

/// Advances the velocities of the n balls s[0..n) (states at the step's start, all in one
/// cluster) over a step of dt > 0: on return s[k].vel and s[k].omega are the mean velocities
/// over the step (the caller advances the positions by dt * vel) and ws->ball_tail what turns
/// them into the velocities at the step's end; positions are not changed. In planar mode
/// (def->airborne false) the vertical velocity is returned as zero. Returns POOL_OK, or
/// POOL_ERR_OUT_OF_MEMORY, or POOL_ERR_INTERNAL when Lemke fails or its residual check does (the
/// states are then left unchanged: never silently wrong velocities).
pool_result pool_link_step(const pool_sim_def *def, pool_ball_state *s, int n, double dt, pool_link_workspace *ws,
                           const pool_allocator *alloc, pool_link_step_stats *stats);

/// Internal study options of a step (pool_link_step uses POOL_LINK_OPTIONS_DEFAULT).
typedef struct pool_link_options {
	int eta;            ///< friction directions per contact: even, 4 ... POOL_LINK_ETA_MAX
	int align_friction; ///< 1: each contact's first friction direction lies along its tangential
	                    ///< slip at the step's start (a sliding contact's friction is then exactly
	                    ///< opposite its slip, as in the closed form, whatever eta); 0: fixed
	                    ///< directions (world x and y on the cloth), as in the 2012 work
} pool_link_options;

/// eta = POOL_LINK_ETA, friction directions aligned with the slip (link_step.c says why).
#define POOL_LINK_OPTIONS_DEFAULT {POOL_LINK_ETA, 1}

/// pool_link_step with explicit options; POOL_ERR_INVALID_ARGUMENT for an eta out of range.
pool_result pool_link_step_with(const pool_sim_def *def, pool_ball_state *s, int n, double dt,
                                const pool_link_options *options, pool_link_workspace *ws,
                                const pool_allocator *alloc, pool_link_step_stats *stats);

#endif
