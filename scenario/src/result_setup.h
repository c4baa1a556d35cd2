// The shot's setup as a result file writes it; shared with the LCM table message, which carries
// the same keys so a subscriber reads one format.
#ifndef POOL_SCENARIO_RESULT_SETUP_H
#define POOL_SCENARIO_RESULT_SETUP_H

#include "json_writer.h"
#include "pool/pool.h"

/// The shot's setup as a result file carries it, as keys of the object being written: "table" (the
/// pocket model and, with "jaws", its geometry, cut angles in degrees), "ball_radius", "params",
/// "models" (docs/interfaces.md "Result file").
void pool_jw_sim_setup(pool_jw *w, const pool_sim_def *def);

#endif
