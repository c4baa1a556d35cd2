#!/usr/bin/env python3
"""Plots of pool-compare's results.json: per scenario, speed against error (one curve per engine
over the time-step sweep, after Erez, Tassa & Todorov 2015) and error against the time step.

usage: plot_results.py RESULTS.json OUT_DIR
Writes OUT_DIR/<scenario>.png and prints the file names written, one per line.
Run with the repository's .venv/bin/python (it has matplotlib).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Errors of exactly 0 (libpool against itself or against a closed form it matches to the last bit)
# cannot sit on a log axis: they are drawn at this floor and labelled.
FLOOR = 1e-12
COLOURS = {"libpool": "tab:green", "ode": "tab:blue", "bullet": "tab:red"}
MARKERS = {"libpool": "*", "ode": "o", "bullet": "s"}


def usable(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


def floored(value):
    return max(value, FLOOR)


def plot_scenario(name, records, out_dir):
    fig, (ax_speed, ax_dt) = plt.subplots(1, 2, figsize=(11, 4.2))
    reference = records[0].get("reference", "?")
    # A libpool reference that took LINK steps (persistent contact) is not exact: the curves are
    # then the engines' disagreement with it, and libpool's point carries its link share.
    inexact = records[0].get("reference_exact") is False
    engines = sorted({r["engine"] for r in records}, key=lambda e: (e != "libpool", e))
    for engine in engines:
        rows = [r for r in records if r["engine"] == engine and usable(r.get("final_position_error"))
                and usable(r.get("cpu_seconds")) and r["cpu_seconds"] > 0]
        if not rows:
            continue
        colour = COLOURS.get(engine)
        marker = MARKERS.get(engine, "^")
        if rows[0].get("dt") is None:  # event-driven: one point, no time step
            r = rows[0]
            err = r["final_position_error"]
            label = f"{engine} (event-driven{', exact' if err == 0 and not inexact else ''})"
            if usable(r.get("link_cpu_share")) and r.get("link_steps"):
                label += f", {100 * r['link_cpu_share']:.0f} % of CPU in {r['link_steps']} link steps"
            ax_speed.scatter([r["sim_seconds"] / r["cpu_seconds"]], [floored(err)], s=160, marker=marker,
                             color=colour, label=label, zorder=3)
            ax_dt.axhline(floored(err), color=colour, linestyle="--", label=label)
            continue
        rows.sort(key=lambda r: -r["dt"])
        speed = [r["sim_seconds"] / r["cpu_seconds"] for r in rows]
        err = [floored(r["final_position_error"]) for r in rows]
        dts = [r["dt"] for r in rows]
        ax_speed.plot(speed, err, marker=marker, color=colour, label=engine)
        for s, e, dt in zip(speed, err, dts):
            ax_speed.annotate(f"{dt:.0e}", (s, e), textcoords="offset points", xytext=(4, 4), fontsize=7)
        ax_dt.plot(dts, err, marker=marker, color=colour, label=engine)
    ax_speed.set_xscale("log")
    ax_speed.set_yscale("log")
    ax_speed.set_xlabel("speed: simulated s per CPU s")
    ax_speed.set_ylabel("final position vs libpool (LINK steps, not exact), m" if inexact
                        else f"final position error, m (vs {reference})")
    ax_speed.set_title(f"{name}: speed against accuracy")
    ax_speed.axhline(1e-3, color="grey", linewidth=0.8, linestyle=":")
    ax_speed.grid(True, which="both", alpha=0.3)
    # The curves run from the top middle (coarse steps) to the left (fine ones) and libpool sits
    # bottom right: the middle of the right edge stays clear of points and their dt labels.
    ax_speed.legend(fontsize=8, loc="center right")
    ax_dt.set_xscale("log")
    ax_dt.set_yscale("log")
    ax_dt.invert_xaxis()
    ax_dt.set_xlabel("time step dt, s")
    ax_dt.set_ylabel("final position error, m")
    ax_dt.set_title(f"{name}: error against time step")
    ax_dt.axhline(1e-3, color="grey", linewidth=0.8, linestyle=":")
    ax_dt.grid(True, which="both", alpha=0.3)
    ax_dt.legend(fontsize=8, loc="best")
    fig.text(0.01, 0.01, f"errors of 0 drawn at {FLOOR:g}; dotted line: 1 mm", fontsize=7, color="grey")
    fig.tight_layout()
    file_name = f"{name}.png"
    fig.savefig(os.path.join(out_dir, file_name), dpi=110)
    plt.close(fig)
    return file_name


def main(argv):
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip(), file=sys.stderr if len(argv) != 2 else sys.stdout)
        return 0 if len(argv) == 2 else 2
    with open(argv[1], encoding="utf-8") as f:
        records = json.load(f)
    by_scenario = {}
    for r in records:
        by_scenario.setdefault(r["scenario"], []).append(r)
    for name in sorted(by_scenario):
        print(plot_scenario(name, by_scenario[name], argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
