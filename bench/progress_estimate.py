#!/usr/bin/env python3
"""The solve's time-left estimate against the time that actually remained (issue 50, item 3).

Bakes each scene at the defaults through bench/progress_estimate.cpp, which records every progress
report with the wall and CPU seconds it came at, and prints a table: the estimate shown once 10 % of the
solve's CPU time had passed, against the CPU and wall seconds the solve then still took. CPU seconds are
the figure to read on a loaded machine: the estimate is made in them and said in wall seconds at the
last 20 s's CPU rate, so a load that changes later moves the wall truth but not the CPU one.

  bench/progress_estimate.py --build build --out /tmp/progress [--scenes seed1,seed2,...] [--at 0.1,0.5] [--gl]

--gl bakes every shot on the GL engine (the default on a machine without a GPU is the rays engine for the
interreflection).
"""
import argparse
import csv
import os
import subprocess
import sys

SCENES = ["seed1", "seed2", "seed3", "house-furnished", "office"]


def main_solve(rows):
    """The bake's own solve: the 'solve' reports after its last start (shots 0)."""
    starts = [i for i, r in enumerate(rows) if r["stage"] == "solve" and int(r["shots"]) == 0]
    if not starts:
        return []
    seg = []
    for r in rows[starts[-1]:]:
        if r["stage"] != "solve":
            break
        seg.append(r)
    return seg


def estimate_at(seg, share):
    """The first report with an estimate once `share` of the solve's CPU time had passed."""
    c0, c1 = float(seg[0]["cpu_s"]), float(seg[-1]["cpu_s"])
    w1 = float(seg[-1]["wall_s"])
    for r in seg:
        cpu, left = float(r["cpu_s"]), float(r["cpu_seconds_left"])
        if cpu >= c0 + share * (c1 - c0) and left >= 0.0 and float(r["fraction"]) < 1.0:
            wall = float(r["wall_s"])
            return {
                "at": (cpu - c0) / (c1 - c0),
                "shots": int(r["shots"]),
                "cpu_est": left,
                "cpu_true": c1 - cpu,
                "wall_est": float(r["seconds_left"]),
                "wall_true": w1 - wall,
                "shots_est": float(r.get("shots_left") or -1),
                "shots_true": int(seg[-1]["shots"]) - int(r["shots"]),
            }
    return None


def run(args, name):
    glb = os.path.join(args.out, name + ".glb")
    table = os.path.join(args.out, name + ".csv")
    if not os.path.exists(table) or args.again:
        subprocess.run([os.path.join(args.build, "apps", "cpgi"), "generate", name, "-o", glb], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run([os.path.join(args.build, "bench", "cpgi_progress_estimate"), glb,
                        os.path.join(args.out, name), table] + (["gl"] if args.gl else []), check=True)
    with open(table) as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="/tmp/progress_estimate")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--at", default="0.1,0.25,0.5", help="shares of the solve's CPU time")
    ap.add_argument("--again", action="store_true", help="bake again even where a CSV is there")
    ap.add_argument("--gl", action="store_true", help="every shot on the GL engine")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    shares = [float(s) for s in args.at.split(",")]
    print("| scene | solve CPU s | shots | at | shots left: estimate / true | estimate CPU s | true CPU s "
          "| CPU ratio | estimate wall s | true wall s | wall ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    worst = 1.0
    for name in args.scenes.split(","):
        seg = main_solve(run(args, name))
        if len(seg) < 2:
            print(f"| {name} | no solve reported | | | | | | | | | |")
            continue
        total = float(seg[-1]["cpu_s"]) - float(seg[0]["cpu_s"])
        for share in shares:
            e = estimate_at(seg, share)
            if not e:
                print(f"| {name} | {total:.1f} | {seg[-1]['shots']} | {share:.0%} | none | | | | | | |")
                continue
            ratio = e["cpu_est"] / e["cpu_true"] if e["cpu_true"] > 0 else float("inf")
            if share == shares[0]:
                worst = max(worst, ratio, 1.0 / ratio if ratio > 0 else float("inf"))
            wall = e["wall_est"] / e["wall_true"] if e["wall_true"] > 0 else float("inf")
            shots = f"{e['shots_est']:.0f} / {e['shots_true']}" if e["shots_est"] >= 0 else f"– / {e['shots_true']}"
            print(f"| {name} | {total:.1f} | {seg[-1]['shots']} | {e['at']:.0%} (shot {e['shots']}) | {shots} "
                  f"| {e['cpu_est']:.1f} | {e['cpu_true']:.1f} | {ratio:.2f} | {e['wall_est']:.1f} "
                  f"| {e['wall_true']:.1f} | {wall:.2f} |")
    print(f"\nworst CPU ratio at {shares[0]:.0%} of the solve: {worst:.2f}x "
          f"(target within 1.3x: {'met' if worst <= 1.3 else 'not met'})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
