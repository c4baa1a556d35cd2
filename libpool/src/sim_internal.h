// Internals of the simulation that tests inspect (not part of the public API).
#ifndef POOL_SIM_INTERNAL_H
#define POOL_SIM_INTERNAL_H

#include "pool/sim.h"

/// s, minimum time between two contacts of bodies pushed together by cloth friction (planar
/// stand-in for persistent contact; see sim.c).
#define POOL_CONTACT_MIN_INTERVAL 1e-3

/// The event got the persistent-contact separation floor (may add a tiny amount of energy).
#define POOL_EVENT_FLAG_FLOOR 1

/// POOL_EVENT_FLAG_* bits of event `index` (0 when out of range).
int pool_sim_event_flags(const pool_sim *sim, int index);

#endif
