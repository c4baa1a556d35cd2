#!/usr/bin/env bash
# README command 1: installs what is missing, builds, then runs the main job.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
bash tools/setup.sh
JOBS="${JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j"$JOBS" >/dev/null
mkdir -p out
echo "== Quartic solver: libpool against GSL =="
build/release/tools/pool-bench-quartic
