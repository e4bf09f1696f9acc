#!/usr/bin/env bash
# The decomposition on models the project did not make (issue 46): OpenArena's game levels from Debian's
# openarena-081-maps (Quake III BSP, converted to OBJ by bench/q3bsp_to_obj.cpp) and houses in the shape
# an IFC export has (scenes: ifc-house*, rooms given as cellvolume: meshes alone, glazed windows, door
# leaves missing, furniture, a shower and a wardrobe, a stair of each kind). Each is decomposed with
# `cpgi decompose` at the defaults (the houses also at each VOXEL given), one process per run under
# /usr/bin/time, as a Markdown table: CPU and wall seconds, peak memory, cells, portals, voxel faces
# between cells no portal covers, closed rooms (no portal, touching no other cell), the outside's pockets
# (space behind a sealed level's one-sided walls), whether every room is reachable from every other,
# and for the houses the portals between the storeys and the adjusted Rand index against the house's
# own rooms (`cpgi compare-cells SCENE auto SCENE`); whether the whole graph is connected (every cell,
# the outside too, reachable from every other), whether every cell is reachable or a closed room, the cells folded as space behind the geometry, the closed
# cells dropped because no triangle faces them (the inside of a brush), the portal pieces merged into one, and the pairs of cells with more than one portal (pair: count).
# MAP_VOXELS runs the maps at those voxel sizes too (the automatic one always).
# BAKE=1 also bakes every model with daylight at the defaults (`cpgi bake MODEL -o DIR --sky uniform --sun
# 0.3,1,0.2,500`, and again with `--time-limit LIMIT` when LIMIT is given), one process each under
# /usr/bin/time, as a second table: CPU seconds (user + sys), peak memory, texels, solve texels, shots, the
# unshot share, the energy (emitted, absorbed, escaped W), how far past the limit it ended (wall), and with
# REFS=DIR (a reference per model, DIR/MODEL, from `cpgi reference MODEL -o DIR/MODEL --sky uniform --sun
# 0.3,1,0.2,500 --texels 40000 --spp 1024`) the worst room's ratio of means and each room's. The maps are
# converted with --open-sky there (OPEN_SKY=0 keeps the sky faces, which seal a level from the daylight).
# UNLIMITED=0 (with LIMIT) runs only the bakes under --time-limit, for a loaded machine where a bake to
# the end takes too long. KEEP=DIR keeps what the runs made, to look at afterwards: the converted maps
# (DIR/MAP.obj, the baked ones DIR/MAP-open.obj), each decomposition (DIR/decompose-MODEL-VOXEL) and each
# bake (DIR/bake-MODEL-LIMIT).
#   [MAPS="oa_dm7 aggressor"] [HOUSES="ifc-house"] [MAP_VOXELS="0.12"] [BAKE=1 [LIMIT=120] [UNLIMITED=0] [REFS=DIR]]
#   [KEEP=DIR] [Q3_DATA=DIR]
#   bench/real_models.sh CPGI_BINARY [VOXEL ...]
# The maps need `apt-get install openarena-081-maps` (the script says so when they are missing); the
# converter is compiled into the work folder with the system's c++ (and Debian's libstb-dev) when no build
# of it is given (Q3BSP_TO_OBJ=path). The data stays outside the repo.
# Materials: the converter writes MAP.mtl beside MAP.obj, one material per shader named by its path
# (textures/base_light/ceil1_39). With Q3_DATA=DIR (a folder of the game's .pk3 archives: Debian's
# openarena-data has pak0.pk3 with the shader scripts) each material gets its texture's mean colour and
# the converter prints the light shaders (q3map_surfacelight) as --emit flags. A closed map (sky faces
# kept) has no daylight and no lamp of its own otherwise; to bake it by its own lights:
#   q3bsp_to_obj MAP.bsp MAP.obj --pk3 /usr/share/games/openarena/baseoa
#   # prints: light shaders (...): cpgi bake MAP.obj -o OUT --emit textures/.../light=100 ...
#   cpgi bake MAP.obj -o OUT --emit textures/.../light=100 ...   # W/m2 each; scale them to taste
set -euo pipefail
cpgi=${1:?usage: real_models.sh CPGI_BINARY [VOXEL ...]}
shift
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(0.05)
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pk3=${OPENARENA_PK3:-/usr/share/games/openarena/baseoa/pak1-maps.pk3}
keep=${KEEP:-}
[ -n "$keep" ] && mkdir -p "$keep"
maps=(${MAPS-oa_dm1 oa_dm4 oa_dm7 aggressor})
map_sizes=(${MAP_VOXELS-})
houses=(${HOUSES-ifc-house ifc-house-open-riser ifc-house-l-stair ifc-house-spiral})
data=()
[ -n "${Q3_DATA:-}" ] && data=(--pk3 "$Q3_DATA")

# One row: decompose SCENE (VOXEL 0 = automatic), then the figures from cells.json (and ARI for a house).
row() {
  local name=$1 scene=$2 voxel=$3 house=$4 out="$work/out"
  rm -rf "$out"
  /usr/bin/time -f "%e %U %S %M" -o "$work/time.txt" "$cpgi" decompose "$scene" -o "$out" --voxel "$voxel" \
    >"$work/log.txt" 2>&1 || { echo "| $name | $voxel | decompose failed: $(tail -1 "$work/log.txt") |"; return; }
  echo '{}' >"$work/cmp.json"
  if [ "$house" = 1 ]; then
    "$cpgi" compare-cells "$scene" auto "$scene" --voxel "$voxel" --json >"$work/cmp.json" 2>/dev/null ||
      echo '{}' >"$work/cmp.json"
  fi
  read -r wall user sys rss <"$work/time.txt"
  python3 - "$name" "$out/cells.json" "$work/cmp.json" "$house" "$wall" "$user" "$sys" "$rss" <<'PY'
import json, sys
name, cells_json, cmp_json, house = sys.argv[1:5]
wall, user, sys_, rss = map(float, sys.argv[5:])
d = json.load(open(cells_json)); c = json.load(open(cmp_json))
ch = d["checks"]
cells = {x["name"]: x for x in d["cells"]}
def kind(n):
    return "horizontal" if abs(n[1]) > 0.999 else "vertical" if abs(n[1]) < 0.001 else "tilted"
# Portals between storeys: joining two rooms whose lowest points are 1.5 m or more apart in height.
stair = [p for p in d["portals"] if "outside" not in p["cells"] and
         abs(cells[p["cells"][0]]["bounds_m"][0][1] - cells[p["cells"][1]]["bounds_m"][0][1]) > 1.5]
ari = c.get("adjusted_rand_index")
pairs = {}
for p in d["portals"]:
    pairs[tuple(p["cells"])] = pairs.get(tuple(p["cells"]), 0) + 1
rooms = [r["best_iou"] for r in c.get("matched_iou_per_cell", []) if r["cell"] != "outside"]
cols = [name, "%.3f" % d["parameters"]["voxel_m"], d["counts"]["cells"], d["counts"]["portals"],
        ch["leaking_faces"], ch.get("closed_rooms", "-"), ch.get("outside_pockets", "-"),
        "yes" if ch["connected"] else "NO", "yes" if ch.get("graph_connected") else "NO",
        {True: "yes", False: "NO"}.get(ch.get("reachable_or_closed"), "-"),
        ch.get("behind_geometry_folded", "-"), ch.get("unfaced_closed_dropped", "-"), ch.get("portal_pieces_merged", "-"),
        ch.get("leak_merges", "-"),
        (", ".join("%.2f m2 %s" % (p["area_m2"], kind(p["normal"])) for p in stair) or "none") if house == "1" else "-",
        ("%.3f" % ari if ari is not None else "none") if house == "1" else "-",
        "%.2f" % min(rooms) if house == "1" and rooms else "-",
        ", ".join("%s-%s: %d" % (a, b, n) for (a, b), n in sorted(pairs.items(), key=lambda x: -x[1]) if n > 1) or "none",
        "%.2f" % (user + sys_), "%.2f" % wall, "%.0f" % (rss / 1024)]
print("| " + " | ".join(str(x) for x in cols) + " |")
PY
  if [ -n "$keep" ]; then rm -rf "$keep/decompose-$name-$voxel" && cp -r "$out" "$keep/decompose-$name-$voxel"; fi
}

# One bake row: MODEL's daylit bake at the defaults (with EXTRA options), its figures from report.json.
bake_row() {
  local name=$1 scene=$2 limit=$3 out="$work/bake"
  rm -rf "$out"
  local extra=()
  [ "$limit" != "-" ] && extra=(--time-limit "$limit")
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S %M" -o "$work/btime.txt" "$cpgi" bake "$scene" -o "$out" --sky uniform \
    --sun 0.3,1,0.2,500 "${extra[@]}" >"$work/blog.txt" 2>&1 || { echo "| $name | $limit | bake failed: $(tail -1 "$work/blog.txt") |"; return; }
  t1=$(date +%s.%N)
  echo '{}' >"$work/bcmp.json"
  if [ -n "${REFS:-}" ] && [ -d "$REFS/$name" ]; then
    "$cpgi" compare-light "$out" "$REFS/$name" --scene "$scene" --json >"$work/bcmp.json" 2>/dev/null || echo '{}' >"$work/bcmp.json"
  fi
  read -r user sys rss <"$work/btime.txt"
  python3 - "$name" "$limit" "$out/report.json" "$work/bcmp.json" "$user" "$sys" "$rss" "$t0" "$t1" <<'PY'
import json, sys
name, limit, report, cmp_json = sys.argv[1:5]
user, sys_, rss, t0, t1 = map(float, sys.argv[5:])
r = json.load(open(report)); c = json.load(open(cmp_json))
e = r["energy"]
past = "%+.1f s" % (t1 - t0 - float(limit)) if limit != "-" else "-"
rooms = c.get("cells", [])
worst = max(rooms, key=lambda x: abs(x["ratio_of_means"] - 1)) if rooms else None
cols = [name, limit, "%.0f" % (user + sys_), "%.0f" % (rss / 1024), r["texels"], r.get("solve_texels", "-"),
        r["shots"], "%.3f %%" % (100 * r["unshot_fraction"]), "yes" if r.get("partial") else "no",
        "%.0f / %.0f / %.0f" % (e["emitted_w"], e["absorbed_w"], e["escaped_w"]), past,
        "%s %.3f" % (worst["name"], worst["ratio_of_means"]) if worst else "-",
        ", ".join("%s %.3f ± %.1f %%" % (x["name"], x["ratio_of_means"], 100 * x["reference_noise"]) for x in rooms) or "-"]
print("| " + " | ".join(str(x) for x in cols) + " |")
PY
  if [ -n "$keep" ]; then rm -rf "$keep/bake-$name-$limit" && cp -r "$out" "$keep/bake-$name-$limit"; fi
}

echo "| model | voxel m | cells | portals | leaking faces | closed rooms | outside pockets | rooms connected | graph connected | reachable or closed | folded behind | unfaced dropped | pieces merged | pairs merged | portals between storeys | ARI vs its rooms | worst room IoU | pairs with several portals | CPU s | wall s | peak MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for h in "${houses[@]}"; do
  "$cpgi" generate "$h" --volumes-only -o "$work/$h.glb" >/dev/null
  for v in 0 "${sizes[@]}"; do row "$h" "$work/$h.glb" "$v" 1; done
done
if [ ${#maps[@]} -gt 0 ]; then
  if [ ! -f "$pk3" ]; then
    echo "real_models.sh: no $pk3: install Debian's openarena-081-maps (apt-get install openarena-081-maps) or set OPENARENA_PK3" >&2
    exit 1
  fi
  conv=${Q3BSP_TO_OBJ:-}
  if [ -z "$conv" ]; then
    conv="$work/q3bsp_to_obj"
    c++ -O2 -std=c++20 -o "$conv" "$here/q3bsp_to_obj.cpp" -lgmp
  fi
  for m in "${maps[@]}"; do
    unzip -o -q -j "$pk3" "maps/$m.bsp" -d "$work"
    "$conv" "$work/$m.bsp" "$work/$m.obj" "${data[@]}" 2>/dev/null
    [ -n "$keep" ] && cp "$work/$m.obj" "$work/$m.mtl" "$keep/"
    for v in 0 "${map_sizes[@]}"; do row "$m" "$work/$m.obj" "$v" 0; done
  done
fi
[ "${BAKE:-0}" = 1 ] || exit 0
limits=(- ${LIMIT:-})
if [ "${UNLIMITED:-1}" = 0 ]; then
  [ -n "${LIMIT:-}" ] || { echo "real_models.sh: UNLIMITED=0 needs LIMIT" >&2; exit 1; }
  limits=("$LIMIT")
fi
echo
echo "| model | --time-limit s | CPU s | peak MB | texels | solve texels | shots | unshot | partial | emitted / absorbed / escaped W | ended past the limit (wall) | worst room | rooms: ratio of means ± reference noise |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for h in "${houses[@]}"; do
  for l in "${limits[@]}"; do bake_row "$h" "$work/$h.glb" "$l"; done
done
for m in "${maps[@]}"; do
  sky=(--open-sky)
  [ "${OPEN_SKY:-1}" = 0 ] && sky=()
  "$conv" "$work/$m.bsp" "$work/$m.obj" "${sky[@]}" "${data[@]}" 2>/dev/null
  [ -n "$keep" ] && cp "$work/$m.obj" "$keep/$m-open.obj" && cp "$work/$m.mtl" "$keep/"
  for l in "${limits[@]}"; do bake_row "$m" "$work/$m.obj" "$l"; done
done
