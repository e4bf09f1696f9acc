#!/usr/bin/env bash
# Cells from room volumes alone (issue 12 item 3): each procedural building of scenes/buildings.h written
# with its rooms only as cellvolume: meshes (`generate --volumes-only`), made into cells and portals by
# `decompose --from-volumes` (what `bake --cells SCENE` does), as a Markdown table: rooms, cells, portals
# against the building's openings, voxel faces between cells not covered by a portal, the command's CPU
# and wall seconds and peak
# memory (/usr/bin/time, one process), and compare-cells of the automatic decomposition against the
# volumes (adjusted Rand index over the whole interior and each side's coverage of it).
#   [BUILDINGS="house-open porch"] bench/volume_cells_bench.sh CPGI_BINARY [VOXEL ...]
set -euo pipefail
cpgi=${1:?usage: volume_cells_bench.sh CPGI_BINARY [VOXEL ...]}
shift
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(0.1 0.05)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| building | voxel m | rooms | cells | portals / openings | uncovered faces | CPU s | wall s | peak MB | auto vs volumes ARI | coverage auto / volumes |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
names=(${BUILDINGS:-house-open house-stair house-spiral house-gallery open-plan porch house-stair-closed})
for name in "${names[@]}"; do
  openings=$("$cpgi" generate "$name" -o "$work/$name-made.glb" | sed -E 's/.* ([0-9]+) portals/\1/')
  "$cpgi" generate "$name" --volumes-only -o "$work/$name.glb" >/dev/null
  for v in "${sizes[@]}"; do
    out="$work/$name-$v"
    /usr/bin/time -f "%e %U %S %M" -o "$work/time.txt" "$cpgi" decompose "$work/$name.glb" -o "$out" --voxel "$v" \
      --from-volumes >/dev/null 2>&1
    read -r wall user sys rss <"$work/time.txt"
    "$cpgi" compare-cells "$work/$name.glb" auto "$work/$name.glb" --voxel "$v" --json >"$work/cmp.json" 2>/dev/null
    python3 - "$name" "$v" "$out/cells.json" "$work/cmp.json" "$openings" "$wall" "$user" "$sys" "$rss" <<'PY'
import json, sys
name, voxel, cells_json, cmp_json, openings = sys.argv[1:6]
wall, user, sys_, rss = map(float, sys.argv[6:])
d = json.load(open(cells_json)); c = json.load(open(cmp_json))
rooms = [x for x in d["cells"] if x["name"] != "outside"]
ari = c["adjusted_rand_index"]
cols = [name, voxel, len(rooms), d["counts"]["cells"], "%d / %s" % (d["counts"]["portals"], openings),
        d["checks"]["leaking_faces"],
        "%.2f" % (user + sys_), "%.2f" % wall, "%.0f" % (rss / 1024),
        "none" if ari is None else "%.3f" % ari, "%.2f / %.2f" % (c["coverage_a"], c["coverage_b"])]
print("| " + " | ".join(str(x) for x in cols) + " |")
PY
  done
done
