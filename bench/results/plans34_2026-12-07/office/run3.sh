#!/bin/bash
# Office bakes; each job taken once (mkdir lock) so two runners share the list. CPU s from /usr/bin/time -v.
cd /tmp/plans34/office
C=/tmp/plans34/cpgi-bin
run() { name=$1; shift; mkdir $name.lock 2>/dev/null || return; /usr/bin/time -v -o $name.time "$@" > $name.log 2>&1; echo $? > $name.done; }
run cells-auto $C bake office.glb -o cells-auto --method cells --cells auto --view-size 160x120 -q
run cells-rays $C bake office.glb -o cells-rays --method cells --backend rays --view-size 160x120 -q
run global-rays $C bake office.glb -o global-rays --backend rays --view-size 160x120 -q
run cells-glall $C bake office.glb -o cells-glall --method cells --backend gl --indirect-solver gpu --view-size 160x120 -q
