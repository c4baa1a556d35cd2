// The separation floor: planar mode's stand-in for persistent contact until LINK (PHYSICS.md
// "LINK"). When cloth friction drives two touching balls (or a ball and a cushion) into each
// other, exact impulses form a Zeno sequence (collisions ever closer in time with geometrically
// shrinking speeds) whose limit is a resting contact that point impulses cannot represent; past it
// the bodies would interpenetrate. Every contact pushed back together therefore leaves with a
// separation speed of at least max(|a_n| POOL_CONTACT_MIN_INTERVAL / 2, POOL_SEPARATION_MIN)
// (a_n the relative normal acceleration), so the next contact is at least
// POOL_CONTACT_MIN_INTERVAL later. This only affects contacts slower than a few mm/s and adds at
// most pool_floor_energy_bound per event; such events are flagged (POOL_EVENT_FLAG_FLOOR) so
// tests can hold every other event to strict energy non-increase.
#ifndef POOL_CONTACT_FLOOR_H
#define POOL_CONTACT_FLOOR_H

#include "pool/ball.h"
#include "pool/table.h"

/// Applies the floor to body 1 (s1) and body 2 (s2, NULL for a cushion) along the horizontal
/// unit normal n towards body 1; returns 1 when it acted.
int pool_contact_floor(const pool_params *p, pool_ball_state *s1, pool_ball_state *s2, pool_vec3 n);

#endif
