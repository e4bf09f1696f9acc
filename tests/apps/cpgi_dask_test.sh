#!/usr/bin/env bash
# Cell jobs on a local Dask cluster of 2 workers give the single-process cells bake (issue 16): the
# 4-room office-small building (2 storeys, a hatch between them; its 2 lamps shot as 2 first-shot jobs),
# compared texel by texel, the first shot, the rounds, their barriers' status and the gather on one
# `cpgi cell-job --serve` process per worker, with one worker killed during round 2 (its jobs rerun on the
# other); and a damaged job file is one line naming it, exit 1.
#   cpgi_dask_test.sh CPGI CPGI_DASK
set -euo pipefail
cpgi=$1 dask=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
"$cpgi" generate office-small -o office.glb >/dev/null
# Item buffers of 128²: the jobs are checked against the single process bit for bit, at any resolution.
options=(--cells office.glb --density 2 --item-buffer 128)
"$cpgi" bake office.glb -o single --method cells "${options[@]}" -q
"$dask" office.glb -o distributed --workers 2 --lose-worker 2 "${options[@]}" | tee dask.log
grep -q "^cpgi-dask: killed worker" dask.log || { echo "FAIL: no worker was lost"; exit 1; }
grep -q "first shot, rounds, status and gather on a cell-job server per worker" dask.log || { echo "FAIL: jobs not served"; exit 1; }
grep -q "^cpgi-dask: first shot: 2 emitter groups in 2 jobs" dask.log || { echo "FAIL: no first-shot line"; exit 1; }
grep -q "^cpgi-dask: round 1: " dask.log || { echo "FAIL: no progress line for round 1"; exit 1; }
# The barriers' status and the gather on the servers too: their seconds in the progress lines.
grep -q "^cpgi-dask: round 3: .*idle before it [0-9.]* s), status [0-9.]* s$" dask.log ||
  { echo "FAIL: no status time in round 3's line"; exit 1; }
grep -q "^cpgi-dask: distributed: [0-9]* rounds, gather [0-9.]* s" dask.log || { echo "FAIL: no gather line"; exit 1; }
rel=$("$cpgi" compare-light distributed single --json | python3 -c "import json, sys; print(json.load(sys.stdin)['rel_rmse'])")
echo "relative RMSE against the single-process bake: $rel"
python3 -c "import sys; sys.exit(0 if float('$rel') <= 1e-4 else 1)" || { echo "FAIL: rel RMSE $rel > 1e-4"; exit 1; }

# A truncated portal-light file: the job that reads it fails with one line naming it.
light=$(ls distributed.plan/round-0001/portal-*.light | head -n 1)
head -c 30 "$light" >cut && mv cut "$light"
set +e
"$cpgi" cell-job distributed.plan --round 2 -q 2>err.txt
status=$?
set -e
[ "$status" -eq 1 ] || { echo "FAIL: exit $status on a truncated job file"; exit 1; }
[ "$(wc -l <err.txt)" -eq 1 ] && grep -q "$(basename "$light")" err.txt || { echo "FAIL: message"; cat err.txt; exit 1; }
echo "PASS"
