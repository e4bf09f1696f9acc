#!/usr/bin/python3
"""Error against seconds, one plot per scene, from the results of bench/speed_accuracy.py.

Reads OUT/results.csv (or a tab-separated file with the same columns, or results.json) and writes
OUT/SCENE-speed-accuracy.png and .svg: two panels, relative RMSE against the reference over the non-emissive
texels (the figure to watch: the lamps dominate the other) and over all texels, against the whole bake's
median seconds, both axes logarithmic. One line per method (global-hemicube, global-hemisphere,
cells-diffuse, cells-directional when the results have it), each point labelled with its atlas resolution
(16² = 16×16 texels per quad; "density" = texels per metre); the reference's own noise is the dotted floor
below which the error cannot be resolved.

Needs matplotlib, which is not part of setup.sh (benchmarks are not in CI): apt-get install python3-matplotlib.
That installs it for Debian's /usr/bin/python3 (hence the first line), not for another python3 on the PATH.

  bench/plot_speed_accuracy.py out/bench/results.csv [-o DIR] [--scenes seed1,seed3]
"""
import argparse
import ast
import csv
import json
import os
import sys

# Fixed colours and markers, so a method looks the same in every scene's plot.
STYLE = {
    "global-hemicube": ("tab:blue", "o"),
    "global-hemisphere": ("tab:orange", "s"),
    "cells-diffuse": ("tab:green", "^"),
    "cells-directional": ("tab:red", "D"),
    "cells-binned": ("tab:purple", "v"),
}
NUMERIC = ("seconds", "seconds_min", "seconds_max", "solve_seconds", "rel_rmse", "rel_rmse_nonemissive",
           "rel_mean_error", "rel_mean_error_nonemissive", "reference_noise", "reference_noise_nonemissive")
PANELS = (("rel_rmse_nonemissive", "reference_noise_nonemissive", "non-emissive texels"),
          ("rel_rmse", "reference_noise", "all texels"))


def read_rows(path):
    """Rows as dicts with the numeric columns as floats (None when empty or absent)."""
    if path.endswith(".json"):
        rows = json.load(open(path))
    else:
        with open(path, newline="") as f:
            header = f.readline()
            f.seek(0)
            rows = list(csv.DictReader(f, delimiter="\t" if "\t" in header else ","))
    missing = [k for k in ("scene", "method", "resolution", "seconds", "rel_rmse") if rows and k not in rows[0]]
    if missing:
        sys.exit(f"plot_speed_accuracy: {path}: no column {', '.join(missing)} (not speed_accuracy.py output?)")
    for r in rows:
        for key in NUMERIC:
            value = r.get(key)
            r[key] = float(value) if value not in (None, "") else None
        # speed_accuracy.py --truth: per cell against one reference (a dict; the CSV holds its repr).
        cells = r.get("truth_cells")
        if isinstance(cells, str) and cells:
            cells = ast.literal_eval(cells)
        r["truth_worst_cell"] = max(cells.values()) if isinstance(cells, dict) and cells else None
    return rows


def resolution_label(res):
    return f"{res}²" if res.isdigit() else res


def plot_scene(plt, ticker, scene, rows, out):
    panels = PANELS
    if any(r.get("truth_worst_cell") is not None for r in rows):
        panels = PANELS + (("truth_worst_cell", None, "worst cell against the truth reference"),)
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 5), sharex=True)
    for ax, (key, noise_key, what) in zip(axes, panels):
        plotted = [r for r in rows if r.get(key) is not None and r["seconds"] is not None]
        if not plotted:
            ax.text(0.5, 0.5, f"no {key} in the results", ha="center", va="center", transform=ax.transAxes)
            ax.set_title(f"{scene}: {what}")
            continue
        for method in dict.fromkeys(r["method"] for r in plotted):
            colour, marker = STYLE.get(method, (None, "x"))
            pts = [r for r in plotted if r["method"] == method]  # in the order run: coarse to fine
            xs, ys = [r["seconds"] for r in pts], [100 * r[key] for r in pts]
            ax.plot(xs, ys, marker=marker, color=colour, label=method)
            for r, x, y in zip(pts, xs, ys):
                ax.annotate(resolution_label(r["resolution"]), (x, y), textcoords="offset points", xytext=(4, 4),
                            fontsize=7, color=colour)
        noise = [r[noise_key] for r in plotted if noise_key and r.get(noise_key)]
        if noise:
            ax.axhline(100 * max(noise), color="grey", linestyle=":", linewidth=1,
                       label="reference noise (largest)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis in (ax.xaxis, ax.yaxis):  # 4, 6, 10 rather than 4×10⁰
            axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
            axis.set_minor_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}" if f"{v:.1g}"[0] in "2468" else ""))
        ax.set_xlabel("seconds (whole bake, median of the repetitions)")
        ax.set_ylabel("relative RMSE against the reference (%)")
        ax.set_title(f"{scene}: {what}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    written = []
    for ext in ("png", "svg"):
        path = os.path.join(out, f"{scene}-speed-accuracy.{ext}")
        fig.savefig(path, dpi=100)
        written.append(path)
    plt.close(fig)
    return written


def plot_all(rows, out, scenes=None):
    """One figure per scene of `rows` (or of `scenes`); returns the paths written."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.ticker as ticker
    except ImportError:
        sys.exit("plot_speed_accuracy: needs matplotlib (apt-get install python3-matplotlib; run with /usr/bin/python3)")
    matplotlib.rcParams["svg.hashsalt"] = "cpgi"  # the same data give the same SVG
    os.makedirs(out, exist_ok=True)
    written = []
    for scene in scenes or dict.fromkeys(r["scene"] for r in rows):
        mine = [r for r in rows if r["scene"] == scene]
        if not mine:
            sys.exit(f"plot_speed_accuracy: no rows for scene {scene}")
        written += plot_scene(plt, ticker, scene, mine, out)
    return written


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", help="results.csv (or .tsv, .json) written by bench/speed_accuracy.py")
    ap.add_argument("-o", "--out", help="folder for the plots (default: beside the results)")
    ap.add_argument("--scenes", help="comma-separated; default: every scene in the results")
    args = ap.parse_args()
    if not os.path.exists(args.results):
        sys.exit(f"plot_speed_accuracy: {args.results}: no such file")
    rows = read_rows(args.results)
    if not rows:
        sys.exit(f"plot_speed_accuracy: {args.results}: no rows")
    out = args.out or os.path.dirname(os.path.abspath(args.results))
    for path in plot_all(rows, out, args.scenes.split(",") if args.scenes else None):
        print("wrote", path)


if __name__ == "__main__":
    main()
