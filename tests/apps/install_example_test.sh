#!/usr/bin/env bash
# The library as a user links it: `cmake --install` into a fresh prefix, examples/ configured against
# that prefix alone (find_package(cpgi) → cpgi::cpgi), built, and run on seed1; the installed cpgi
# writes the scene. Fails unless the example's result set is complete and its lightmap holds light.
#   install_example_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A step's output is kept out of the test's log unless the step fails: then its last lines say why.
quietly() {
  "$@" >"$work/step.log" 2>&1 || { echo "install: '$*' failed:" >&2; tail -25 "$work/step.log" >&2; exit 1; }
}

quietly cmake --install "$build" --prefix "$work/prefix"
for f in bin/cpgi include/cpgi/radiosity/bake/bake.h include/cpgi/radiosity/bake/bake_settings.h \
         lib/cmake/cpgi/cpgiConfig.cmake lib/cmake/cpgi/cpgiTargets.cmake; do
  [ -e "$work/prefix/$f" ] || { echo "install: $f missing from the prefix" >&2; exit 1; }
done

# Only the prefix: the build tree and the sources are not on the package's or the example's paths.
if grep -l -- "$source\|$build" "$work/prefix/lib/cmake/cpgi/"*.cmake; then
  echo "install: the package above names the source or build tree" >&2
  exit 1
fi
quietly cmake -S "$source/examples" -B "$work/example" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix"
quietly cmake --build "$work/example"
if grep -q -- "-I$source\b\|-I$build\b" "$work/example/build.ninja"; then
  echo "example: compiled against the source or build tree, not the installed headers" >&2
  exit 1
fi

quietly "$work/prefix/bin/cpgi" generate seed1 -o "$work/seed1.glb"
"$work/example/bake_scene" "$work/seed1.glb" "$work/out" 4
for f in lightmap.exr lightmap.png baked.glb report.json report.html; do
  [ -s "$work/out/$f" ] || { echo "example: $f not written" >&2; exit 1; }
done
ls "$work/out"/view-*.png >/dev/null
# The same bake as the command line's at that density: the books balance and light landed.
python3 - "$work/out/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
e = r["energy"]
assert e["emitted_w"] > 0 and e["absorbed_w"] > 0.5 * e["emitted_w"], e
print("example: emitted %.1f W, absorbed %.1f W, %d shots" % (e["emitted_w"], e["absorbed_w"], r.get("shots", -1)))
PY
