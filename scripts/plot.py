#!/usr/bin/env python3
"""The plots of `vplkit bench gi`, `vplkit bench direct` and `vplkit sequence --reference`, drawn
with matplotlib (Agg: no display needed) from the CSV/JSON those commands write.

usage: scripts/plot.py bench-gi DIR            DIR/points.json -> rmse_vs_time.png,
                                               rmse_vs_gi_time.png, levels.png, block_size_rmse.png,
                                               block_size_time.png, vpl_count_build_time.png
       scripts/plot.py bench-direct DIR        DIR/points.csv -> rmse_vs_time.png, rmse_vs_spp.png
       scripts/plot.py sequence DIR --scene S  DIR/metrics.csv -> metrics.png

Prints "wrote PATH" for each picture. Every input is read and checked before anything is drawn,
and each PNG is written under a temporary name and renamed, so bad input (a missing file, a
malformed CSV or JSON) leaves no picture behind: one line on stderr names the file and the
problem, and the exit status is 1.

bench gi's Pareto fronts are not computed here: points.json lists them (of all methods:
"pareto_front", indices into "points"; each method's own: "method_fronts"), the fronts report.md
lists, so the plot and the report agree by construction.
"""

import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (the backend is chosen first)
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FuncFormatter, MaxNLocator  # noqa: E402

# Okabe-Ito (safe for colour-blind readers) without yellow, hard to see on white, and without
# black, which marks the Pareto front.
COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"]
# bench gi's points of one method: its quality sweep, half resolution and svgf as lines; the
# single-point variants as markers only.
VARIANTS = {  # sweep: (legend entry, marker, line style or None)
    "quality": ("quality sweep (spp / N_avg)", "o", "-"),
    "resolution": ("half resolution", "s", "--"),
    "denoise": ("svgf", "^", ":"),
    "block": ("block size k", "D", None),
    "interleave": ("interleaved", "P", None),
    "mock": ("no mock cuts", "X", None),
}


class InputError(Exception):
    """Bad input: the message names the file and the problem."""


def short_name(scene):
    """A scene's short name: a file's stem, a set-up's name as it is."""
    base = os.path.basename(scene.rstrip("/"))
    return os.path.splitext(base)[0] if base.endswith((".gltf", ".glb")) else base


def number(value):
    """A JSON number, or NaN for null (vplkit writes NaN and infinity as null)."""
    return math.nan if value is None else float(value)


def read_csv(path, columns):
    """The rows of a CSV file with at least `columns`, those parsed as numbers where the column
    name maps to float (an empty cell is NaN)."""
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        missing = [c for c in columns if c not in (reader.fieldnames or [])]
        if missing:
            raise InputError(f"{path}: not the expected CSV: no column {', '.join(missing)}")
        rows = []
        for row in reader:
            if None in row or any(row[c] is None for c in columns):
                raise InputError(f"{path}:{reader.line_num}: {len(reader.fieldnames)} columns expected")
            for c, kind in columns.items():
                if kind is float:
                    try:
                        row[c] = float(row[c]) if row[c].strip() else math.nan
                    except ValueError:
                        raise InputError(f"{path}:{reader.line_num}: column {c}: '{row[c]}' is not a number")
            rows.append(row)
    if not rows:
        raise InputError(f"{path}: no data rows")
    return rows


def read_json(path):
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: not valid JSON: {e}")


def placeable(xs, ys, log_x, log_y):
    """The points that can be drawn: finite, and positive on a log axis."""
    def ok(v, log):
        return math.isfinite(v) and (v > 0 or not log)
    return [(x, y) for x, y in zip(xs, ys) if ok(x, log_x) and ok(y, log_y)]


def new_plot(title, x_label, y_label, log_x, log_y, has_data):
    fig, ax = plt.subplots(figsize=(9.6, 6.0), dpi=100)
    ax.set_title(title, fontsize=12, wrap=True)
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.grid(True, which="major", alpha=0.35)
    ax.grid(True, which="minor", alpha=0.12)
    if has_data:
        ax.set_xscale("log" if log_x else "linear")
        ax.set_yscale("log" if log_y else "linear")
        for axis, log in ((ax.xaxis, log_x), (ax.yaxis, log_y)):
            if log:
                decimal_log_labels(axis)
    else:
        ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", va="center", fontsize=14, color="grey")
    return fig, ax


def decimal_log_labels(axis):
    """A log axis labelled in plain decimals ("0.05", "200"), not powers of ten. One that spans
    under about a decade and a half also labels its 2, 3 and 5 multiples; under a factor of 4,
    every minor tick (else a narrow axis would show one number or none)."""
    def minor(v, _):
        lo, hi = sorted(axis.get_view_interval())
        if lo <= 0 or hi / lo >= 30:
            return ""
        mantissa = round(v / 10 ** math.floor(math.log10(v)), 6)
        return f"{v:g}" if hi / lo < 4 or mantissa in (2, 3, 5) else ""
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(FuncFormatter(minor))


def integer_ticks(axis, values):
    """Ticks at the data's whole values (spp, block size: 1, 2, 4, ...), written as integers."""
    ticks = sorted({v for v in values if math.isfinite(v) and v > 0})
    if ticks and len(ticks) <= 12:
        axis.set_ticks(ticks)
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(FuncFormatter(lambda v, _: ""))


def centre_single_values(ax, points, log_x, log_y):
    """An axis whose points all share one value (a --quick run's single block size or VPL count)
    gets a range centred on it: a factor of 2 each way on a log axis, 10% on a linear one."""
    for values, log, set_limits in (([x for x, _ in points], log_x, ax.set_xlim),
                                    ([y for _, y in points], log_y, ax.set_ylim)):
        if values and min(values) == max(values):
            v = values[0]
            set_limits((v / 2, v * 2) if log else (v - 0.1 * abs(v) - 0.5 * (v == 0), v + 0.1 * abs(v) + 0.5 * (v == 0)))


def save(fig, path, wrote):
    """Writes the picture under a temporary name, then renames it: never a partial PNG."""
    tmp = path + ".tmp.png"
    fig.savefig(tmp, bbox_inches="tight")
    plt.close(fig)
    os.replace(tmp, path)
    wrote.append(path)


def line_plot(path, title, x_label, y_label, series, log_x, log_y, wrote, int_x=False):
    """series: [(name, xs, ys)], each a line with markers."""
    drawn = [(n, placeable(xs, ys, log_x, log_y)) for n, xs, ys in series]
    fig, ax = new_plot(title, x_label, y_label, log_x, log_y, any(p for _, p in drawn))
    for i, (name, points) in enumerate(drawn):
        if points:
            ax.plot(*zip(*points), marker="o", color=COLOURS[i % len(COLOURS)], label=name)
    if any(p for _, p in drawn):
        ax.legend(fontsize=9)
        centre_single_values(ax, [xy for _, p in drawn for xy in p], log_x, log_y)
        if int_x:
            integer_ticks(ax.xaxis, [x for _, p in drawn for x, _ in p])
    save(fig, path, wrote)


# --- bench gi ---------------------------------------------------------------------------------

GI_POINT_KEYS = ["method", "sweep", "label", "spp", "block", "vpls", "frame_ms", "gi_ms", "trees_ms", "vpls_ms",
                 "rmse", "levels_per_traversal"]


def read_bench_gi(folder):
    path = os.path.join(folder, "points.json")
    run = read_json(path)
    if not isinstance(run, dict):
        raise InputError(f"{path}: not a vplkit bench gi result (not an object)")
    for key in ["scene", "width", "height", "points", "curves", "pareto_front", "vpl_count_curve"]:
        if key not in run:
            raise InputError(f"{path}: not a vplkit bench gi result: no \"{key}\"")
    for key in ["points", "curves", "pareto_front"]:
        if not isinstance(run[key], list):
            raise InputError(f"{path}: \"{key}\" is not a list")
    for i, p in enumerate(run["points"]):
        missing = [k for k in GI_POINT_KEYS if not isinstance(p, dict) or k not in p]
        if missing:
            raise InputError(f"{path}: point {i} has no {', '.join(missing)}")
        for k in GI_POINT_KEYS[3:]:
            if p[k] is not None and not isinstance(p[k], (int, float)):
                raise InputError(f"{path}: point {i}: \"{k}\" is not a number")
    for c in run["curves"]:
        if not isinstance(c, dict) or not all(k in c for k in ["name", "quality_sweep", "sweeps", "samples"]):
            raise InputError(f"{path}: a curve without name, quality_sweep, sweeps or samples")
    for i in run["pareto_front"]:
        if not isinstance(i, int) or not 0 <= i < len(run["points"]):
            raise InputError(f"{path}: pareto_front holds {i!r}, not the index of a point")
    fronts = run.setdefault("method_fronts", {})
    if not isinstance(fronts, dict):
        raise InputError(f"{path}: \"method_fronts\" is not an object")
    for method, indices in fronts.items():
        if not isinstance(indices, list) or not all(isinstance(i, int) and 0 <= i < len(run["points"]) for i in indices):
            raise InputError(f"{path}: method_fronts[{method!r}] is not a list of indices of points")
    return run


def variant(point, curve):
    return "quality" if point["sweep"] == curve["quality_sweep"] else point["sweep"]


def variant_style(key):
    """(legend entry, marker, line style or None) of a variant; a sweep this script does not know
    still shows, as stars."""
    return VARIANTS.get(key, (f"{key} sweep", "*", None))


def rmse_vs_time(run, folder, gi_only, wrote):
    """RMSE against frame time (or GI + tree time) of every comparable point (the VPL-count sweep
    places other budgets), log-log: colour by method, marker by variant; each method's own front
    as a wide pale staircase in its colour; the Pareto front of all by frame time (report.md's)
    ringed, joined by its staircase and labelled."""
    size = f"{run['width']}x{run['height']}"
    scene = short_name(run["scene"])

    def x_of(p):
        return number(p["gi_ms"]) + number(p["trees_ms"]) if gi_only else number(p["frame_ms"])

    points = [p for p in run["points"] if p["sweep"] != "vpls"]
    has_data = bool(placeable([x_of(p) for p in points], [number(p["rmse"]) for p in points], True, True))
    fig, ax = new_plot(f"{scene}: RMSE vs {'GI + tree time' if gi_only else 'frame time'} ({size})",
                       "GI + trees (ms, GPU)" if gi_only else "frame time (ms, GPU)", "RMSE (tonemapped)",
                       True, True, has_data)
    method_handles, variants_used = [], []
    for i, curve in enumerate(run["curves"]):
        colour = COLOURS[i % len(COLOURS)]
        mine = [p for p in points if p["method"] == curve["name"]]
        if mine:
            method_handles.append(Line2D([], [], color=colour, marker="o", label=curve["name"]))
        for key in dict.fromkeys(variant(p, curve) for p in mine):
            chosen = [p for p in mine if variant(p, curve) == key]
            xy = placeable([x_of(p) for p in chosen], [number(p["rmse"]) for p in chosen], True, True)
            if xy:
                _, marker, style = variant_style(key)
                ax.plot(*zip(*xy), color=colour, marker=marker, linestyle=style or "none", markersize=6)
                variants_used += [key] if key not in variants_used else []
    handles = method_handles
    for key in sorted(variants_used, key=lambda k: list(VARIANTS).index(k) if k in VARIANTS else len(VARIANTS)):
        name, marker, style = variant_style(key)
        handles.append(Line2D([], [], color="grey", marker=marker, linestyle=style or "none", label=name))
    if not gi_only:
        # Each method's own front (report.md's list): a staircase in its colour under the points.
        for i, curve in enumerate(run["curves"]):
            own = [run["points"][j] for j in run["method_fronts"].get(curve["name"], [])]
            xy = sorted(placeable([x_of(p) for p in own], [number(p["rmse"]) for p in own], True, True))
            if len(xy) > 1:
                ax.plot(*zip(*xy), color=COLOURS[i % len(COLOURS)], linestyle="-", linewidth=3, alpha=0.3,
                        drawstyle="steps-post", zorder=0)
        if any(len(v) > 1 for v in run["method_fronts"].values()):
            handles.append(Line2D([], [], color="grey", linewidth=3, alpha=0.3, label="a method's own front"))
        front = [run["points"][i] for i in run["pareto_front"]]
        front = sorted((p for p in front if placeable([x_of(p)], [number(p["rmse"])], True, True)), key=x_of)
        if front:
            xs, ys = [x_of(p) for p in front], [number(p["rmse"]) for p in front]
            ax.plot(xs, ys, color="black", linestyle="--", linewidth=1, drawstyle="steps-post", zorder=1)
            ax.plot(xs, ys, marker="o", markersize=14, markerfacecolor="none", markeredgecolor="black",
                    markeredgewidth=1.5, linestyle="none", zorder=3)
            for k, (p, x, y) in enumerate(zip(front, xs, ys)):
                # Points within 5% of each other on both axes: their labels stacked, not overprinted.
                near = sum(1 for x0, y0 in zip(xs[:k], ys[:k]) if abs(math.log(x / x0)) < 0.05
                           and abs(math.log(y / y0)) < 0.05)
                ax.annotate(p["label"], (x, y), textcoords="offset points", xytext=(8, 8 + 11 * near), fontsize=8)
            handles.append(Line2D([], [], color="black", linestyle="--", marker="o", markerfacecolor="none",
                                  markersize=10, label="Pareto front (report.md)"))
    if handles and has_data:
        ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    save(fig, os.path.join(folder, "rmse_vs_gi_time.png" if gi_only else "rmse_vs_time.png"), wrote)


def select(run, method, sweep):
    return [p for p in run["points"] if p["method"] == method and p["sweep"] == sweep]


def with_base(run, method, sweep, key):
    """A curve's points of `sweep` and its 8 spp quality point, sorted by `key`."""
    points = select(run, method, sweep) + [p for p in select(run, method, "spp") if p["spp"] == 8]
    return sorted(points, key=lambda p: number(p[key]))


def budget_check(run, folder, wrote):
    """The budget chooser's check (report.md's table): the choice's measured RMSE and the best
    measured within each budget B; the choice's measured and predicted time against B."""
    rows = run.get("budget_check") or []
    if not isinstance(rows, list) or not rows:
        return
    for i, r in enumerate(rows):
        if not isinstance(r, dict) or not all(k in r for k in ["budget_ms", "measured_ms", "predicted_ms",
                                                                "measured_rmse", "best_rmse"]):
            raise InputError(f"points.json: budget_check row {i} lacks a budget_ms, measured_ms, predicted_ms, "
                             f"measured_rmse or best_rmse")
    scene = short_name(run["scene"])
    size = f"{run['width']}x{run['height']}"
    # The rows as calibrated (scale 1) and with the drift's correction (another scale).
    models = [("calibrated", [r for r in rows if number(r.get("scale", 1)) == 1]),
              ("drift-scaled", [r for r in rows if number(r.get("scale", 1)) != 1])]
    models = [(name, chosen) for name, chosen in models if chosen]
    budgets = [number(r["budget_ms"]) for r in models[0][1]]
    with_best = [r for r in models[0][1] if r["best_rmse"] is not None]
    rmse_series, time_series = [], []
    for name, chosen in models:
        xs = [number(r["budget_ms"]) for r in chosen]
        rmse_series.append((f"chosen ({name}), measured", xs, [number(r["measured_rmse"]) for r in chosen]))
        time_series += [(f"chosen ({name}), measured", xs, [number(r["measured_ms"]) for r in chosen]),
                        (f"chosen ({name}), predicted", xs, [number(r["predicted_ms"]) for r in chosen])]
    line_plot(os.path.join(folder, "budget_rmse.png"), f"{scene}: the budget's choice vs the best within B ({size})",
              "budget B (ms, GPU)", "RMSE (tonemapped)",
              rmse_series + [("best measured within B", [number(r["budget_ms"]) for r in with_best],
                              [number(r["best_rmse"]) for r in with_best])], False, True, wrote)
    line_plot(os.path.join(folder, "budget_time.png"), f"{scene}: the budget's choice, frame time ({size})",
              "budget B (ms, GPU)", "frame time (ms, GPU)",
              time_series + [("B", budgets, budgets), ("1.15 B", budgets, [1.15 * b for b in budgets])],
              False, False, wrote)


def bench_gi(folder, args):
    run = read_bench_gi(folder)
    scene = short_name(run["scene"])
    wrote = []
    rmse_vs_time(run, folder, False, wrote)
    rmse_vs_time(run, folder, True, wrote)
    budget_check(run, folder, wrote)
    levels = [(c["name"], [number(p["spp"]) for p in select(run, c["name"], "spp")],
               [number(p["levels_per_traversal"]) for p in select(run, c["name"], "spp")])
              for c in run["curves"] if c["samples"]]
    line_plot(os.path.join(folder, "levels.png"), f"{scene}: tree levels per traversal", "samples per pixel",
              "levels per traversal", levels, True, False, wrote, int_x=True)
    for time in (False, True):
        series = []
        for c in run["curves"]:
            if "block" in c["sweeps"]:
                points = with_base(run, c["name"], "block", "block")
                series.append((c["name"], [number(p["block"]) for p in points],
                               [number(p["gi_ms"] if time else p["rmse"]) for p in points]))
        line_plot(os.path.join(folder, "block_size_time.png" if time else "block_size_rmse.png"),
                  f"{scene}: cut block size vs {'GI time' if time else 'RMSE'} (8 spp)", "block size k (pixels)",
                  "GI time (ms, GPU)" if time else "RMSE (tonemapped)", series, True, False, wrote, int_x=True)
    curve = run["vpl_count_curve"]
    points = with_base(run, curve, "vpls", "vpls")
    vpls = [number(p["vpls"]) for p in points]
    line_plot(os.path.join(folder, "vpl_count_build_time.png"), f"{scene}: VPL count vs build time", "VPLs",
              "GPU time (ms)", [("trees (keys, sort, leaves, light tree, SST)", vpls,
                                 [number(p["trees_ms"]) for p in points]),
                                ("VPL generation", vpls, [number(p["vpls_ms"]) for p in points]),
                                (f"{curve} GI, 8 spp", vpls, [number(p["gi_ms"]) for p in points])],
              True, True, wrote)
    return wrote


# --- bench direct, sequence --------------------------------------------------------------------

def bench_direct(folder, args):
    path = os.path.join(folder, "points.csv")
    rows = read_csv(path, {"scene": str, "width": str, "height": str, "sampler": str, "spp": float,
                           "direct_ms": float, "relative_rmse": float})
    scene = short_name(rows[0]["scene"])
    size = f"{rows[0]['width']}x{rows[0]['height']}"
    samplers = list(dict.fromkeys(r["sampler"] for r in rows))
    wrote = []
    for key, x_label, name in [("direct_ms", "direct-light GPU time (ms)", "time"),
                               ("spp", "samples per pixel", "spp")]:
        series = [(s, [r[key] for r in rows if r["sampler"] == s], [r["relative_rmse"] for r in rows
                                                                    if r["sampler"] == s]) for s in samplers]
        line_plot(os.path.join(folder, f"rmse_vs_{name}.png"),
                  f"{scene}: direct light, relative RMSE vs {'time' if key == 'direct_ms' else 'samples per pixel'}"
                  f" ({size})", x_label, "relative RMSE", series, True, True, wrote, int_x=key == "spp")
    return wrote


def sequence(folder, args):
    path = os.path.join(folder, "metrics.csv")
    rows = read_csv(path, {"frame": float, "mean_abs_error": float, "mean_abs_error_change": float})
    frames = [r["frame"] for r in rows]
    has_data = bool(placeable(frames, [r["mean_abs_error"] for r in rows], False, False))
    fig, ax = new_plot(f"{short_name(args.scene)}: temporal error of the indirect light ({len(rows)} frames)",
                       "frame", "Reinhard luminance error", False, False, has_data)
    for i, (key, name) in enumerate([("mean_abs_error", "|E| (mean absolute error)"),
                                     ("mean_abs_error_change", "|E'| (mean absolute error change)")]):
        xy = placeable(frames, [r[key] for r in rows], False, False)
        if xy:
            ax.plot(*zip(*xy), marker="o", color=COLOURS[i], label=name)
    if has_data:
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylim(bottom=0)
        ax.legend(fontsize=9)
    wrote = []
    save(fig, os.path.join(folder, "metrics.png"), wrote)
    return wrote


def main():
    parser = argparse.ArgumentParser(description="vplkit's plots from its benches' and sequences' CSV/JSON.")
    sub = parser.add_subparsers(dest="kind", required=True)
    for kind, what in [("bench-gi", "points.json"), ("bench-direct", "points.csv"), ("sequence", "metrics.csv")]:
        p = sub.add_parser(kind, help=f"plots from DIR/{what}")
        p.add_argument("dir", help="the command's output folder; the PNGs are written there")
        if kind == "sequence":
            p.add_argument("--scene", required=True, help="the scene's name, for the title")
    args = parser.parse_args()
    draw = {"bench-gi": bench_gi, "bench-direct": bench_direct, "sequence": sequence}[args.kind]
    try:
        if not os.path.isdir(args.dir):
            raise InputError(f"{args.dir}: no such folder")
        wrote = draw(args.dir, args)
    except InputError as e:
        print(f"plot.py: {e}", file=sys.stderr)
        return 1
    for path in wrote:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
