#!/usr/bin/env python3
"""Speed against accuracy for cpgi (design.md §5): for each scene and atlas resolution, bake with every
method, bake the reference on the same atlas, and put seconds beside the relative RMSE against it.

Writes OUT/results.json, OUT/results.csv and OUT/table.md (the thesis's Table 9.1 layout with our figures),
OUT/report/report.html (the last bake in 3D against its reference, with the speed-against-accuracy chart of
every row: `cpgi compare-light --report --bench`), and with --plot one error-against-seconds plot per scene (PNG and SVG) by bench/plot_speed_accuracy.py, which
also plots an existing results.csv on its own. Plotting needs matplotlib (`apt-get install python3-matplotlib`).

  bench/speed_accuracy.py --cpgi build/apps/cpgi --out out/bench --scenes seed1,seed3 --reps 3 --plot

At large atlases (seed3 at 64² has 4.9 M texels) a full reference takes hours: --ref-texels N traces a
stratified sample of N texels (`cpgi reference --texels`), and compare-light estimates the RMSE on it, with the
sampling error in `rel_rmse_sampling_error` (bench/RESULTS.md, "Sparse reference").

With --truth N, every bake is also compared against one reference per scene at N² texels per quad (a
--truth-texels sample at --truth-spp), read at its texels through the scene (compare-light --scene): the
error against the light itself, per cell, at whatever atlas the bake had (OUT/table_truth.md). The
resolution "auto" (bake --density auto) is compared that way only, no reference sharing its atlas.

  bench/speed_accuracy.py --out out/t91 --resolutions 16,32,64,density,auto --truth 64 \
      --methods global-hemicube,cells-binned --plot

Timing: every bake is run --reps times in one run of this script and the median kept (2 noisy cores);
compare methods as ratios within one run, never across runs or machines.
"""
import argparse
import csv
import json
import os
import resource
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
    "cells-binned": ["--method", "cells", "--cells", "{scene}", "--portals", "binned"],
    # Each backend alone (issue 47 item 4): every shot by GL item buffers, the interreflection of a
    # two-level solve too (--indirect-solver gpu; auto gives it to rays on a software rasterizer), or every
    # shot by Embree rays with no GL at all.
    "global-gl": ["--method", "global", "--backend", "gl", "--indirect-solver", "gpu"],
    "global-rays": ["--method", "global", "--backend", "rays"],
    "cells-gl": ["--method", "cells", "--cells", "{scene}", "--backend", "gl", "--indirect-solver", "gpu"],
    "cells-rays": ["--method", "cells", "--cells", "{scene}", "--backend", "rays"],
}


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, log):
    """Runs cmd; returns (process, wall seconds). run.cpu holds the CPU seconds it used (all its threads):
    steadier than wall time on a shared machine."""
    started, cpu = time.monotonic(), cpu_of_children()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    elapsed = time.monotonic() - started
    run.cpu = cpu_of_children() - cpu
    with open(log, "a") as f:
        f.write("$ " + " ".join(cmd) + f"\n# exit {proc.returncode}, {elapsed:.2f} s\n{proc.stdout}{proc.stderr}\n")
    return proc, elapsed


def atlas_args(res):
    if res == "auto":
        return ["--density", "auto"]
    return ["--density", res[len("density"):] or "10"] if res.startswith("density") else ["--texels-per-quad", res]


def truth_figures(err):
    """compare-light's figures against the truth reference: the whole scene's and per cell (the RMSE
    without the reference's own noise, and the ratio of means)."""
    return {"truth_rel_rmse": err["rel_rmse"],
            "truth_cells": {c["name"]: c.get("rel_rmse_without_noise", c["rel_rmse"]) for c in err.get("cells", [])},
            "truth_ratio": {c["name"]: c["ratio_of_means"] for c in err.get("cells", [])}}


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
    ap.add_argument("--ref-texels", type=int, default=0,
                    help="trace the reference on a sample of this many texels (0 = all)")
    ap.add_argument("--truth", default="",
                    help="also compare every bake (and only so 'auto', whose atlas no reference shares) against "
                         "one reference per scene at this many texels per quad, read at its texels through the "
                         "scene (compare-light --scene): the error against the light itself, per cell")
    ap.add_argument("--truth-texels", type=int, default=4000, help="texels the truth reference traces")
    ap.add_argument("--truth-spp", type=int, default=4096, help="its samples per texel")
    ap.add_argument("--plot", action="store_true")
    ap.add_argument("--resume", action="store_true",
                    help="keep OUT/results.json's rows and skip what they cover; reuse finished references")
    args = ap.parse_args()
    if args.ref_texels < 0:
        sys.exit("speed_accuracy: --ref-texels must be 0 (all texels) or positive")
    ref_sample = ["--texels", str(args.ref_texels)] if args.ref_texels > 0 else []

    os.makedirs(args.out, exist_ok=True)
    log = os.path.join(args.out, "commands.log")
    results = os.path.join(args.out, "results.json")
    rows = json.load(open(results)) if args.resume and os.path.exists(results) else []
    done = {(r["scene"], r["resolution"], r["method"]) for r in rows}
    last = None  # the last (bake, reference) compared, for OUT/report
    for scene in args.scenes.split(","):
        glb = os.path.join(args.out, scene + ".glb")
        if not os.path.exists(glb):
            proc, _ = run([args.cpgi, "generate", scene, "-o", glb], log)
            if proc.returncode:
                sys.exit(f"speed_accuracy: cannot generate {scene}: {proc.stderr.strip()}")
        truth_dir = os.path.join(args.out, f"{scene}-truth-{args.truth}") if args.truth else None
        if truth_dir and not (args.resume and os.path.exists(os.path.join(truth_dir, "report.json"))):
            proc, _ = run([args.cpgi, "reference", glb, "-o", truth_dir, "--texels-per-quad", args.truth,
                           "--texels", str(args.truth_texels), "--spp", str(args.truth_spp)], log)
            if proc.returncode:
                sys.exit(f"speed_accuracy: {scene}: truth reference failed: {proc.stderr.strip()}")
        for res in args.resolutions.split(","):
            methods = [m for m in args.methods.split(",") if (scene, res, m) not in done]
            if not methods:
                continue
            if res == "auto" and not truth_dir:
                sys.exit("speed_accuracy: resolution 'auto' needs --truth (no reference shares its atlas)")
            ref_dir = os.path.join(args.out, f"{scene}-{res}-reference") if res != "auto" else None
            ref_json = os.path.join(ref_dir, "report.json") if ref_dir else None
            reusable = ref_dir is None or (args.resume and os.path.exists(ref_json) and
                                           same_reference(json.load(open(ref_json)), args))
            if not reusable:
                proc, _ = run([args.cpgi, "reference", glb, "-o", ref_dir, "--spp", str(args.spp)] + atlas_args(res)
                              + ref_sample, log)
                if proc.returncode:
                    print(f"{scene} {res}: reference failed: {proc.stderr.strip()}", file=sys.stderr)
                    continue
            ref_report = json.load(open(ref_json)) if ref_json else {}
            for method in methods:
                extra = [a.replace("{scene}", glb) for a in METHODS[method]]
                out_dir = os.path.join(args.out, f"{scene}-{res}-{method}")
                times, solves, cpus, report = [], [], [], None
                for _ in range(args.reps):
                    proc, wall = run([args.cpgi, "bake", glb, "-o", out_dir, "--quiet"] + atlas_args(res) + extra, log)
                    if proc.returncode:
                        print(f"{scene} {res} {method}: {proc.stderr.strip()}", file=sys.stderr)
                        break
                    report = json.load(open(os.path.join(out_dir, "report.json")))
                    times.append(report["seconds"])
                    cpus.append(run.cpu)
                    solves.append(report["solve_seconds"])
                if report is None or len(times) < args.reps:
                    continue
                truth = {}
                if truth_dir:
                    proc, _ = run([args.cpgi, "compare-light", out_dir, truth_dir, "--json", "--scene", glb], log)
                    if proc.returncode:
                        print(f"{scene} {res} {method}: truth compare failed: {proc.stderr.strip()}", file=sys.stderr)
                        continue
                    truth = truth_figures(json.loads(proc.stdout))
                if ref_dir:
                    proc, _ = run([args.cpgi, "compare-light", out_dir, ref_dir, "--json"], log)
                    if proc.returncode:
                        print(f"{scene} {res} {method}: compare failed: {proc.stderr.strip()}", file=sys.stderr)
                        continue
                    err = json.loads(proc.stdout)
                    last = (out_dir, ref_dir)
                else:  # auto: no same-atlas figures (table.md and table91.md leave it out)
                    err = {"rel_rmse": None, "rel_mean_error": None}
                row = {
                    "scene": scene, "resolution": res, "method": method,
                    "seconds": statistics.median(times), "seconds_min": min(times), "seconds_max": max(times),
                    "solve_seconds": statistics.median(solves), "cpu_seconds": statistics.median(cpus),
                    "reps": args.reps,
                    "shots": report.get("shots"), "texels": report.get("texels"),
                    "unshot_fraction": report.get("unshot_fraction"),
                    "rel_rmse": err["rel_rmse"], "rel_mean_error": err["rel_mean_error"],
                    "reference_noise": ref_report.get("noise_rel_rmse", ref_report.get("noise")),
                    # Without the lamp texels, which dominate the all-texel figure (bench/RESULTS.md).
                    "rel_rmse_nonemissive": err.get("rel_rmse_nonemissive"),
                    "rel_mean_error_nonemissive": err.get("rel_mean_error_nonemissive"),
                    "reference_noise_nonemissive": ref_report.get("noise_nonemissive"),
                    "reference_seconds": ref_report.get("seconds"),
                    # The reference's texel sample (--ref-texels; texels_traced = texels when it traced all)
                    # and the error that sampling adds to rel_rmse (0 for a full reference).
                    "ref_texels": args.ref_texels,
                    "reference_texels_traced": ref_report.get("texels_traced", ref_report.get("texels")),
                    "rel_rmse_sampling_error": err.get("rel_rmse_sampling_error", 0.0),
                    "rel_rmse_nonemissive_sampling_error": err.get("rel_rmse_nonemissive_sampling_error"),
                    "same_atlas_reference": ref_dir is not None,
                    **truth,
                }
                rows.append(row)
                shown = row["rel_rmse"] if row["rel_rmse"] is not None else row["truth_rel_rmse"]
                print(f"{scene:6} {res:>9} {method:18} {row['seconds']:8.3f} s  rel_rmse {shown:.4f}", flush=True)
                save(rows, args.out)  # after every row: a long run stopped half-way keeps what it measured

    save(rows, args.out)
    if last and rows:
        # The report's chart plots the same-atlas figures; the auto rows have none.
        same_atlas = os.path.join(args.out, "results-same-atlas.json")
        json.dump([r for r in rows if r.get("rel_rmse") is not None], open(same_atlas, "w"), indent=1)
        proc, _ = run([args.cpgi, "compare-light", last[0], last[1], "--report", os.path.join(args.out, "report"),
                       "--bench", same_atlas], log)
        if proc.returncode:
            print(f"report: {proc.stderr.strip()}", file=sys.stderr)
    if args.plot and rows:
        plot(args.out)


def save(rows, out):
    json.dump(rows, open(os.path.join(out, "results.json"), "w"), indent=1)
    if rows:
        fields = list(dict.fromkeys(k for r in rows for k in r))
        with open(os.path.join(out, "results.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            w.writerows(rows)
    same_atlas = [r for r in rows if r.get("rel_rmse") is not None]
    write_table(same_atlas, os.path.join(out, "table.md"))
    write_table91(same_atlas, os.path.join(out, "table91.md"))
    if any(r.get("truth_cells") for r in rows):
        write_truth_table(rows, os.path.join(out, "table_truth.md"))


def same_reference(report, args):
    """Whether a finished reference was traced with this run's --spp and --ref-texels."""
    texels, traced = report.get("texels"), report.get("texels_traced", report.get("texels"))
    wanted = texels if args.ref_texels == 0 or texels is None else min(args.ref_texels, texels)
    return report.get("spp") == args.spp and traced == wanted


def write_table(rows, path):
    """Rows: scene × method; columns: resolutions; cells: 'seconds s / rel RMSE % (without lamps %)'."""
    resolutions = list(dict.fromkeys(r["resolution"] for r in rows))
    lines = ["| scene | method | " + " | ".join(f"{r}²" if r.isdigit() else r for r in resolutions) + " |",
             "|---|---|" + "---|" * len(resolutions)]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for method in dict.fromkeys(r["method"] for r in rows if r["scene"] == scene):
            cells = []
            for res in resolutions:
                hit = [r for r in rows if (r["scene"], r["method"], r["resolution"]) == (scene, method, res)]
                if not hit:
                    cells.append("–")
                    continue
                ne = hit[0].get("rel_rmse_nonemissive")
                cells.append(f"{hit[0]['seconds']:.2f} s / {100 * hit[0]['rel_rmse']:.2f}%" +
                             (f" ({100 * ne:.1f}%)" if ne is not None else ""))
            lines.append(f"| {scene} | {method} | " + " | ".join(cells) + " |")
    open(path, "w").write("\n".join(lines) + "\n")


# The thesis's Table 9.1 (seconds on a 2008 GeForce 6200, fixed iterations, its own scenes 1–3):
# (with cells and portals, without). Scene 3 at 128² was not run there either.
THESIS_91 = {
    ("seed1", "16"): (0.879, 1.127), ("seed1", "32"): (0.958, 1.341), ("seed1", "64"): (1.497, 2.662),
    ("seed1", "128"): (5.366, 11.871), ("seed2", "16"): (1.570, 2.362), ("seed2", "32"): (1.964, 2.735),
    ("seed2", "64"): (3.281, 5.834), ("seed2", "128"): (11.239, 26.875), ("seed3", "16"): (27.858, 31.189),
    ("seed3", "32"): (31.196, 36.272), ("seed3", "64"): (51.092, 77.298),
}


def write_table91(rows, path):
    """The thesis's Table 9.1 layout: one row per scene and resolution, the thesis's seconds with and
    without cells, then ours per method as 'seconds s (CPU s) / rel RMSE % / without lamps %', with the
    sampling error of the RMSE when the reference was a texel sample."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    lines = ["| scene | texels per quad | thesis with cells (s) | thesis without (s) | texels | " +
             " | ".join(methods) + " |", "|---|---|---|---|---|" + "---|" * len(methods)]
    order = lambda res: (0, int(res)) if res.isdigit() else (1, 0)  # 16², 32², …, then density
    for scene in sorted(dict.fromkeys(r["scene"] for r in rows)):
        for res in sorted(dict.fromkeys(r["resolution"] for r in rows if r["scene"] == scene), key=order):
            mine = {r["method"]: r for r in rows if (r["scene"], r["resolution"]) == (scene, res)}
            thesis = THESIS_91.get((scene, res))
            texels = next(iter(mine.values())).get("texels")
            cells = []
            for m in methods:
                r = mine.get(m)
                if r is None:
                    cells.append("–")
                    continue
                text = f"{r['seconds']:.1f} s"
                if r.get("cpu_seconds") is not None:
                    text += f" ({r['cpu_seconds']:.1f})"
                text += f" / {100 * r['rel_rmse']:.2f}%"
                if r.get("rel_rmse_sampling_error"):
                    text += f" ±{100 * r['rel_rmse_sampling_error']:.2f}"
                if r.get("rel_rmse_nonemissive") is not None:
                    text += f" / {100 * r['rel_rmse_nonemissive']:.1f}%"
                cells.append(text)
            label = f"{res}²" if res.isdigit() else res
            lines.append(f"| {scene} | {label} | " + (f"{thesis[0]:.3f} | {thesis[1]:.3f}" if thesis else "– | –") +
                         f" | {texels} | " + " | ".join(cells) + " |")
    open(path, "w").write("\n".join(lines) + "\n")


def write_truth_table(rows, path):
    """Rows: scene × resolution; per method 'seconds s (CPU s) / each cell's rel RMSE against the truth
    reference, without its noise' — the error a user sees, at any atlas, per room."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    lines = ["| scene | resolution | texels | " + " | ".join(methods) + " |", "|---|---|---|" + "---|" * len(methods)]
    order = lambda res: (0, int(res)) if res.isdigit() else (1, 0) if res.startswith("density") else (2, 0)
    for scene in sorted(dict.fromkeys(r["scene"] for r in rows)):
        for res in sorted(dict.fromkeys(r["resolution"] for r in rows if r["scene"] == scene), key=order):
            mine = {r["method"]: r for r in rows if (r["scene"], r["resolution"]) == (scene, res)}
            cells = []
            for m in methods:
                r = mine.get(m)
                if r is None or not r.get("truth_cells"):
                    cells.append("–")
                    continue
                per_cell = " / ".join(f"{k} {100 * v:.2f}" for k, v in sorted(r["truth_cells"].items()))
                cells.append(f"{r['seconds']:.1f} s ({r.get('cpu_seconds', 0):.1f}) / {per_cell} %")
            texels = next(iter(mine.values())).get("texels")
            label = f"{res}²" if res.isdigit() else res
            lines.append(f"| {scene} | {label} | {texels} | " + " | ".join(cells) + " |")
    open(path, "w").write("\n".join(lines) + "\n")


def plot(out):
    """bench/plot_speed_accuracy.py on the results just written (its own interpreter: Debian's matplotlib)."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "plot_speed_accuracy.py")
    proc = subprocess.run([script, os.path.join(out, "results.csv")])
    if proc.returncode:
        sys.exit("speed_accuracy: plotting failed")


if __name__ == "__main__":
    main()
