#!/usr/bin/env bash
# `cpgi cell-job PLAN --serve` (issue 16): first-shot and round jobs answered one line each by one
# long-lived process give the single-process cells bake bit for bit (lightmap.exr byte for byte) on the
# 4-room office-small; a server killed (SIGKILL) during a job of round 2 leaves the round unfinished, and a
# new server reruns it to the same state and portal-light bytes; a refused request is answered and the
# server goes on; a served status request answers what --status --json prints, at every step; a served
# gather writes the files of the one-shot gather.
#   cell_job_serve_test.sh CPGI
set -euo pipefail
cpgi=$1
work=$(mktemp -d)
server_pid=
trap '[ -n "$server_pid" ] && kill -9 "$server_pid" 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
"$cpgi" generate office-small -o office.glb >/dev/null
# Item buffers of 128²: the jobs are checked against the single process bit for bit, at any resolution.
options=(--cells office.glb --density 2 --item-buffer 128)
"$cpgi" bake office.glb -o single --method cells "${options[@]}" -q
"$cpgi" bake office.glb -o served --method cells "${options[@]}" --plan plan -q

status() { "$cpgi" cell-job plan --status --json; }
field() { python3 -c "import json, sys; s = json.load(sys.stdin); print($1)"; }
mapfile -t cells < <(python3 -c "import json; print('\n'.join(c['name'] for c in json.load(open('plan/plan.json'))['cells']))")
[ "${#cells[@]}" -eq 4 ] || fail "office-small has ${#cells[@]} cells"

start_server() {
  coproc SERVER { exec "$cpgi" cell-job plan --serve 2>>server.err; }
  server_pid=$SERVER_PID
}
request() { echo "{\"round\": $1, \"cells\": [\"$2\"]}" >&"${SERVER[1]}"; }
answer() {
  local line
  read -r line <&"${SERVER[0]}" || fail "the server ended without answering: $(tail -n 1 server.err)"
  echo "$line"
}
ok() { [ "$(echo "$1" | field 's["ok"]')" = True ] || fail "job not done: $1"; }
# A served status request answers what `cpgi cell-job --status --json` prints (cpgi-dask asks the servers
# at every round's barrier); $1 says where.
served_status_matches() {
  echo '{"status": true, "id": "barrier"}' >&"${SERVER[1]}"
  local line
  line=$(answer)
  ok "$line"
  status >status.json
  echo "$line" | python3 -c "import json, sys; a = json.load(sys.stdin); s = json.load(open('status.json'))
sys.exit(0 if a['status'] == s and a['id'] == 'barrier' else 1)" ||
    fail "$1: the served status is not --status --json's: $line against $(cat status.json)"
  served_statuses=$((served_statuses + 1))
}
served_statuses=0
# The light files of a round (every file but the summaries, which also record the job's seconds).
light_sums() { (cd "plan/round-$(printf %04d "$1")" && md5sum $(ls | grep -v '\.summary$' | grep -v '\.part-')); }

start_server
# The lamps' first shot, one emitter group a request, last group first (it needs no summed plan).
groups=$(python3 -c "import json; print(len(json.load(open('plan/plan.json'))['first_shot_groups']))")
for ((g = groups - 1; g >= 0; --g)); do echo "{\"first_shot\": [$g]}" >&"${SERVER[1]}"; ok "$(answer)"; done
[ "$(status | field 's["next_step"]')" = first-shot-sum ] || fail "served first shot left groups missing"
served_status_matches "before the first shot's sum"
"$cpgi" cell-job plan --first-shot-sum -q
served_status_matches "after the first shot's sum"
# A request for a round the plan is not at yet is refused, with its id; the server goes on.
echo "{\"round\": 3, \"cells\": [\"${cells[0]}\"], \"id\": \"early\"}" >&"${SERVER[1]}"
refused=$(answer)
[ "$(echo "$refused" | field 's["ok"], s["id"]')" = "False early" ] || fail "round 3 before round 1: $refused"
echo "refused as it should be: $refused"

round=1
while [ "$(status | field 's["next_step"]')" = round ]; do
  round=$(status | field 's["next_round"]')
  if [ "$round" -eq 2 ]; then
    # The first cell of round 2 answered, the server is killed as soon as it has the second's request:
    # during that job (the kill comes microseconds after the request; a job takes milliseconds at least).
    request 2 "${cells[0]}"
    ok "$(answer)"
    request 2 "${cells[1]}"
    kill -9 "$server_pid"
    wait "$server_pid" 2>/dev/null || true
    missing=$(status | field 'len(s["missing"])')
    [ "$(status | field 's["next_round"]')" -eq 2 ] && [ "$missing" -ge 1 ] ||
      fail "the server was killed after round 2 was complete (missing $missing): not mid-round"
    echo "killed mid-round 2: $missing of ${#cells[@]} cells missing"
    light_sums 2 | sort >before-kill.md5
    start_server
    # A new server reruns the whole round: the cells done before the kill rewrite the same bytes.
    for c in "${cells[@]}"; do request 2 "$c"; ok "$(answer)"; done
    light_sums 2 | sort >after-rerun.md5
    join before-kill.md5 after-rerun.md5 | awk '$2 != $3 { bad = 1; print "differs: " $1 } END { exit bad }' ||
      fail "a rerun of round 2 wrote other bytes than the jobs before the kill"
    echo "round 2 rerun: $(wc -l <before-kill.md5) files from before the kill rewritten byte for byte"
    continue
  fi
  for c in "${cells[@]}"; do request "$round" "$c"; done
  for c in "${cells[@]}"; do ok "$(answer)"; done
  served_status_matches "after round $round"
done
[ "$round" -ge 3 ] || fail "only $round rounds: the kill was not followed by a served round"
[ "$(status | field 's["next_step"]')" = gather ] && [ "$served_statuses" -ge 4 ] ||
  fail "the served status was not checked at the gather ($served_statuses checks)"
# The gather served too (the plan's -o folder, "served"), then again as its own process: the same files.
echo '{"gather": true, "id": "gather"}' >&"${SERVER[1]}"
ok "$(answer)"
mv served served-by-server
input=${SERVER[1]}
exec {input}>&-  # end of input: the server exits 0
wait "$server_pid" || fail "the server exited with status $? at the end of its input"
server_pid=
"$cpgi" cell-job plan --gather -q
cmp served/lightmap.exr single/lightmap.exr || fail "served lightmap.exr differs from the single process's"
for f in lightmap.exr lightmap.png baked.glb; do
  cmp served-by-server/$f served/$f || fail "the served gather's $f differs from the one-shot gather's"
done
echo "PASS: $round rounds served, lightmap.exr byte for byte the single process's; the served gather's files the one-shot gather's"
