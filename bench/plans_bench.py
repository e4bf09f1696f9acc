#!/usr/bin/env python3
"""The bake methods over many random floor plans (issue 47 item 3, design.md §5 "Many layouts, not one").

For each seed: `cpgi generate plan --seed N`, one path-traced reference (`cpgi reference`, fixed density),
then every method's bake (global with the defaults; cells through each portal model on the plan's own
cells; cells on the automatic ones), each compared per room with `cpgi compare-light --json` (ratio of
means, relative RMSE, red/green and blue/green against the reference, the floor's step across every
portal). CPU seconds are user + system of each process (/usr/bin/time). Prints, per method, the
distribution over every room of every plan: median, 90th percentile and the worst room (which plan, which
room), and the same split by how many openings separate a room from the nearest lamp.

  bench/plans_bench.py --cpgi build/apps/cpgi --seeds 1-30 --work /tmp/plans [--spp 512] [--density 10]

Runs are kept in --work and skipped when their results are there, so an interrupted bench resumes where it
stopped and a table can be printed again (--table-only) from what has run, or after every bake is compared
again by a newer compare-light (--recompare; not while a bench runs in the same --work).
"""
import argparse
import json
import math
import os
import struct
import subprocess
import sys
import time

METHODS = {
    "global": [],
    "cells-binned": ["--method", "cells", "--cells", "{plan}", "--portals", "binned"],
    "cells-directional": ["--method", "cells", "--cells", "{plan}", "--portals", "directional"],
    "cells-diffuse": ["--method", "cells", "--cells", "{plan}", "--portals", "diffuse"],
    "cells-auto": ["--method", "cells", "--cells", "auto"],
}


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            seeds.extend(range(int(a), int(b) + 1))
        else:
            seeds.append(int(part))
    return seeds


def timed(cmd, log):
    """Runs cmd, its output to log; returns (ok, cpu seconds, wall seconds)."""
    timing = log + ".time"
    start = time.time()
    with open(log, "w") as out:
        rc = subprocess.call(["/usr/bin/time", "-f", "%U %S", "-o", timing] + cmd, stdout=out,
                             stderr=subprocess.STDOUT)
    wall = time.time() - start
    try:
        user, system = open(timing).read().split()[-2:]
        cpu = float(user) + float(system)
    except (OSError, ValueError):
        cpu = float("nan")
    return rc == 0, cpu, wall


def glb_json(path):
    """The JSON chunk of a .glb."""
    with open(path, "rb") as f:
        data = f.read()
    length, kind = struct.unpack_from("<II", data, 12)
    return json.loads(data[20:20 + length].decode())


def openings_from_lamp(plan_glb):
    """Per room, the openings between it and the nearest room with a lamp, from the glb's node names:
    portal:A:B[.window] nodes, and the rooms whose subtree holds a "lamp" node."""
    gltf = glb_json(plan_glb)
    nodes = gltf.get("nodes", [])
    edges, lit, rooms = [], set(), set()
    def walk(i, cell):
        name = nodes[i].get("name", "")
        if name.startswith("cell:"):
            cell = name[5:]
            rooms.add(cell)
        if cell and name.split("/")[-1].startswith("lamp"):
            lit.add(cell)
        for c in nodes[i].get("children", []):
            walk(c, cell)
    roots = set(range(len(nodes))) - {c for n in nodes for c in n.get("children", [])}
    for r in roots:
        walk(r, None)
    for n in nodes:
        name = n.get("name", "")
        if name.startswith("portal:"):
            a, b = name[7:].split(".")[0].split(":")[:2]
            edges.append((a, b))
    dist = {r: 0 for r in lit}
    frontier = list(lit)
    while frontier:
        nxt = []
        for r in frontier:
            for a, b in edges:
                for x, y in ((a, b), (b, a)):
                    if x == r and y not in dist:
                        dist[y] = dist[r] + 1
                        nxt.append(y)
        frontier = nxt
    return {r: dist.get(r, -1) for r in rooms}


def compare_run(cpgi, out, ref, glb, run):
    """compare-light of the bake in `out` against the reference, per room, into `run`."""
    cmp = subprocess.run([cpgi, "compare-light", out, ref, "--json", "--scene", glb], capture_output=True, text=True)
    if cmp.returncode == 0:
        j = json.loads(cmp.stdout)
        run["rel_rmse"] = j["rel_rmse_nonemissive"]
        run["cells"] = j["cells"]
        run["portal_seams"] = j.get("portal_seams")
        run.pop("compare_error", None)
    else:
        run["compare_error"] = cmp.stderr.strip()[-300:]


def recompare(args, seed):
    """Every bake of a plan compared again (a newer compare-light's figures); nothing baked."""
    folder = os.path.join(args.work, "plan-%d" % seed)
    record_path = os.path.join(folder, "record.json")
    if not os.path.exists(record_path):
        return None
    record = json.load(open(record_path))
    for method, run in record["runs"].items():
        if method != "reference" and run.get("ok"):
            compare_run(args.cpgi, os.path.join(folder, method), os.path.join(folder, "reference"),
                        os.path.join(folder, "plan.glb"), run)
    json.dump(record, open(record_path, "w"), indent=1)
    return record


def run_plan(args, seed):
    """Generates, references, bakes and compares one plan; returns its record (cached in its folder)."""
    folder = os.path.join(args.work, "plan-%d" % seed)
    record_path = os.path.join(folder, "record.json")
    record = json.load(open(record_path)) if os.path.exists(record_path) else {"seed": seed, "runs": {}}
    os.makedirs(folder, exist_ok=True)
    glb = os.path.join(folder, "plan.glb")
    if not os.path.exists(glb):
        subprocess.check_call([args.cpgi, "generate", "plan", "--seed", str(seed), "-o", glb],
                              stdout=subprocess.DEVNULL)
    record["openings_from_lamp"] = openings_from_lamp(glb)
    views = ["--view-size", args.view_size]
    ref = os.path.join(folder, "reference")
    if "reference" not in record["runs"]:
        ok, cpu, wall = timed([args.cpgi, "reference", glb, "-o", ref, "--density", str(args.density),
                               "--spp", str(args.spp), "-q"] + views, ref + ".log")
        record["runs"]["reference"] = {"ok": ok, "cpu_s": cpu, "wall_s": wall}
        json.dump(record, open(record_path, "w"), indent=1)
    if not record["runs"]["reference"]["ok"]:
        return record
    for method in args.methods:
        if method in record["runs"]:
            continue
        out = os.path.join(folder, method)
        options = [a.replace("{plan}", glb) for a in METHODS[method]]
        ok, cpu, wall = timed([args.cpgi, "bake", glb, "-o", out, "-q"] + options + views,
                              out + ".log")
        run = {"ok": ok, "cpu_s": cpu, "wall_s": wall}
        if ok:
            compare_run(args.cpgi, out, ref, glb, run)
        record["runs"][method] = run
        json.dump(record, open(record_path, "w"), indent=1)
        print("plan %d %-18s %s %6.1f CPU s" % (seed, method, "ok" if ok else "FAILED", cpu), file=sys.stderr)
    return record


def quantile(values, q):
    v = sorted(values)
    if not v:
        return float("nan")
    k = (len(v) - 1) * q
    lo = int(math.floor(k))
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def pct(x):
    return "-" if x is None or x != x else "%.1f" % (100.0 * x)


def ambient_shares(work, seed, method):
    """Per room, the share of its light the bake left to the ambient term at its stop (report.json's
    ambient_share), or {} where the bake did not say."""
    report = os.path.join(work, "plan-%d" % seed, method, "report.json")
    try:
        return json.load(open(report)).get("ambient_share") or {}
    except (OSError, ValueError):
        return {}


def method_rooms(records, method, work):
    """Per room of every plan the method baked: (mean error, RMSE without the reference's noise, R/G, B/G,
    "plan/room", openings from a lamp, the ambient term's share of its light or None, its light per m² in the
    reference against its plan's brightest room or None); the measured seams:
    (excess, over noise, "plan/portal", |excess| over the larger texel noise); CPU s."""
    rooms, seams, cpus = [], [], []
    for rec in records:
        run = rec["runs"].get(method)
        if not run or not run.get("ok") or "cells" not in run:
            continue
        cpus.append(run["cpu_s"])
        shares = ambient_shares(work, rec["seed"], method)
        brightest = max((c.get("reference_mean") or 0.0 for c in run["cells"]), default=0.0)
        for c in run["cells"]:
            if c["ratio_of_means"] is None:
                continue
            rooms.append((c["ratio_of_means"] - 1.0, c["rel_rmse_without_noise"], c.get("red_green_ratio"),
                          c.get("blue_green_ratio"), "%d/%s" % (rec["seed"], c["name"]),
                          rec["openings_from_lamp"].get(c["name"], -1), shares.get(c["name"]),
                          c["reference_mean"] / brightest if c.get("reference_mean") and brightest > 0 else None))
        for s in run.get("portal_seams") or []:
            if s["measured"]:
                tolerance = max(s["noise"], s["noise_reference"])
                seams.append((s["excess"], s["seam"], "%d/%s" % (rec["seed"], s["name"][7:]),
                              abs(s["excess"]) / tolerance if tolerance > 0 else float("inf")))
    return rooms, seams, cpus


def worst(rows, key, fmt):
    if not rows:
        return "-"
    r = max(rows, key=key)
    return fmt(r) + " (%s)" % r[4]


def complete(rec, methods):
    return all(rec["runs"].get(m, {}).get("ok") and "cells" in rec["runs"][m] for m in methods)


def rooms_off_by_bucket(buckets, methods, count):
    """A table's rows: per method and bucket, the rooms off > 3 % of all, and the worst."""
    lines = []
    for method in methods:
        cols = []
        for b in range(count):
            v = buckets.get(method, {}).get(b, [])
            w = max(v, key=lambda r: abs(r[0])) if v else None
            cols.append("%d of %d%s" % (sum(1 for r in v if abs(r[0]) > 0.03), len(v),
                                        ", worst %+.1f (%s)" % (100 * w[0], w[4]) if w else ""))
        lines.append("| %s | %s |" % (method, " | ".join(cols)))
    return lines


def table(records, methods, work):
    """The distributions over the plans every method has baked and been compared on (so that the rows
    compare the methods on the same rooms), and a line naming the plans left out."""
    partial = [rec["seed"] for rec in records if not complete(rec, methods)]
    records = [rec for rec in records if complete(rec, methods)]
    lines = ["| method | plans | rooms | mean error, median / p90 / worst (plan/room) | rooms off > 3 % | "
             "RMSE without ref. noise, median / p90 / worst | colour off > 3 % (R/G or B/G) | worst R/G | "
             "worst B/G | seams over noise | worst seam: excess, over its noise (plan/portal) | CPU s, median plan / total |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    split, by_share, by_level = {}, {}, {}
    for method in methods:
        rooms, seams, cpus = method_rooms(records, method, work)
        if not rooms:
            lines.append("| %s | 0 |" % method + " |" * 10)
            continue
        err = [abs(r[0]) for r in rooms]
        rmse = [r[1] for r in rooms if r[1] is not None]
        rg = [r for r in rooms if r[2] is not None]
        bg = [r for r in rooms if r[3] is not None]
        colour_off = sum(1 for r in rooms if (r[2] is not None and abs(r[2] - 1) > 0.03) or
                         (r[3] is not None and abs(r[3] - 1) > 0.03))
        # The seam farthest past its tolerance: the reference's texel noise in a room lit through two or
        # three openings reaches tens of per cent at 512 paths, so the largest excess alone is its noise.
        worst_seam = max(seams, key=lambda s: s[3]) if seams else None
        lines.append("| %s | %d | %d | %s / %s / %s | %d | %s / %s / %s | %d | %s | %s | %d of %d | %s | %.1f / %.0f |" % (
            method, len(cpus), len(rooms), pct(quantile(err, 0.5)), pct(quantile(err, 0.9)),
            worst(rooms, lambda r: abs(r[0]), lambda r: "%+.1f" % (100 * r[0])),
            sum(1 for e in err if e > 0.03),
            pct(quantile(rmse, 0.5)), pct(quantile(rmse, 0.9)),
            worst([r for r in rooms if r[1] is not None], lambda r: r[1], lambda r: pct(r[1])),
            colour_off,
            worst(rg, lambda r: abs(r[2] - 1), lambda r: "%.3f" % r[2]),
            worst(bg, lambda r: abs(r[3] - 1), lambda r: "%.3f" % r[3]),
            sum(1 for s in seams if s[1]), len(seams),
            "%+.1f %%, %.1f× its noise (%s)" % (100 * worst_seam[0], worst_seam[3], worst_seam[2])
            if worst_seam else "-",
            quantile(cpus, 0.5), sum(cpus)))
        for r in rooms:
            split.setdefault(method, {}).setdefault(min(r[5], 3), []).append(abs(r[0]))
            if r[6] is not None:
                bucket = 0 if r[6] < 0.1 else 1 if r[6] < 0.3 else 2
                by_share.setdefault(method, {}).setdefault(bucket, []).append(r)
            if r[7] is not None:
                bucket = 0 if r[7] >= 1e-2 else 1 if r[7] >= 1e-3 else 2
                by_level.setdefault(method, {}).setdefault(bucket, []).append(r)
    lines += ["", "Mean error per room by openings from the nearest lamp (median / worst |ratio of means - 1|, %, "
              "rooms):", "", "| method | lit (0) | 1 | 2 | 3 or more |", "|---|---|---|---|---|"]
    for method in methods:
        cols = []
        for d in range(4):
            v = split.get(method, {}).get(d, [])
            cols.append("%s / %s (%d)" % (pct(quantile(v, 0.5)), pct(max(v)) if v else "-", len(v)))
        lines.append("| %s | %s |" % (method, " | ".join(cols)))
    lines += ["", "Rooms by the share of their light the bake left to the ambient term at its stop (report.json's "
              "ambient_share; over 0.1 the stop per room was refused and then bounded): rooms off > 3 % of all, "
              "and the worst:", "", "| method | share < 0.1 | 0.1–0.3 | ≥ 0.3 |", "|---|---|---|---|"]
    lines += rooms_off_by_bucket(by_share, methods, 3)
    lines += ["", "Rooms by their light per m² in the reference against their plan's brightest room (below 10⁻³, ten "
              "stops down, a room is black at any exposure that shows the lit ones): rooms off > 3 % of all, and "
              "the worst:", "", "| method | ≥ 10⁻² | 10⁻³–10⁻² | < 10⁻³ |", "|---|---|---|---|"]
    lines += rooms_off_by_bucket(by_level, methods, 3)
    auto = []
    for rec in records:
        report = os.path.join(work, "plan-%d" % rec["seed"], "cells-auto", "report.json")
        if os.path.exists(report):
            auto.append((json.load(open(report)).get("cells"), len(rec["openings_from_lamp"])))
    if auto:
        lines += ["", "Automatic cells (`--cells auto`) against the plan's rooms: %d plans, as many in %d, one fewer in "
                  "%d, more in %d, two or more fewer in %d." % (
                      len(auto), sum(1 for c, r in auto if c == r), sum(1 for c, r in auto if c == r - 1),
                      sum(1 for c, r in auto if c > r), sum(1 for c, r in auto if c <= r - 2))]
    ref_cpu = [rec["runs"]["reference"]["cpu_s"] for rec in records if rec["runs"].get("reference", {}).get("ok")]
    lines += ["", "Reference: %d plans, CPU s median %.0f, total %.0f." % (len(ref_cpu), quantile(ref_cpu, 0.5),
                                                                        sum(ref_cpu))]
    lines.append("Plans: %s%s." % (", ".join(str(rec["seed"]) for rec in records),
                                   "; left out, not every method done: " + ", ".join(map(str, partial))
                                   if partial else ""))
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cpgi", default=os.path.join(os.path.dirname(__file__), "..", "build", "apps", "cpgi"))
    p.add_argument("--seeds", default="1-30", help="e.g. 1-30 or 1,4,9")
    p.add_argument("--work", default="/tmp/cpgi-plans-bench", help="folder for the runs (kept, resumed)")
    p.add_argument("--spp", type=int, default=512, help="reference paths per texel")
    p.add_argument("--density", type=float, default=10, help="the reference's texels per metre")
    p.add_argument("--view-size", default="160x120", help="bake and reference pictures (small: seconds)")
    p.add_argument("--methods", default=",".join(METHODS), help="comma-separated, of: " + ", ".join(METHODS))
    p.add_argument("--table-only", action="store_true", help="print the table of the runs in --work, run nothing")
    p.add_argument("--recompare", action="store_true",
                   help="compare every bake in --work again with this --cpgi (no bake), then print the table")
    args = p.parse_args()
    args.methods = args.methods.split(",")
    for m in args.methods:
        if m not in METHODS:
            p.error("unknown method " + m)
    records = []
    for seed in parse_seeds(args.seeds):
        path = os.path.join(args.work, "plan-%d" % seed, "record.json")
        if args.recompare:
            record = recompare(args, seed)
            if record:
                records.append(record)
            continue
        if args.table_only:
            if os.path.exists(path):
                records.append(json.load(open(path)))
            continue
        records.append(run_plan(args, seed))
    print(table(records, args.methods, args.work))


if __name__ == "__main__":
    main()
