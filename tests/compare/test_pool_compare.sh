#!/usr/bin/env bash
# End-to-end tests of pool-compare: the frozen example plugin and libpool run and produce the
# outputs; bad options, scenarios and plugins are refused with exit status 2 and a clear message.
# usage: test_pool_compare.sh POOL_COMPARE PLUGIN_DIR TEST_PLUGIN_DIR SOURCE_DIR WORK_DIR lcm|nolcm [LCM_PYTHON_DIR]
set -u
BIN=$1 PLUGINS=$2 TEST_PLUGINS=$3 SRC=$4 WORK=$5 LCM=$6 LCM_PY=${7:-}
SCEN=$SRC/compare/scenarios
PY=$SRC/.venv/bin/python
[ -x "$PY" ] || PY=python3
rm -rf "$WORK" && mkdir -p "$WORK"
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect STATUS PATTERN ARGS...: exit status and a pattern in standard error.
expect() {
	local status=$1 pattern=$2
	shift 2
	"$BIN" "$@" >"$WORK/out" 2>"$WORK/err"
	local got=$?
	if [ "$got" -ne "$status" ]; then
		fail "pool-compare $* exited $got, expected $status; stderr: $(cat "$WORK/err")"
	elif ! grep -q -- "$pattern" "$WORK/err"; then
		fail "pool-compare $*: stderr lacks '$pattern': $(cat "$WORK/err")"
	else
		echo "ok: pool-compare $* -> $status: $(head -n1 "$WORK/err")"
	fi
}

# Options.
"$BIN" --help >"$WORK/help" || fail "--help exited $?"
grep -q -- "--engines" "$WORK/help" || fail "--help lacks --engines"
expect 2 "unknown option '--bogus'" --bogus
expect 2 "^pool-compare: --dt" --dt 1e-3,abc
expect 2 "^pool-compare: --dt" --dt -1e-3
expect 2 "^pool-compare: --spread" --spread x
expect 2 "^pool-compare: --scenario needs" --scenario
expect 2 "^pool-compare: --plugin-dir" --plugin-dir "$WORK/nowhere"

# Plugins: missing, not a plugin, wrong ABI.
expect 2 "plugin 'nosuch': no module $PLUGINS/libpool_engine_nosuch.so" --engines nosuch --plugin-dir "$PLUGINS"
expect 2 "does not export the entry symbol pool_engine_plugin" --engines "$TEST_PLUGINS/libpool_engine_nosymbol.so"
expect 2 "has plugin ABI version 99, this harness needs version 1" --engines "$TEST_PLUGINS/libpool_engine_wrongabi.so"
printf 'not an ELF file' >"$WORK/libpool_engine_garbage.so"
expect 2 "plugin 'garbage': cannot load" --engines garbage --plugin-dir "$WORK"

# Scenarios: the parser's message, naming the field.
cat >"$WORK/overlap.json" <<'JSON'
{"format": "libpool-scenario/1", "balls": [{"id": 0, "pos": [1.0, 0.6]}, {"id": 1, "pos": [1.03, 0.6]}]}
JSON
expect 2 "overlap.json: balls\[1\].pos: overlaps ball 0" --engines frozen --scenario "$WORK/overlap.json"
printf '{"format": "libpool-scenario/1", "balls": [' >"$WORK/broken.json"
expect 2 "broken.json: " --engines frozen --scenario "$WORK/broken.json"
cat >"$WORK/unknown.json" <<'JSON'
{"format": "libpool-scenario/1", "balls": [{"id": 0, "pos": [1.0, 0.6]}], "spin": 3}
JSON
expect 2 "unknown.json: spin: unknown field" --engines frozen --scenario "$WORK/unknown.json"
expect 2 "nofile.json: cannot read" --engines frozen --scenario "$WORK/nofile.json"

# LCM: refused cleanly when not built in; published over the in-process transport when it is.
if [ "$LCM" = lcm ]; then
	"$BIN" --engines frozen --scenario "$SCEN/slide.json" --out "$WORK/lcm" --no-plots --quiet \
		--lcm-url memq:// >/dev/null 2>"$WORK/err" || fail "--lcm-url memq:// exited $?: $(cat "$WORK/err")"
	# A subscriber receives every record on POOL_BENCH over multicast, inside a private network
	# namespace (skipped where unshare is not allowed).
	if [ -n "$LCM_PY" ] && unshare --net true 2>/dev/null && "$PY" -c "import lcm" 2>/dev/null; then
		cat >"$WORK/sub.py" <<'PY'
import select, sys, time
sys.path.insert(0, sys.argv[1])
import lcm
from pool_lcm import bench_result_t
lc = lcm.LCM("udpm://239.255.76.67:7667?ttl=0")
got = []
lc.subscribe("POOL_BENCH", lambda ch, data: got.append(bench_result_t.decode(data)))
open(sys.argv[2], "w").close()  # ready
end = time.time() + 20
while time.time() < end and len(got) < 2:
    if select.select([lc.fileno()], [], [], 0.1)[0]:
        lc.handle()
assert [(m.scenario, m.engine, m.reference) for m in got] == [("slide", "libpool", "closed-form"), ("slide", "frozen", "closed-form")], got
assert got[0].dt == 0.0 and got[0].final_position_error < 1e-8 and '"engine":"libpool"' in got[0].json
assert abs(got[1].final_position_error - 10.901) < 1e-3
print("ok: POOL_BENCH carried", len(got), "records")
PY
		unshare --net sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo &&
			("$0" "$1/sub.py" "$2" "$1/ready" & while [ ! -e "$1/ready" ]; do sleep 0.1; done; sleep 0.3;
			 "$3" --engines libpool,frozen --scenario "$4" --out "$1/lcm2" --no-plots --quiet \
			   --lcm-url "udpm://239.255.76.67:7667?ttl=0" >/dev/null; wait $!)' \
			"$PY" "$WORK" "$LCM_PY" "$BIN" "$SCEN/slide.json" || fail "POOL_BENCH subscriber"
	fi
else
	expect 2 "built without LCM" --engines frozen --scenario "$SCEN/slide.json" --lcm-url memq://
fi

# The example plugin and libpool: every output, the INTERFACES.md fields, libpool exact on a closed form.
if "$BIN" --engines frozen,libpool --scenario "$SCEN/slide.json" "$SCEN/cut30.json" --out "$WORK/run" \
	--plugin-dir "$PLUGINS" >"$WORK/table" 2>"$WORK/err"; then
	for f in results.json results.csv report.md slide.png cut30.png; do
		[ -s "$WORK/run/$f" ] || fail "run did not write $f"
	done
	grep -q "slide .*libpool .*event" "$WORK/table" || fail "table lacks the libpool slide row: $(cat "$WORK/table")"
	grep -q "cut30.png" "$WORK/run/report.md" || fail "report.md lacks the plot"
	"$PY" - "$WORK/run/results.json" <<'PY' || fail "results.json check"
import json, sys
records = json.load(open(sys.argv[1]))
need = ["scenario", "engine", "dt", "cpu_seconds", "sim_seconds", "final_position_error", "event_time_error",
        "energy_error", "missed_collisions", "phantom_collisions", "max_penetration", "reference"]
assert len(records) == 4, len(records)
for r in records:
    missing = [k for k in need if k not in r]
    assert not missing, missing
    assert r["dt"] is None, r  # both engines are event-driven
by = {(r["scenario"], r["engine"]): r for r in records}
lp = by[("slide", "libpool")]
assert lp["reference"] == "closed-form" and lp["final_position_error"] < 1e-8, lp
assert by[("cut30", "libpool")]["reference"] == "libpool"
fz = by[("slide", "frozen")]
assert abs(fz["final_position_error"] - 10.901) < 1e-3, fz  # it never moved
assert by[("cut30", "frozen")]["missed_collisions"] == 3, by[("cut30", "frozen")]  # ball pair + 2 cushions
print("ok: results.json has the INTERFACES.md fields and the expected errors")
PY
else
	fail "frozen,libpool run exited $?: $(cat "$WORK/err")"
fi

[ "$failures" -eq 0 ] && echo "passed" || echo "FAILED: $failures"
exit $((failures > 0))
