#!/usr/bin/env python3
"""Speed against accuracy for cpgi (design.md §5): for each scene and atlas resolution, bake with every
method, bake the reference on the same atlas, and put seconds beside the relative RMSE against it.

Writes OUT/results.json, OUT/results.csv and OUT/table.md (the thesis's Table 9.1 layout with our figures),
and with --plot one error-against-seconds plot per scene (PNG and SVG; the Pareto front named).

  bench/speed_accuracy.py --cpgi build/apps/cpgi --out out/bench --scenes seed1,seed3 --reps 3 --plot

Timing: every bake is run --reps times in one run of this script and the median kept (2 noisy cores);
compare methods as ratios within one run, never across runs or machines.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import time

METHODS = {
    # name: extra bake arguments
    "global-hemicube": ["--method", "global", "--visibility", "hemicube"],
    "global-hemisphere": ["--method", "global", "--visibility", "hemisphere"],
    "cells-diffuse": ["--method", "cells", "--cells", "{scene}", "--portals", "diffuse"],
    "cells-directional": ["--method", "cells", "--cells", "{scene}", "--portals", "directional"],
}


def run(cmd, log):
    started = time.monotonic()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    elapsed = time.monotonic() - started
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + f"\n# exit {proc.returncode}, {elapsed:.2f} s\n{proc.stdout}{proc.stderr}\n")
    return proc, elapsed


def atlas_args(res):
    return ["--density", res[len("density"):] or "10"] if res.startswith("density") else ["--texels-per-quad", res]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cpgi", default="build/apps/cpgi")
    ap.add_argument("--out", default="out/bench")
    ap.add_argument("--scenes", default="seed1,seed2,seed3")
    ap.add_argument("--resolutions", default="16,32,64,128,density",
                    help="texels per quad, or 'density' / 'densityT' for T texels per metre")
    ap.add_argument("--methods", default="global-hemicube,global-hemisphere,cells-diffuse,cells-directional",
                    help="comma-separated, from: " + ", ".join(METHODS))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--spp", type=int, default=256, help="reference samples per texel")
    ap.add_argument("--plot", action="store_true")
    args = ap.parse_args()

    os.makedirs(args.out, exist_ok=True)
    log = os.path.join(args.out, "commands.log")
    rows = []
    for scene in args.scenes.split(","):
        glb = os.path.join(args.out, scene + ".glb")
        if not os.path.exists(glb):
            proc, _ = run([args.cpgi, "generate", scene, "-o", glb], log)
            if proc.returncode:
                sys.exit(f"speed_accuracy: cannot generate {scene}: {proc.stderr.strip()}")
        for res in args.resolutions.split(","):
            ref_dir = os.path.join(args.out, f"{scene}-{res}-reference")
            proc, _ = run([args.cpgi, "reference", glb, "-o", ref_dir, "--spp", str(args.spp)] + atlas_args(res), log)
            if proc.returncode:
                print(f"{scene} {res}: reference failed: {proc.stderr.strip()}", file=sys.stderr)
                continue
            ref_report = json.load(open(os.path.join(ref_dir, "report.json")))
            for method in args.methods.split(","):
                extra = [a.replace("{scene}", glb) for a in METHODS[method]]
                out_dir = os.path.join(args.out, f"{scene}-{res}-{method}")
                times, solves, report = [], [], None
                for _ in range(args.reps):
                    proc, wall = run([args.cpgi, "bake", glb, "-o", out_dir, "--quiet"] + atlas_args(res) + extra, log)
                    if proc.returncode:
                        print(f"{scene} {res} {method}: {proc.stderr.strip()}", file=sys.stderr)
                        break
                    report = json.load(open(os.path.join(out_dir, "report.json")))
                    times.append(report["seconds"])
                    solves.append(report["solve_seconds"])
                if report is None or len(times) < args.reps:
                    continue
                proc, _ = run([args.cpgi, "compare-light", out_dir, ref_dir, "--json"], log)
                if proc.returncode:
                    print(f"{scene} {res} {method}: compare failed: {proc.stderr.strip()}", file=sys.stderr)
                    continue
                err = json.loads(proc.stdout)
                row = {
                    "scene": scene, "resolution": res, "method": method,
                    "seconds": statistics.median(times), "seconds_min": min(times), "seconds_max": max(times),
                    "solve_seconds": statistics.median(solves), "reps": args.reps,
                    "shots": report.get("shots"), "texels": report.get("texels"),
                    "unshot_fraction": report.get("unshot_fraction"),
                    "rel_rmse": err["rel_rmse"], "rel_mean_error": err["rel_mean_error"],
                    "rel_rmse_nonemissive": err.get("rel_rmse_nonemissive"),
                    "rel_mean_error_nonemissive": err.get("rel_mean_error_nonemissive"),
                    "reference_noise": ref_report.get("noise_rel_rmse", ref_report.get("noise")),
                    "reference_seconds": ref_report.get("seconds"),
                }
                rows.append(row)
                print(f"{scene:6} {res:>9} {method:18} {row['seconds']:8.3f} s  rel_rmse {row['rel_rmse']:.4f}", flush=True)

    json.dump(rows, open(os.path.join(args.out, "results.json"), "w"), indent=1)
    if rows:
        with open(os.path.join(args.out, "results.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    write_table(rows, os.path.join(args.out, "table.md"))
    if args.plot:
        plot(rows, args.out)


def write_table(rows, path):
    """Rows: scene × method; columns: resolutions; cells: 'seconds s / rel RMSE %'."""
    resolutions = list(dict.fromkeys(r["resolution"] for r in rows))
    lines = ["| scene | method | " + " | ".join(f"{r}²" if r.isdigit() else r for r in resolutions) + " |",
             "|---|---|" + "---|" * len(resolutions)]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for method in dict.fromkeys(r["method"] for r in rows if r["scene"] == scene):
            cells = []
            for res in resolutions:
                hit = [r for r in rows if (r["scene"], r["method"], r["resolution"]) == (scene, method, res)]
                cells.append(f"{hit[0]['seconds']:.2f} s / {100 * hit[0]['rel_rmse']:.2f}%" if hit else "–")
            lines.append(f"| {scene} | {method} | " + " | ".join(cells) + " |")
    open(path, "w").write("\n".join(lines) + "\n")


def pareto(points):
    """Indices of the points no other point beats in both seconds and error."""
    front = []
    for i, (t, e) in enumerate(points):
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for j, (t2, e2) in enumerate(points) if j != i):
            front.append(i)
    return front


def plot(rows, out):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("speed_accuracy: --plot needs matplotlib (apt-get install python3-matplotlib; run with /usr/bin/python3)")
    for scene in dict.fromkeys(r["scene"] for r in rows):
        mine = [r for r in rows if r["scene"] == scene]
        fig, ax = plt.subplots(figsize=(7, 5))
        for method in dict.fromkeys(r["method"] for r in mine):
            pts = [r for r in mine if r["method"] == method]
            ax.plot([r["seconds"] for r in pts], [100 * r["rel_rmse"] for r in pts], "o-", label=method)
        front = pareto([(r["seconds"], r["rel_rmse"]) for r in mine])
        for i in front:
            r = mine[i]
            ax.annotate(f"{r['method']} {r['resolution']}", (r["seconds"], 100 * r["rel_rmse"]),
                        textcoords="offset points", xytext=(5, 5), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("seconds (whole bake, median)")
        ax.set_ylabel("relative RMSE against the reference (%)")
        ax.set_title(f"{scene}: error against time (Pareto front named)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        for ext in ("png", "svg"):
            fig.savefig(os.path.join(out, f"{scene}-pareto.{ext}"), dpi=120, bbox_inches="tight")
        plt.close(fig)


if __name__ == "__main__":
    main()
