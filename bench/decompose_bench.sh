#!/usr/bin/env bash
# Sweeps the voxel size on the procedural house and prints a Markdown table: voxels, stage seconds, wall
# and CPU seconds, peak resident memory (from /usr/bin/time, one process per size).
#   bench/decompose_bench.sh BUILD_DIR [VOXEL ...]
set -euo pipefail
build=${1:?usage: decompose_bench.sh BUILD_DIR [VOXEL ...]}
shift
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(0.2 0.15 0.1 0.075 0.05 0.04 0.03)
echo "| voxel m | voxels | inside | cells | portals | voxelize | classify | distance | watershed | merge | portals | assign | wall s | CPU s | peak MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for v in "${sizes[@]}"; do
  json=$(/usr/bin/time -f "%e %U %S %M" -o /tmp/decompose_bench_time.txt "$build/bench/decompose_bench" --voxel "$v")
  read -r wall user sys rss < /tmp/decompose_bench_time.txt
  python3 - "$json" "$wall" "$user" "$sys" "$rss" <<'PY'
import json, sys
d = json.loads(sys.argv[1]); wall, user, sys_, rss = map(float, sys.argv[2:])
s = d["stages_s"]
cols = [d["voxel_m"], d["voxels"], d["inside_voxels"], d["cells"], d["portals"]] + \
       ["%.2f" % s.get(k, 0.0) for k in ("voxelize", "classify", "distance", "watershed", "merge", "portals", "assign")] + \
       ["%.2f" % wall, "%.2f" % (user + sys_), "%.0f" % (rss / 1024)]
print("| " + " | ".join(str(c) for c in cols) + " |")
PY
done
