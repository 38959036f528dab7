#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: `irradiant soak` for every registered technique — FRAMES
# (10 000) frames over two-rooms' lamp switching off, looped, checked every 500 — and the same
# held still for the drift check. Writes soak.tgz (logs and JSON) into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
frames=${FRAMES:-10000}
lf='bake.probe_counts=[4,4,4]'
techniques="none,classic-probes,ddgi,ssil,ssil+ddgi,lightfield{$lf},lightfield-traced{$lf},lightfield-naive{$lf}"
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
status=0
../irradiant soak --frames "$frames" --every 500 --techniques "$techniques" \
    --json "$res/soak-animated.json" > "$res/soak-animated.txt" 2>&1 || status=1
../irradiant soak --still --frames "$frames" --every 500 --techniques "$techniques" \
    --json "$res/soak-still.json" > "$res/soak-still.txt" 2>&1 || status=1
tail -n 30 "$res"/soak-*.txt
tar -C "$res" -czf "$OUT/soak.tgz" .
exit $status
