#!/usr/bin/env bash
# README command 1: installs what is missing, builds, then runs the main job.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
bash tools/setup.sh
JOBS="${JOBS:-$(nproc)}"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j"$JOBS" >/dev/null
# (every command creates the directories it writes to)
echo "== Quartic solver: libpool against GSL =="
build/release/bench/pool-bench-quartic

echo "== Break shot: pool-rack 8ball | pool-sim | pool-plot =="
build/release/tools/pool-rack 8ball -o out/break_scenario.json
build/release/tools/pool-sim out/break_scenario.json --sample 0.01 --summary -o out/break.json
.venv/bin/python tools/pool-plot out/break.json -o out/break.png --title "8-ball break"
echo "scenario out/break_scenario.json, result out/break.json, picture out/break.png"

# --- engine comparison (compare/): libpool against ODE and Bullet on the default scenarios ---
echo "== Engine comparison: pool-compare (default scenarios, a few minutes) =="
build/release/compare/pool-compare --out out/compare
echo "table, plots and report: out/compare/report.md (data: out/compare/results.json, results.csv)"
