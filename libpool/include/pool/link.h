// libpool: LINK, persistent contact as a cluster advanced by LCP steps (docs/physics.md "LINK";
// docs/library.md "Persistent contact").
#ifndef POOL_LINK_H
#define POOL_LINK_H

#include "pool/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/// s, the length of a link step where the contacts act (a step ends earlier when an event from
/// outside reaches one of the cluster's balls, and grows up to POOL_LINK_STEP_MAX where they
/// barely act). Contacts inside a cluster are resolved to first order in it: 1 ms keeps a
/// pushed ball's path within a millimetre of the limit (docs/measurements.md) at a few hundred
/// steps per second of contact.
#define POOL_LINK_STEP_TIME 1e-3

/// s, the longest link step. A step grows (doubling) while its contacts barely act: it is first
/// order in the contact forces (a ball's position over a step is off by about 1/2 a dt^2 for a
/// contact acceleration a), so the next step is at most sqrt(2 POOL_LINK_STEP_ERROR / a) long,
/// and never shorter than POOL_LINK_STEP_TIME. Two balls rolling together, pressed by the
/// difference of their rolling resistances (1e-3 m/s^2), take 16 ms steps instead of 1 ms ones;
/// a push, a ball sliding on the cloth (mu_slide g) or resting on others (g) keeps 1 ms steps.
#define POOL_LINK_STEP_MAX 16e-3
/// m, the position error per step that bounds the growth of the steps (POOL_LINK_STEP_MAX).
/// Against steps held at 1 ms, 500 random frozen breaks end with the same final positions to
/// 1.3e-5 m in 90 % of the shots (1e-7 here: 2.2e-6 m; breaks are chaotic, so the rest drift
/// further, docs/measurements.md), with 9.3 link steps per shot instead of 16.6 (1e-7) and 40.
#define POOL_LINK_STEP_ERROR 1e-6

/// Collisions of one pair (two balls, or a ball and a rail), at distinct instants within
/// POOL_LINK_TRIGGER_WINDOW, that make the pair persistent contact and start a cluster. Exact
/// impulses on a pushed contact form a Zeno series (ever closer collisions); a genuine second
/// collision (a follow shot hitting the object ball again) comes tenths of a second later.
#define POOL_LINK_TRIGGER_COLLISIONS 4
/// Collisions of one pair at one instant that start a cluster: the inelastic collapse of a
/// low-restitution line (thousands of same-instant impulses). The sequential impulses of frozen
/// breaks hit a pair at most 5 times at the instant of impact (8- and 9-ball racks, e_ball 0.92
/// to 0.98, 2 to 12 m/s, docs/measurements.md), so they never trigger it.
#define POOL_LINK_TRIGGER_SAME_INSTANT 12
/// s, the window of POOL_LINK_TRIGGER_COLLISIONS.
#define POOL_LINK_TRIGGER_WINDOW 0.05

/// m/s: a cluster resting above the cloth (a ball on two others) sleeps, taking no more steps
/// until something hits it, once every ball moves and spins (|w| R) slower than this; on the
/// cloth such a cluster dissolves. A ball touching a cluster joins it when it closes on one of
/// its balls faster than this.
#define POOL_LINK_REST_SPEED 1e-5

/// m/s: a ball touching a cluster's ball and closing on it faster than this hits it: the
/// collision is an event (Petit's law, with restitution), not the cluster's (its steps are
/// inelastic), and the ball joins only if it does not part. The contact forces of a cluster,
/// about g at most (gravity on a ball resting on others; the cloth's friction is 0.2 g), change a
/// closing speed by at most g POOL_LINK_STEP_TIME = 9.8 mm/s over a step, so a ball closing faster
/// was not brought there by persistent contact: a break's ball running into a cluster in the rack
/// and the frozen neighbours it sets moving. Joined, each of those made the cluster's LCP grow
/// (9 balls, 22 contacts) and absorbed its bounce.
#define POOL_LINK_IMPACT_SPEED 1e-2

/// m/s of normal impulse / ball mass per POOL_LINK_STEP_TIME (an acceleration of 1e-5 m/s^2, a
/// millionth of g): a ball of a cluster whose ball-ball and cushion contacts press it less than
/// this over a step leaves the cluster (on the cloth; above it once it touches nothing) and
/// resumes its closed-form state, and a cluster dissolves when all its balls do. Spheres
/// rolling together in contact need no contact force to stay so; a ball at the end of a chain
/// that the cluster presses, however weakly, stays (released, it would be hit at once).
#define POOL_LINK_PUSH_MIN 1e-8

/// What the LINK steps of a shot did.
typedef struct pool_link_stats {
	int clusters;         ///< clusters formed (link_begin events)
	int steps;            ///< LCP solves (link_step and link_end events)
	long long pivots;     ///< Lemke pivots, all solves
	int warm_solves;      ///< solves answered by the previous step's basis
	int max_balls;        ///< largest cluster
	int max_contacts;     ///< largest LCP, in contacts
	double max_residual;  ///< largest relative complementarity residual of a solve
} pool_link_stats;

/// The LINK statistics of the current shot (zero when no cluster formed).
POOL_API pool_result pool_sim_link_stats(const pool_sim *sim, pool_link_stats *out);

#ifdef __cplusplus
}
#endif

#endif
