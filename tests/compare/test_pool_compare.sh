#!/usr/bin/env bash
# End-to-end tests of pool-compare: the frozen example plugin and libpool run and produce the
# outputs; bad options, scenarios and plugins are refused with exit status 2 and a clear message;
# a plugin that crashes, exits, hangs or returns bad states (the faulty test plugin) gives error
# rows while libpool's results stay whole, and a harness killed mid-run leaves its finished rows.
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
grep -q -- "--airborne" "$WORK/help" || fail "--help lacks --airborne"
expect 2 "unknown option '--bogus'" --bogus
expect 2 "^pool-compare: --dt" --dt 1e-3,abc
expect 2 "^pool-compare: --dt" --dt -1e-3
expect 2 "^pool-compare: --spread" --spread x
expect 2 "^pool-compare: --scenario needs" --scenario
expect 2 "^pool-compare: --plugin-dir" --plugin-dir "$WORK/nowhere"
expect 2 "^pool-compare: --timeout" --timeout soon
expect 2 "^pool-compare: --timeout" --timeout -1
expect 2 "^pool-compare: --scale: '1' is not a ball count in \[2, 4096\]" --scale 16,1
expect 2 "^pool-compare: --scale: '5000'" --scale 5000
expect 2 "^pool-compare: --scale needs" --scale
expect 2 "^pool-compare: --families: unknown family 'crowd'" --scale 16 --families crowd

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
# Input larger than the commands' limit (64 MiB): refused with a message, not read to the end.
expect 2 "/dev/zero: input is larger than the limit of 67108864 bytes" --engines frozen --scenario /dev/zero
printf '{"format": "libpool-scenario/1", "balls": [' >"$WORK/broken.json"
expect 2 "broken.json: " --engines frozen --scenario "$WORK/broken.json"
cat >"$WORK/unknown.json" <<'JSON'
{"format": "libpool-scenario/1", "balls": [{"id": 0, "pos": [1.0, 0.6]}], "spin": 3}
JSON
expect 2 "unknown.json: spin: unknown field" --engines frozen --scenario "$WORK/unknown.json"
expect 2 "nofile.json: No such file or directory" --engines frozen --scenario "$WORK/nofile.json"

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
			("$0" "$1/sub.py" "$2" "$1/ready" & for i in $(seq 200); do [ -e "$1/ready" ] || ! kill -0 $! 2>/dev/null && break; sleep 0.1; done; sleep 0.3;
			 "$3" --engines libpool,frozen --scenario "$4" --out "$1/lcm2" --no-plots --quiet \
			   --lcm-url "udpm://239.255.76.67:7667?ttl=0" >/dev/null; wait $!)' \
			"$PY" "$WORK" "$LCM_PY" "$BIN" "$SCEN/slide.json" || fail "POOL_BENCH subscriber"
	fi
else
	expect 2 "built without LCM" --engines frozen --scenario "$SCEN/slide.json" --lcm-url memq://
fi

# The example plugin and libpool: every output, the docs/interfaces.md fields, libpool exact on a closed form.
if "$BIN" --engines frozen,libpool --scenario "$SCEN/slide.json" "$SCEN/cut30.json" --out "$WORK/run" \
	--plugin-dir "$PLUGINS" >"$WORK/table" 2>"$WORK/err"; then
	for f in results.json results.csv report.md slide.png cut30.png slide.svg cut30.svg; do
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
print("ok: results.json has the docs/interfaces.md fields and the expected errors")
PY
else
	fail "frozen,libpool run exited $?: $(cat "$WORK/err")"
fi

# Isolation: every failure of the faulty plugin (one per time step, faulty_plugin.c) next to
# libpool, in one run with a 1 s limit per run. Exit status 1, every output written, an error row
# with its reason for each failure, libpool's rows complete and exact.
FAULTY=$TEST_PLUGINS/libpool_engine_faulty.so
start=$(date +%s%N)
"$BIN" --engines libpool,"$FAULTY" --plugin-dir "$PLUGINS" --scenario "$SCEN/slide.json" "$SCEN/cut30.json" \
	--dt 1e-3,2e-3,3e-3,4e-3,5e-3,6e-3,7e-3,8e-3,9e-3,1e-2 --timeout 1 --out "$WORK/faulty" --no-plots \
	>"$WORK/faulty.table" 2>"$WORK/faulty.err"
got=$?
took_ms=$((($(date +%s%N) - start) / 1000000))
if [ "$got" -ne 1 ]; then
	fail "faulty run exited $got, expected 1; stderr: $(cat "$WORK/faulty.err")"
else
	echo "ok: faulty run exited 1 in $took_ms ms"
fi
# Two hung runs at 1 s each, everything else in well under a second: a hang not killed at the
# limit would take forever.
[ "$took_ms" -lt 20000 ] || fail "faulty run took $took_ms ms"
grep -q "18 of 22 runs failed" "$WORK/faulty.err" || fail "stderr lacks the failure summary: $(cat "$WORK/faulty.err")"
grep -q "cut30 .*faulty .*4e-03 .*failed: exit(3)" "$WORK/faulty.table" || fail "table lacks the exit(3) row"
for f in results.json results.csv report.md engines.log; do
	[ -s "$WORK/faulty/$f" ] || fail "faulty run did not write $f"
done
"$PY" - "$WORK/faulty" <<'PY' || fail "faulty results check"
import csv, json, sys
d = sys.argv[1]
records = json.load(open(d + "/results.json"))
assert len(records) == 22, len(records)
by = {(r["scenario"], r["engine"], r["dt"]): r for r in records}
balls = {"slide": 1, "cut30": 2}
for scen in ("slide", "cut30"):
    n = balls[scen]
    lp = by[(scen, "libpool", None)]
    assert lp["error"] is None and lp["outcome"] == "ok", lp
    assert lp["final_position_error"] is not None and lp["final_position_error"] < 1e-8, lp
    assert lp["cpu_seconds"] > 0 and lp["repetitions"] >= 1 and lp["wall_seconds"] > 0, lp
    assert lp["reference"] == ("closed-form" if scen == "slide" else "libpool"), lp
    if scen == "cut30":
        assert lp["missed_collisions"] == 0 and lp["phantom_collisions"] == 0 and lp["collisions_reference"] == 3, lp
    ok = by[(scen, "faulty", 1e-3)]
    assert ok["error"] is None and ok["outcome"] == "ok" and ok["final_position_error"] > 1, ok
    expected = {
        2e-3: ("crashed", lambda e: e == "killed by SIGSEGV"),
        3e-3: ("crashed", lambda e: e == "killed by SIGABRT"),
        4e-3: ("exited", lambda e: e == "exit(3)"),
        5e-3: ("timed_out", lambda e: e == "timed out after 1 s"),
        6e-3: ("failed", lambda e: e.startswith("non-finite state of ball 0 (pos nan nan")),
        7e-3: ("failed", lambda e: e.startswith("non-finite state of ball 0") and "vel inf" in e),
        8e-3: ("failed", lambda e: e.startswith("balls() reported %d balls, the scenario has %d" % (n + 1, n))),
        9e-3: ("failed", lambda e: e.startswith("balls() returned %d but wrote only 0 balls" % n)),
        1e-2: ("failed", lambda e: e.startswith("events() returned 5 but wrote only 0 events")),
    }
    for dt, (outcome, check) in expected.items():
        r = by[(scen, "faulty", dt)]
        assert r["outcome"] == outcome and r["error"] and check(r["error"]), (dt, r["outcome"], r["error"])
        # An error row scores nothing: no NaN position is an error of 0.
        assert r["final_position_error"] is None and r["cpu_seconds"] is None, (dt, r)
    hung = by[(scen, "faulty", 5e-3)]
    assert 1.0 <= hung["wall_seconds"] < 3.0, hung["wall_seconds"]  # killed at the limit (slack: a loaded machine)
rows = list(csv.DictReader(open(d + "/results.csv")))
assert len(rows) == 22 and sum(1 for r in rows if r["error"]) == 18, len(rows)
assert {r["outcome"] for r in rows} == {"ok", "failed", "crashed", "exited", "timed_out"}, {r["outcome"] for r in rows}
report = open(d + "/report.md").read()
for reason in ("killed by SIGSEGV (crashed)", "killed by SIGABRT (crashed)", "exit(3) (exited)",
               "timed out after 1 s (timed_out)", "non-finite state", "the scenario has 2"):
    assert reason in report, reason
print("ok: 18 error rows with their reasons, libpool's 2 rows whole, the hung runs killed after 1 s")
PY

# The harness itself killed (SIGKILL) while a run hangs with no time limit: the rows finished
# before it are on disk, results.json is whole, and the hung run does not outlive the harness.
POOL_FAULTY_MODE=hang "$BIN" --engines libpool,"$FAULTY" --plugin-dir "$PLUGINS" --scenario "$SCEN/slide.json" \
	--dt 1e-3 --timeout 0 --out "$WORK/killed" --no-plots --quiet >/dev/null 2>&1 &
harness=$!
# The children of a process, from /proc (field 4 of stat, after the command name, is the parent).
children_of() {
	local stat
	for stat in /proc/[0-9]*/stat; do
		[ "$(sed 's/.*) //' "$stat" 2>/dev/null | cut -d' ' -f2)" = "$1" ] && basename "$(dirname "$stat")"
	done
}
for _ in $(seq 200); do
	grep -q '"libpool"' "$WORK/killed/results.json" 2>/dev/null && break
	sleep 0.05
done
sleep 0.3
child=$(children_of "$harness" | head -n1) # the faulty run, hanging
kill -9 "$harness"
wait "$harness" 2>/dev/null
if [ -z "${child:-}" ]; then
	fail "no run process under the harness"
else
	for _ in $(seq 40); do kill -0 "$child" 2>/dev/null || break; sleep 0.05; done
	if kill -0 "$child" 2>/dev/null; then
		fail "the hung run $child outlived the harness"
		kill -9 "$child"
	fi
fi
"$PY" - "$WORK/killed/results.json" <<'PY' || fail "results.json after the harness was killed"
import json, sys
records = json.load(open(sys.argv[1]))
assert [(r["scenario"], r["engine"]) for r in records] == [("slide", "libpool")], records
assert records[0]["error"] is None and records[0]["final_position_error"] < 1e-8, records[0]
print("ok: the harness killed mid-run left its finished row in a whole results.json")
PY

# --in-process: the same results without a child process.
if "$BIN" --engines libpool --plugin-dir "$PLUGINS" --scenario "$SCEN/slide.json" --in-process \
	--out "$WORK/inproc" --no-plots --quiet >/dev/null 2>"$WORK/err"; then
	"$PY" -c "
import json, sys
r = json.load(open(sys.argv[1]))
assert len(r) == 1 and r[0]['outcome'] == 'ok' and r[0]['final_position_error'] < 1e-8, r
" "$WORK/inproc/results.json" || fail "--in-process results"
else
	fail "--in-process run exited $?: $(cat "$WORK/err")"
fi

# Airborne scenarios (compare/scenarios/airborne, not in the default set): drop has the airborne
# closed form, jump has none and, while libpool refuses airborne motion, no reference either:
# its engines still run, its rows say "no reference", the harness exits 1 (libpool's rows fail),
# and the landing fields are in results.json and report.md. Once libpool simulates airborne
# motion, jump's reference is libpool and the harness exits 0.
ENGS=libpool
[ -e "$PLUGINS/libpool_engine_ode.so" ] && ENGS=$ENGS,ode
"$BIN" --engines "$ENGS" --plugin-dir "$PLUGINS" --scenario "$SCEN/airborne/drop.json" "$SCEN/airborne/jump.json" \
	--dt 1e-3 --out "$WORK/airborne" --no-plots --quiet >"$WORK/out" 2>"$WORK/err"
status=$?
"$PY" - "$WORK/airborne" "$status" "$ENGS" <<'PY' || fail "airborne scenarios: $(cat "$WORK/err")"
import json, sys
out, status, engines = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(",")
rows = json.load(open(out + "/results.json"))
assert [(r["scenario"], r["engine"]) for r in rows] == [(s, e) for s in ("drop", "jump") for e in engines], rows
for r in rows:
    if r["error"] is not None and r["engine"] == "libpool":
        continue  # an error row (libpool refusing airborne motion) holds no measurements
    for key in ("landing_time_error", "landing_position_error", "bounce_height_error", "landings_reference",
                "landings_engine", "reference_error"):
        assert key in r, key
lib = {r["scenario"]: r for r in rows if r["engine"] == "libpool"}
supported = lib["drop"]["error"] is None
if not supported:
    assert "airborne" in lib["drop"]["error"] and status == 1, (lib["drop"]["error"], status)
report = open(out + "/report.md").read()
for r in rows:
    if r["scenario"] == "drop":
        assert r["reference"] == "closed-form", r
        assert r["error"] is not None or r["landings_reference"] == 9, r
        if r["engine"] == "ode":
            assert r["error"] is None and 0 <= r["landing_time_error"] <= 6e-3 and r["landings_engine"] >= 5, r
    elif not supported:
        assert r["reference"] == "none" and "airborne" in r["reference_error"], r
        if r["engine"] == "ode":
            assert r["error"] is None and r["final_position_error"] is None and r["cpu_seconds"] > 0, r
    else:
        assert r["reference"] == "libpool", r
if not supported:
    assert "no reference" in report and "Scenarios without a reference" in report, report
assert "Flight and landing" in report, report
print("ok: airborne drop scored against its closed form, jump without reference runs and says so")
PY
# --airborne runs every compare/scenarios/airborne file after the --scenario ones.
"$BIN" --engines libpool --plugin-dir "$PLUGINS" --scenario "$SCEN/slide.json" --airborne --out "$WORK/airborne_set" \
	--no-plots --quiet >/dev/null 2>&1
"$PY" -c "
import json, sys
names = [r['scenario'] for r in json.load(open(sys.argv[1]))]
assert names == ['slide', 'cushion_hop', 'drop', 'hop', 'jump', 'masse'], names
" "$WORK/airborne_set/results.json" || fail "--airborne scenario list"

# The scale smoke run (the benchmark runs N up to 1,024 on demand): both families at 16 balls,
# one step, every built engine. The generated scenarios are written and pool-sim-readable, the
# records carry the ball count, family and horizon, horizon.json holds libpool's self horizons
# and every run's track, and the report and plots have the scale and horizon parts.
ENGS=libpool
for e in ode bullet; do [ -e "$PLUGINS/libpool_engine_$e.so" ] && ENGS=$ENGS,$e; done
if "$BIN" --engines "$ENGS" --plugin-dir "$PLUGINS" --scale 16 --dt 1e-3 --out "$WORK/scale" \
	>"$WORK/scale_table" 2>"$WORK/err"; then
	for f in scenarios/scale_break_16.json scenarios/scale_gas_16.json horizon.json scale.png scale.svg \
		scale_gas_16_horizon.png scale_gas_16_horizon.svg scale_break_16.svg; do
		[ -s "$WORK/scale/$f" ] || fail "--scale did not write $f"
	done
	grep -q "Scale: CPU per simulated second" "$WORK/scale/report.md" || fail "report.md lacks the scale section"
	grep -q "Predictability horizon" "$WORK/scale/report.md" || fail "report.md lacks the horizon section"
	grep -q "libpool, start 1 nm off" "$WORK/scale_table" || fail "the printed tables lack the self horizons"
	"$PY" - "$WORK/scale" "$ENGS" <<'PY' || fail "--scale outputs: $(cat "$WORK/err")"
import json, sys
out, engines = sys.argv[1], sys.argv[2].split(",")
rows = json.load(open(out + "/results.json"))
assert [(r["scenario"], r["engine"]) for r in rows] == [(s, e) for s in ("scale_break_16", "scale_gas_16") for e in engines], rows
for r in rows:
    assert r["balls"] == 16 and r["family"] == r["scenario"].split("_")[1], r
    assert r["spread_runs"] == 0, r  # the horizon replaces the spread
    assert isinstance(r["horizon_seconds"], float) and 0 < r["horizon_seconds"] <= 2.0, r
    if r["engine"] == "libpool":
        assert r["horizon_censored"] is True and r["final_position_error"] == 0, r
h = json.load(open(out + "/horizon.json"))
assert h["threshold"] == 0.01, h["threshold"]
assert [s["scenario"] for s in h["scenarios"]] == ["scale_break_16", "scale_gas_16"]
for s in h["scenarios"]:
    assert [x["perturbation"] for x in s["self"]] == [1e-9, 1e-6, 1e-3], s["self"]
    assert all(len(x["track"]) == 400 and x["runs"] == 8 for x in s["self"])
    assert len(s["runs"]) == len(engines) - 1 and all(len(r["track"]) == 400 for r in s["runs"])
    assert s["libpool_cpu_per_sim_second"] > 0
print("ok: --scale 16 wrote the families, the horizons and the scale summary")
PY
	# What --scale writes is a scenario pool-sim reads (the file names the family and ball count).
	"$(dirname "$BIN")/../tools/pool-sim" "$WORK/scale/scenarios/scale_gas_16.json" -o /dev/null 2>"$WORK/err" ||
		fail "pool-sim refused the generated gas: $(cat "$WORK/err")"
else
	fail "--scale 16 exited $?: $(cat "$WORK/err")"
fi

[ "$failures" -eq 0 ] && echo "passed" || echo "FAILED: $failures"
exit $((failures > 0))
