#!/usr/bin/env bash
# Checks the broadphase (libpool/src/broadphase.c) against the all-pairs search on every test
# suite's shots: a build where the grid serves every shot from 2 balls and each contact search
# is also done over all pairs, abort() on any difference (CMake option POOL_BROADPHASE_VERIFY);
# then every test of that build (unit, command, LCM, Python) and a soak run on it. Every search of every shot of
# those suites must agree to the bit (so must their events). Takes a while; run on demand.
# usage: tools/verify_broadphase.sh [SOAK_SECONDS]   (default 60; BUILD=dir, default build/verify)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
BUILD="${BUILD:-build/verify}"
SOAK_SECONDS="${1:-60}"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DPOOL_BROADPHASE_VERIFY=ON -DPOOL_BUILD_COMPARE=OFF >/dev/null
cmake --build "$BUILD" -j"${JOBS:-2}"
ctest --test-dir "$BUILD" --output-on-failure -j"${JOBS:-2}" -E '^soak$'
"$BUILD/tests/soak/soak" --seconds "$SOAK_SECONDS" --seed 1 --classes all
echo "verify_broadphase: every search of the grid matched all pairs"
