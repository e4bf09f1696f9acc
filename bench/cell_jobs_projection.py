#!/usr/bin/python3
"""Projects the wall time of a cell-job bake (docs/cell-jobs.md) on 1..64 workers from one measured run.

    bench/cell_jobs_projection.py PLAN --job-overhead SECONDS [--plan-seconds S] [--first-shot-overhead S]
                                  [--sum S | --first-shot S] [--gather S] [--barrier S] [--dask-log LOG]
                                  [--straggle P] [--time-scale F]

Reads every round's cell summaries in PLAN (the binary records of radiosity/cells/cell_job_files.h: each
cell's measured job seconds and portal bytes) and every emitter group's first-shot record (its measured
seconds), and simulates, per worker count W:
  - the plan step (--plan-seconds, one worker),
  - the first shot as cpgi-dask runs it: the emitter groups in batches (2 per worker, contiguous runs by
    patches), list-scheduled longest first, each batch costing --first-shot-overhead (process, scene,
    global atlas, EGL) plus its groups' seconds; then their sum (--sum, one worker). With --first-shot S
    instead, the first shot is S seconds on one worker (the serial plan of before, for comparison),
  - the groups cpgi-dask makes of the cells (3 per worker, contiguous runs of texels along a breadth-first
    walk),
  - each round's jobs list-scheduled longest first onto the earliest free worker, each costing the fixed
    per-job overhead (process start, scene load, atlases of the group's cells and their neighbours) plus
    its cells' measured seconds,
  - a barrier between rounds and the gather after (one worker); with --dask-log, both as a cpgi-dask run
    measured them (its progress lines: each round's idle time before its first job, the median of them as
    the barrier, and the gather task's seconds),
  - stragglers: each job 2x slower with probability 5 % (mean of 20 draws).
Prints a Markdown table: workers, projected wall, speed-up against 1 worker, efficiency, critical path
(the slowest single job of each round, summed: no worker count goes below it).
"""
import argparse
import glob
import json
import os
import random
import re
import struct
import sys

sys.dont_write_bytecode = True  # apps/cpgi-dask is loaded for its partition(); no __pycache__ beside it


def read_summary(path):
    # format 4 (radiosity/cells/cell_job_files.cpp putFigures/putSendFigures): round, cell, solved, kept power,
    # kept RGB, reflector gain, shots, 7 doubles; sends; job seconds, portal bytes
    data = open(path, "rb").read()
    magic, version, kind, size = struct.unpack_from("<8sIIQ", data, 0)
    if magic != b"CPGICELL" or version != 4 or kind != 3 or size != len(data) - 32:
        sys.exit("%s: not a version 4 cell summary" % path)
    fmt = "<iiBd3ddi7d"
    p = struct.unpack_from(fmt, data, 24)
    at = 24 + struct.calcsize(fmt)
    (sends,) = struct.unpack_from("<I", data, at)
    at += 4 + sends * struct.calcsize("<iii3fdd3d")
    seconds, portal_bytes = struct.unpack_from("<dQ", data, at)
    if at + 16 != 24 + size:
        sys.exit("%s: summary layout not understood" % path)
    return {"round": p[0], "cell": p[1], "solved": p[2], "shots": p[8], "seconds": seconds,
            "portal_bytes": portal_bytes}


def read_group(path):
    data = open(path, "rb").read()
    magic, version, kind, size = struct.unpack_from("<8sIIQ", data, 0)
    if magic != b"CPGICELL" or version != 4 or kind != 5 or size != len(data) - 32:
        sys.exit("%s: not a version 4 first-shot group record" % path)
    group, cell, _, emitted, shots, seconds = struct.unpack_from("<iiQdid", data, 24)
    return {"group": group, "cell": cell, "shots": shots, "seconds": seconds}


def list_schedule(jobs, workers):
    free = [0.0] * workers
    for t in sorted(jobs, reverse=True):
        k = free.index(min(free))
        free[k] += t
    return max(free) if jobs else 0.0


def load_driver():
    import importlib.machinery
    import importlib.util
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "apps", "cpgi-dask")
    loader = importlib.machinery.SourceFileLoader("cpgi_dask", path)
    spec = importlib.util.spec_from_loader("cpgi_dask", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def simulate(rounds, groups_of, workers, overhead, barrier, straggle, rng):
    total = 0.0
    for cells in rounds:
        jobs = []
        for g in groups_of:
            t = overhead + sum(cells.get(c, 0.0) for c in g)
            if rng.random() < straggle:
                t *= 2.0
            jobs.append(t)
        total += list_schedule(jobs, workers) + barrier
    return total


def first_shot_wall(batches, seconds, workers, overhead, straggle, rng):
    jobs = []
    for b in batches:
        t = overhead + sum(seconds[g] for g in b)
        if rng.random() < straggle:
            t *= 2.0
        jobs.append(t)
    return list_schedule(jobs, workers)


def dask_log_figures(path):
    """The barrier (median idle time before a round's first job, rounds 2 on) and the gather's seconds, from
    cpgi-dask's progress lines."""
    idle, gather = [], None
    for line in open(path):
        m = re.match(r"cpgi-dask: round \d+: .*idle before it ([0-9.]+) s", line)
        if m:
            idle.append(float(m.group(1)))
        m = re.match(r"cpgi-dask: .*: \d+ rounds, gather ([0-9.]+) s", line)
        if m:
            gather = float(m.group(1))
    if not idle or gather is None:
        sys.exit("%s: no cpgi-dask progress lines with the idle time between rounds and the gather" % path)
    return sorted(idle)[len(idle) // 2], gather


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("plan")
    ap.add_argument("--job-overhead", type=float, required=True, help="seconds per job besides its cells")
    ap.add_argument("--plan-seconds", type=float, default=0.0, help="the plan step (one worker)")
    ap.add_argument("--first-shot-overhead", type=float, default=0.0,
                    help="seconds per first-shot job besides its groups' solves")
    ap.add_argument("--sum", type=float, default=0.0, help="the first shot's sum (one worker)")
    ap.add_argument("--first-shot", type=float, help="model the first shot as this many seconds on one worker")
    ap.add_argument("--gather", type=float, help="the gather (one worker; default 0)")
    ap.add_argument("--baseline-first-shot", type=float,
                    help="speed-up against 1 worker whose first shot is this many seconds in one solve (the "
                         "emitters shot together cost less than shot group by group)")
    ap.add_argument("--barrier", type=float, help="seconds between rounds (status, scheduling; default 0.3)")
    ap.add_argument("--dask-log", help="cpgi-dask's output of a run: the barrier and the gather as it measured "
                                       "them (an explicit --barrier or --gather wins)")
    ap.add_argument("--straggle", type=float, default=0.05)
    ap.add_argument("--groups-per-worker", type=int, default=3, help="cell groups per worker (cpgi-dask: 3)")
    ap.add_argument("--time-scale", type=float, default=1.0,
                    help="multiplies the measured cell seconds (jobs measured side by side on shared cores run "
                         "slower than one job alone on its machine)")
    args = ap.parse_args()
    barrier, gather = dask_log_figures(args.dask_log) if args.dask_log else (0.3, 0.0)
    args.barrier = barrier if args.barrier is None else args.barrier
    args.gather = gather if args.gather is None else args.gather
    print("barrier %.3f s a round, gather %.2f s%s" % (args.barrier, args.gather,
                                                      " (from %s)" % args.dask_log if args.dask_log else ""))
    plan = json.load(open(os.path.join(args.plan, "plan.json")))
    texels = [c["texels"] for c in plan["cells"]]
    neighbours = [c["neighbours"] for c in plan["cells"]]
    rounds, traffic = [], []
    for d in sorted(glob.glob(os.path.join(args.plan, "round-*")))[1:]:
        cells = {}
        bytes_ = 0
        for f in glob.glob(os.path.join(d, "*.summary")):
            s = read_summary(f)
            cells[s["cell"]] = s["seconds"] * args.time_scale
            bytes_ += s["portal_bytes"]
        rounds.append(cells)
        traffic.append(bytes_)
    driver = load_driver()
    partition = driver.partition
    group_files = sorted(glob.glob(os.path.join(args.plan, "first-shot", "group-*.shot")))
    emitters = [read_group(f) for f in group_files]
    group_seconds = [g["seconds"] * args.time_scale for g in emitters]
    weights = [1 + len(g["patches"]) for g in plan.get("first_shot_groups", [])]
    if args.first_shot is None and len(weights) != len(emitters):
        sys.exit("%s: %d emitter groups in plan.json, %d group records" % (args.plan, len(weights), len(emitters)))
    if emitters:
        print("first shot: %d emitter groups, %d shots, seconds: sum %.1f, max %.2f" %
              (len(emitters), sum(g["shots"] for g in emitters), sum(group_seconds), max(group_seconds)))
    cell_seconds = [t for r in rounds for t in r.values()]
    print("%d cells, %d rounds, cell job seconds: sum %.1f, max %.2f, median %.3f; portal traffic per round: "
          "%s kB" % (len(texels), len(rounds), sum(cell_seconds), max(cell_seconds),
                     sorted(cell_seconds)[len(cell_seconds) // 2], ", ".join("%.0f" % (b / 1e3) for b in traffic)))
    critical = sum(max(r.values()) + args.job_overhead + args.barrier for r in rounds)
    base = None
    print("\n| workers | groups | projected wall (s) | speed-up | efficiency | critical path (s) |")
    print("|---|---|---|---|---|---|")
    for w in (1, 2, 4, 8, 16, 32, 64):
        groups = partition(texels, neighbours, args.groups_per_worker * w)
        rng = random.Random(w)
        shot_batches = driver.batches(weights, 2 * w) if weights else []
        walls = []
        for _ in range(20):
            shot = (args.first_shot if args.first_shot is not None else
                    first_shot_wall(shot_batches, group_seconds, w, args.first_shot_overhead, args.straggle, rng) +
                    args.sum)
            walls.append(shot + simulate(rounds, groups, w, args.job_overhead, args.barrier, args.straggle, rng))
        wall = args.plan_seconds + args.gather + sum(walls) / len(walls)
        if base is None:
            base = wall
            if args.baseline_first_shot is not None:
                base = min(wall, wall - (sum(walls) / len(walls) - sum(
                    simulate(rounds, groups, w, args.job_overhead, args.barrier, args.straggle,
                             random.Random(w)) for _ in range(20)) / 20) + args.baseline_first_shot)
        shot_critical = (args.first_shot if args.first_shot is not None else
                         args.first_shot_overhead + max(group_seconds or [0.0]) + args.sum)
        print("| %d | %d | %.1f | %.2f | %.2f | %.1f |" % (w, len(groups), wall, base / wall, base / wall / w,
                                                          args.plan_seconds + shot_critical + args.gather + critical))


if __name__ == "__main__":
    main()
