#!/bin/bash
# Where the time of `cpgi bake --method cells` goes, before and after compiling the solver's programs once
# per context, and with --jobs 2. Mesa keeps compiled shaders in a disk cache (~/.cache/mesa_shader_cache);
# "cold" runs switch it off (MESA_SHADER_CACHE_DISABLE=true: a first run on a fresh machine or CI), "warm"
# runs use it. One line per run from report.json.
# Usage: bench/cells_speed.sh OLD_CPGI NEW_CPGI WORKDIR [REPEATS]   (OLD_CPGI may be "-" to skip it)
set -euo pipefail
old=$1 new=$2 work=$3 repeats=${4:-1}
mkdir -p "$work"
"$new" generate seed1 -o "$work/seed1.glb" > /dev/null
"$new" generate seed3 -o "$work/seed3.glb" > /dev/null

row() {  # label binary cache scene atlas-args extra-args
  local label=$1 bin=$2 cache=$3 scene=$4 atlas=$5 extra=$6
  local out="$work/out-$label-$cache-$scene"
  rm -rf "$out"
  MESA_SHADER_CACHE_DISABLE=$([ "$cache" = cold ] && echo true || echo false) \
    "$bin" bake "$work/$scene.glb" -o "$out" --method cells --cells "$work/$scene.glb" $atlas -q $extra
  python3 - "$out/report.json" "$label" "$cache" "$scene" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1])); t = r["timings"]
solves = sum(c["solves"] for c in r["cell_energy"])
print(f"{sys.argv[4]:6} {sys.argv[2]:10} {sys.argv[3]:5} {r['seconds']:8.2f} {r['solve_seconds']:8.2f} "
      f"{t.get('solve: setup', 0):7.3f} {t.get('solve: shots', 0):8.2f} {t.get('cells: atlases', 0):7.3f} "
      f"{solves:6d} {r['shots']:6d}")
EOF
}

echo "scene  binary     cache  seconds    solve   setup    shots atlases solves  shots(n)"
for i in $(seq "$repeats"); do
  for cache in cold warm; do
    for scene in seed1 seed3; do
      if [ "$scene" = seed1 ]; then atlas="--texels-per-quad 8 --unshot 0.01"; else atlas="--texels-per-quad 4 --unshot 0.05"; fi
      [ "$old" != - ] && row before "$old" $cache $scene "$atlas" ""
      row after "$new" $cache $scene "$atlas" ""
      row after-j2 "$new" $cache $scene "$atlas" "--jobs 2"
      cmp -s "$work/out-after-$cache-$scene/lightmap.exr" "$work/out-after-j2-$cache-$scene/lightmap.exr" ||
        echo "  !! --jobs 2 lightmap differs from --jobs 1"
      if [ "$old" != - ]; then
        cmp -s "$work/out-before-$cache-$scene/lightmap.exr" "$work/out-after-$cache-$scene/lightmap.exr" ||
          echo "  !! the lightmap differs from the old binary's"
      fi
    done
  done
done
