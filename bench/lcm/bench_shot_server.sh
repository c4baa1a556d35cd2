#!/bin/sh
# Load benchmark of pool-shot-server, inside a private network namespace (multicast stays on its
# loopback): short shots, then breaks. Prints per-run figures, median and minimum, and the machine.
# usage: bench/lcm/bench_shot_server.sh [BUILD_DIR] [extra pool-bench-shot-server options]
# Options for the server (e.g. --workers 2) go in POOL_SHOT_SERVER_ARGS:
#   POOL_SHOT_SERVER_ARGS='--workers 2' bench/lcm/bench_shot_server.sh build/release --runs 3
set -eu
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${1:-$ROOT/build/release}"
[ $# -gt 0 ] && shift
if [ -z "${POOL_IN_NETNS:-}" ]; then
  export POOL_IN_NETNS=1
  exec unshare --net sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec "$@"' \
    netns "$0" "$BUILD" "$@"
fi
URL='udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608'
DATA="$ROOT/tests/lcm/data"
LOG="${TMPDIR:-/tmp}/pool-shot-server-bench.$$.log"
# shellcheck disable=SC2086 # POOL_SHOT_SERVER_ARGS is a list of options, split on purpose
"$BUILD/tools/pool-shot-server" --lcm-url "$URL" ${POOL_SHOT_SERVER_ARGS:-} 2>"$LOG" &
SERVER=$!
trap 'kill $SERVER 2>/dev/null || true' EXIT
# Wait for the server's ready line (it subscribes before printing it), at most 10 s.
tries=0
until grep -q 'pool-shot-server: ready' "$LOG" 2>/dev/null; do
  if ! kill -0 $SERVER 2>/dev/null; then
    echo "bench_shot_server.sh: pool-shot-server exited before it was ready:" >&2
    cat "$LOG" >&2
    exit 1
  fi
  tries=$((tries + 1))
  if [ $tries -gt 200 ]; then
    echo "bench_shot_server.sh: pool-shot-server not ready after 10 s" >&2
    exit 1
  fi
  sleep 0.05
done
echo "server: pool-shot-server ${POOL_SHOT_SERVER_ARGS:-(default options)}"
# The labels count the events pool-sim produces for each scenario, so they follow the engine.
events() { "$BUILD/tools/pool-sim" "$1" --summary 2>&1 >/dev/null | sed -n 's/^pool-sim: \([0-9]*\) events.*/\1/p'; }
"$BUILD/bench/pool-bench-shot-server" --lcm-url "$URL" --scenario "$DATA/short.json" \
  --name "short shot (1 ball, $(events "$DATA/short.json") events)" "$@"
"$BUILD/bench/pool-bench-shot-server" --lcm-url "$URL" --scenario "$DATA/break.json" \
  --name "break (16 balls, $(events "$DATA/break.json") events)" "$@"
kill -TERM $SERVER
wait $SERVER || true
trap - EXIT
tail -1 "$LOG"
rm -f "$LOG"
