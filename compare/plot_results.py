#!/usr/bin/env python3
"""Plots of pool-compare's results.json (and horizon.json beside it), each as PNG and SVG:

- <scenario>.png: speed against error (one curve per engine over the time-step sweep, after Erez,
  Tassa & Todorov 2015) and error against the time step;
- <scenario>_horizon.png (scenarios with a predictability horizon): each run's distance from
  libpool against time, beside libpool against itself with its start 1 nm, 1 um and 1 mm off;
- scale.png (pool-compare --scale): CPU per simulated second against the number of balls, per
  family and engine, runs as predictive as libpool with its start 1 mm off filled.

usage: plot_results.py RESULTS.json OUT_DIR
Prints the PNG file names written, one per line (each has an SVG twin).
Run with the repository's .venv/bin/python (it has matplotlib).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"libpool": "tab:green", "ode": "tab:blue", "bullet": "tab:red"}
MARKERS = {"libpool": "*", "ode": "o", "bullet": "s"}
DT_STYLES = {1e-2: ":", 1e-3: "-.", 1e-4: "--", 1e-5: "-"}
SELF_STYLES = {1e-9: ("#1b5e20", "-"), 1e-6: ("#43a047", "--"), 1e-3: ("#a5d6a7", ":")}
# Labels closer than this (in decades, on log axes) are merged or moved apart.
LABEL_GAP = 0.12


def usable(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


def length_name(m):
    return f"{m * 1e9:g} nm" if m < 1e-6 else f"{m * 1e6:g} um" if m < 1e-3 else f"{m * 1e3:g} mm"


def save(fig, out_dir, stem):
    """Writes stem.png and stem.svg; returns the PNG's name."""
    fig.savefig(os.path.join(out_dir, f"{stem}.png"), dpi=110)
    fig.savefig(os.path.join(out_dir, f"{stem}.svg"))
    plt.close(fig)
    return f"{stem}.png"


def dt_labels(points):
    """points: (x, y, dt, engine) of every time-stepped run. A dt whose points (one per engine)
    lie within LABEL_GAP decades of each other gets one label; otherwise each engine's label has an
    offset of its own (ODE above, Bullet below), so coinciding engines never overprint."""
    labels = []
    for dt in sorted({p[2] for p in points}):
        at = [p for p in points if p[2] == dt]
        xs = [math.log10(p[0]) for p in at]
        ys = [math.log10(p[1]) for p in at]
        if max(xs) - min(xs) < LABEL_GAP and max(ys) - min(ys) < LABEL_GAP:
            labels.append((at[0][0], at[0][1], f"{dt:.0e}", (5, 3)))
        else:
            for k, p in enumerate(sorted(at, key=lambda p: p[3])):
                labels.append((p[0], p[1], f"{dt:.0e}", (5, 4) if k % 2 == 0 else (5, -10)))
    return labels


def plot_scenario(name, records, out_dir):
    fig, (ax_speed, ax_dt) = plt.subplots(1, 2, figsize=(11, 4.2))
    reference = records[0].get("reference", "?")
    # A libpool reference that took LINK steps (persistent contact) is not exact: the curves are
    # then the engines' disagreement with it, and libpool's point carries its link share.
    inexact = records[0].get("reference_exact") is False
    engines = sorted({r["engine"] for r in records}, key=lambda e: (e != "libpool", e))
    points, errors = [], []
    exact_zero = []  # event-driven runs with error exactly 0 against a closed form
    for engine in engines:
        rows = [r for r in records if r["engine"] == engine and usable(r.get("cpu_seconds")) and r["cpu_seconds"] > 0]
        if not rows:
            continue
        colour = COLOURS.get(engine)
        marker = MARKERS.get(engine, "^")
        if rows[0].get("dt") is None:  # event-driven: one point, no time step
            r = rows[0]
            speed = r["sim_seconds"] / r["cpu_seconds"]
            extra = ""
            if usable(r.get("link_cpu_share")) and r.get("link_steps"):
                extra = f", {100 * r['link_cpu_share']:.0f} % of CPU in {r['link_steps']} link steps"
            if engine == "libpool" and reference == "libpool":
                # The reference has no error of its own: its speed, as a line, not a point at a floor.
                label = f"libpool: the reference{' (LINK steps, not exact)' if inexact else ''}, {speed:.3g} sim s / CPU s{extra}"
                ax_speed.axvline(speed, color=colour, linewidth=2, label=label)
                continue
            err = r.get("final_position_error")
            if not usable(err):
                continue
            if err == 0:
                exact_zero.append((speed, engine, colour, marker, extra))
                continue
            label = f"{engine} (event-driven){extra}"
            ax_speed.scatter([speed], [err], s=160, marker=marker, color=colour, label=label, zorder=3)
            ax_dt.axhline(err, color=colour, linestyle="--", label=label)
            errors.append(err)
            continue
        rows = [r for r in rows if usable(r.get("final_position_error")) and r["final_position_error"] > 0]
        rows.sort(key=lambda r: -r["dt"])
        if not rows:
            continue
        speed = [r["sim_seconds"] / r["cpu_seconds"] for r in rows]
        err = [r["final_position_error"] for r in rows]
        dts = [r["dt"] for r in rows]
        errors.extend(err)
        ax_speed.plot(speed, err, marker=marker, color=colour, label=engine)
        points.extend((s, e, dt, engine) for s, e, dt in zip(speed, err, dts))
        ax_dt.plot(dts, err, marker=marker, color=colour, label=engine)
    for x, y, text, offset in dt_labels(points):
        ax_speed.annotate(text, (x, y), textcoords="offset points", xytext=offset, fontsize=7)
    for ax in (ax_speed, ax_dt):
        ax.set_yscale("log")
        if errors:  # the 1 mm line always in view
            ax.set_ylim(min(min(errors) / 3, 3e-4), max(max(errors) * 3, 3e-3))
    # An error of exactly 0 (libpool on a closed form it matches to the last bit) has no place on a
    # log axis: a marker on the bottom edge, said in the legend.
    for speed, engine, colour, marker, extra in exact_zero:
        ax_speed.scatter([speed], [0.0], s=160, marker="v", color=colour, clip_on=False, zorder=3,
                         transform=ax_speed.get_xaxis_transform(), label=f"{engine} (event-driven): error 0, exact{extra}")
    ax_speed.set_xscale("log")
    ax_speed.set_xlabel("speed: simulated s per CPU s")
    ax_speed.set_ylabel("final position vs libpool (LINK steps, not exact), m" if inexact
                        else f"final position error, m (vs {reference})")
    ax_speed.set_title(f"{name}: speed against accuracy")
    ax_speed.axhline(1e-3, color="grey", linewidth=0.8, linestyle=":")
    ax_speed.grid(True, which="both", alpha=0.3)
    # The curves run from the top middle (coarse steps) to the left (fine ones) and libpool sits
    # on the right: the middle of the right edge stays clear of points and their dt labels.
    ax_speed.legend(fontsize=7, loc="center right")
    ax_dt.set_xscale("log")
    ax_dt.invert_xaxis()
    ax_dt.set_xlabel("time step dt, s")
    ax_dt.set_ylabel("final position error, m")
    ax_dt.set_title(f"{name}: error against time step")
    ax_dt.axhline(1e-3, color="grey", linewidth=0.8, linestyle=":")
    ax_dt.grid(True, which="both", alpha=0.3)
    if ax_dt.get_legend_handles_labels()[0]:
        ax_dt.legend(fontsize=8, loc="best")
    fig.text(0.01, 0.01, "dotted line: 1 mm", fontsize=7, color="grey")
    fig.tight_layout()
    return save(fig, out_dir, name)


def plot_horizon(study, threshold, out_dir):
    """Distance from libpool against time: every time-stepped run and libpool against itself."""
    fig, ax = plt.subplots(figsize=(8.5, 4.6))
    floor = 1e-10
    for self in study["self"]:
        colour, style = SELF_STYLES.get(self["perturbation"], ("tab:green", "-"))
        t = [p[0] for p in self["track"]]
        e = [max(p[1], floor) if usable(p[1]) else float("nan") for p in self["track"]]
        ax.plot(t, e, color=colour, linestyle=style, linewidth=2,
                label=f"libpool, start {length_name(self['perturbation'])} off")
    for run in sorted(study["runs"], key=lambda r: (r["engine"], -r["dt"])):
        t = [p[0] for p in run["track"]]
        e = [max(p[1], floor) if usable(p[1]) else float("nan") for p in run["track"]]
        ax.plot(t, e, color=COLOURS.get(run["engine"], "tab:purple"), linestyle=DT_STYLES.get(run["dt"], "-"),
                linewidth=1.2, label=f"{run['engine']}, dt {run['dt']:.0e}")
    ax.axhline(threshold, color="grey", linewidth=0.8, linestyle=":")
    ax.set_yscale("log")
    ax.set_ylim(bottom=floor)
    ax.set_xlabel("time, s")
    ax.set_ylabel("distance from libpool's trajectory, m (largest over the balls)")
    ax.set_title(f"{study['scenario']} ({study['balls']} balls): predictability horizon")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right", ncol=2)
    fig.text(0.01, 0.01, f"dotted line: {threshold * 100:g} cm; below {floor:g} m drawn at {floor:g}",
             fontsize=7, color="grey")
    fig.tight_layout()
    return save(fig, out_dir, f"{study['scenario']}_horizon")


def spread_labels(entries, gap):
    """entries: [y (log10), text]; returns them with y moved apart by at least gap, order kept."""
    entries = sorted(entries)
    for k in range(1, len(entries)):
        if entries[k][0] - entries[k - 1][0] < gap:
            entries[k][0] = entries[k - 1][0] + gap
    return entries


def plot_scale(studies, records, out_dir):
    """CPU per simulated second against the ball count, one panel per scale family."""
    families = [f for f in ("break", "gas") if any(s["family"] == f for s in studies)]
    fig, axes = plt.subplots(1, len(families), figsize=(6.2 * len(families), 4.8), squeeze=False)
    for ax, family in zip(axes[0], families):
        group = sorted((s for s in studies if s["family"] == family), key=lambda s: s["balls"])
        balls = [s["balls"] for s in group]
        lib = [s["libpool_cpu_per_sim_second"] for s in group]
        ax.plot(balls, lib, color=COLOURS["libpool"], marker="*", markersize=12, linewidth=2.5, label="libpool (events)")
        labels = [[math.log10(lib[-1]), "libpool", COLOURS["libpool"]]] if usable(lib[-1]) else []
        runs = {}
        for s in group:
            one_mm = next((x for x in s["self"] if x["perturbation"] == 1e-3), None)
            for r in records:
                if r["scenario"] != s["scenario"] or r.get("dt") is None or not usable(r.get("cpu_seconds")):
                    continue
                if not usable(r.get("sim_seconds")) or r["sim_seconds"] <= 0:
                    continue
                eq = one_mm and one_mm["equal_predictability_dt"].get(r["engine"])
                runs.setdefault((r["engine"], r["dt"]), []).append(
                    (s["balls"], r["cpu_seconds"] / r["sim_seconds"], eq is not None and r["dt"] <= eq))
        for (engine, dt), pts in sorted(runs.items(), key=lambda kv: (kv[0][0], -kv[0][1])):
            pts.sort()
            colour = COLOURS.get(engine, "tab:purple")
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=colour, linestyle=DT_STYLES.get(dt, "-"),
                    linewidth=1, alpha=0.8)
            for n, cost, good in pts:
                ax.scatter([n], [cost], marker=MARKERS.get(engine, "^"), s=36, color=colour if good else "white",
                           edgecolors=colour, zorder=3)
            labels.append([math.log10(pts[-1][1]), f"{engine} {dt:.0e}", colour])
        # Labels at the right end of the lines, moved apart so that equal costs never overprint.
        for y, text, colour in spread_labels(labels, LABEL_GAP * 1.3):
            ax.annotate(text, xy=(1.01, 10 ** y), xycoords=("axes fraction", "data"), fontsize=7, color=colour,
                        va="center", annotation_clip=False)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xticks(balls)
        ax.set_xticklabels([str(n) for n in balls])
        ax.set_xlabel("balls (table area grows with them: 16 per standard table)")
        ax.set_ylabel("CPU s per simulated s")
        ax.set_title(f"scale {family}")
        ax.grid(True, which="both", alpha=0.3)
        ax.scatter([], [], marker="o", color="grey", label="filled: as predictive as libpool, start 1 mm off")
        ax.scatter([], [], marker="o", color="white", edgecolors="grey", label="hollow: less predictive")
        ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.subplots_adjust(right=0.9)
    return save(fig, out_dir, "scale")


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
    horizon_file = os.path.join(os.path.dirname(os.path.abspath(argv[1])), "horizon.json")
    if os.path.exists(horizon_file):
        with open(horizon_file, encoding="utf-8") as f:
            horizons = json.load(f)
        for study in horizons["scenarios"]:
            print(plot_horizon(study, horizons["threshold"], argv[2]))
        studies = [s for s in horizons["scenarios"] if s.get("family")]
        if studies:
            print(plot_scale(studies, records, argv[2]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
