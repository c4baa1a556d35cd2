// Internals of the simulation that tests inspect (not part of the public API).
#ifndef POOL_SIM_INTERNAL_H
#define POOL_SIM_INTERNAL_H

#include "pool/sim.h"

/// s, minimum time between two contacts of bodies pushed together by cloth friction (planar
/// stand-in for persistent contact; see sim.c).
#define POOL_CONTACT_MIN_INTERVAL 1e-3

/// The event got the persistent-contact separation floor (may add a tiny amount of energy).
#define POOL_EVENT_FLAG_FLOOR 1

/// J, the most kinetic energy one floored event can add. The floor raises a pair's separation
/// speed from vn >= 0 to f, adding (m/4)(f^2 - vn^2) <= (m/4) f^2 for two balls ((m/2) f^2 / 4
/// ... for a cushion, less); f = max(|a_n| POOL_CONTACT_MIN_INTERVAL / 2, POOL_SEPARATION_MIN) with
/// the relative normal acceleration |a_n| <= 2 max(mu_slide, mu_roll) g (two balls sliding apart).
/// 1.6e-7 J with the default parameters; it grows with (mu g)^2.
double pool_floor_energy_bound(const pool_params *params);

/// POOL_EVENT_FLAG_* bits of event `index` (0 when out of range).
int pool_sim_event_flags(const pool_sim *sim, int index);

#endif
