// libpool: the fast algebraic quartic path (internal), verified, with a fallback signal.
#ifndef POOL_QUARTIC_FAST_H
#define POOL_QUARTIC_FAST_H

/// Real roots of c[0] x^4 + ... + c[4] (ascending, 0 to 4) by a factorisation into two real
/// quadratics; returns -1 when the answer could be wrong (near-multiple or near-real roots,
/// extreme scaling, c[0] or c[4] zero, no convergence): the caller then uses the isolation solver.
int pool_quartic_fast_real_roots(const double c[5], double roots[4]);

#endif
