// libpool: exact, event-driven pool (billiards) physics. Umbrella header.
#ifndef POOL_POOL_H
#define POOL_POOL_H

#include "pool/base.h"
#include "pool/ball.h"
#include "pool/event.h"
#include "pool/link.h"
#include "pool/quartic.h"
#include "pool/rack.h"
#include "pool/sim.h"
#include "pool/strike.h"
#include "pool/table.h"

#endif
