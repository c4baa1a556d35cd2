#!/usr/bin/env python3
"""pip install ./python in a fresh virtual environment: the package builds its own libpool.so,
libpool_games.so and libpool_scenario.so, `import libpool` works from another directory with those bundled
libraries, and a break's event list, a libpool.batch run, the break judged by libpool.game and a
noisy strike equal the in-tree binding's bit for bit.

Usage: test_install.py --source PYTHON_DIR --work DIR
(run with the in-tree binding importable: PYTHONPATH holds python/, LIBPOOL_PATH the build's
libpool.so). Exits 77 (ctest: skipped) only when pip cannot reach the package registry to fetch
the build backend; any other failure fails.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import time

SKIP = 77

# Run by the installed package, from a directory outside the repository. Floats as hex, so the
# comparison is bit for bit.
PROBE = r"""
import json, sys
import libpool, libpool.batch, libpool.game, libpool._scenario

def ball(b):
    return [b.id, b.motion] + [x.hex() for x in b.pos + b.vel + b.omega]

with libpool.Sim(max_time=120.0) as sim:
    sim.rack("8ball", gap=1e-4)
    sim.break_strike(8.0)
    stop = sim.run()
    judged = libpool.game.judge(sim, libpool.game.State.default("8ball")).to_dict()
    noisy = [x.hex() for x in libpool.game.noisy_strike((2.0, 10.0, 0.0, 0.0, 0.0), "fastfiz", 7, 3)]
    events = [[e.time.hex(), e.type, list(e.balls), e.rail, e.pocket, [ball(b) for b in e.after]]
              for e in sim.events]
    layout = {"format": "libpool-scenario/1",
              "balls": [{"id": b.id, "pos": list(b.pos[:2])} for b in sim.balls
                        if b.motion == "stationary"],
              "strike": {"ball": 0, "speed": 2.0}}
res = libpool.batch.run(layout, [(0, 1.0 + 0.5 * k, 37.0 * k, 2.0, 0.001 * k, -0.002)
                                 for k in range(10)], workers=2)
batch = {k: getattr(res, k).tobytes().hex() for k in
         ("stop_reason", "events", "end_time", "first_hit", "pos", "state")}
print(json.dumps({"library": libpool.library_path(), "module": libpool.__file__, "stop": stop,
                  "events": events, "layout": layout, "batch": batch,
                  "game": {"judged": judged, "noisy": noisy, "games_library": libpool.game.library_path()},
                  "scenario_library": libpool._scenario.library_path()}))
"""


def clean_env():
    """The environment without the in-tree binding's settings (and without a sanitizer runtime
    preloaded into pip, the compiler and the installed package)."""
    env = dict(os.environ)
    for k in ("PYTHONPATH", "LIBPOOL_PATH", "LD_PRELOAD", "ASAN_OPTIONS", "UBSAN_OPTIONS",
              "PYTHONHOME"):
        env.pop(k, None)
    return env


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--source", required=True, help="the python/ directory (pyproject.toml)")
    parser.add_argument("--work", required=True)
    a = parser.parse_args()
    start = time.monotonic()
    work = os.path.abspath(a.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = clean_env()
    venv = os.path.join(work, "venv")
    # The base interpreter, not a virtual environment's (a fresh environment: no site packages).
    base = getattr(sys, "_base_executable", sys.executable)
    p = run([base, "-m", "venv", venv], env=env)
    if p.returncode != 0:
        sys.exit(f"test_install: python -m venv failed:\n{p.stdout}{p.stderr}")
    py = os.path.join(venv, "bin", "python")

    # Can pip reach the registry? Fetch the build backend alone, quickly; when it cannot, the
    # test is skipped (and says why), never passed.
    probe_dir = os.path.join(work, "probe")
    p = run([py, "-m", "pip", "download", "--no-deps", "--timeout", "20", "--retries", "1",
             "-d", probe_dir, "scikit-build-core>=0.8"], env=env)
    if p.returncode != 0:
        print("test_install: SKIPPED: pip cannot fetch scikit-build-core from the package "
              "registry (offline?):\n" + p.stdout[-2000:] + p.stderr[-2000:])
        return SKIP

    p = run([py, "-m", "pip", "install", a.source], env=env, cwd=work)
    print(p.stdout[-3000:])
    if p.returncode != 0:
        sys.exit(f"test_install: pip install {a.source} failed:\n{p.stderr[-5000:]}")
    site = run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
               env=env).stdout.strip()
    bundled = os.path.join(site, "libpool", "libpool.so")
    if not os.path.isfile(bundled):
        sys.exit(f"test_install: no bundled library at {bundled}")

    # From another directory, with LIBPOOL_PATH naming a library that does not exist: the
    # bundled one is found first.
    elsewhere = os.path.join(work, "elsewhere")
    os.makedirs(elsewhere)
    env_run = dict(env, LIBPOOL_PATH=os.path.join(work, "no-such-libpool.so"))
    p = run([py, "-c", PROBE], env=env_run, cwd=elsewhere)
    if p.returncode != 0:
        sys.exit(f"test_install: the installed package failed:\n{p.stdout}{p.stderr}")
    installed = json.loads(p.stdout)
    if os.path.realpath(installed["library"]) != os.path.realpath(bundled):
        sys.exit(f"test_install: library_path() is {installed['library']}, not {bundled}")
    if not os.path.realpath(installed["module"]).startswith(os.path.realpath(site)):
        sys.exit(f"test_install: imported {installed['module']}, not the installed package")

    # The same probe with the in-tree binding (this interpreter's PYTHONPATH / LIBPOOL_PATH).
    p = run([sys.executable, "-c", PROBE], cwd=elsewhere)
    if p.returncode != 0:
        sys.exit(f"test_install: the in-tree binding failed:\n{p.stdout}{p.stderr}")
    tree = json.loads(p.stdout)
    if os.path.realpath(tree["library"]) == os.path.realpath(bundled):
        sys.exit("test_install: the in-tree run used the installed library")
    games = os.path.join(site, "libpool", "libpool_games.so")
    if os.path.realpath(installed["game"].pop("games_library")) != os.path.realpath(games):
        sys.exit(f"test_install: libpool.game did not load the bundled {games}")
    tree["game"].pop("games_library")
    scenario = os.path.join(site, "libpool", "libpool_scenario.so")
    if os.path.realpath(installed.pop("scenario_library")) != os.path.realpath(scenario):
        sys.exit(f"test_install: libpool.batch did not load the bundled {scenario}")
    tree.pop("scenario_library")
    for key in ("stop", "events", "layout", "batch", "game"):
        if installed[key] != tree[key]:
            sys.exit(f"test_install: {key} differs between the installed package and the "
                     f"in-tree binding ({tree['library']})")
    n = len(tree["events"])
    print(f"test_install: OK: pip install {a.source} into a fresh venv; {bundled}; a break of "
          f"{n} events, a 10-shot batch, the break judged by libpool.game and a noisy strike bit-identical to the in-tree binding "
          f"({tree['library']}); {time.monotonic() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
