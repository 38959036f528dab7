#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the DDGI frame, pass by pass, with the binary before a change
# (.dev/before) and after it, in the order before, after, after, before (so that clock drift
# over the call shows), on Sibenik at 32×8×32 probes × 256 rays and on Sponza's own volume, at
# 1920×1080. Writes speed.txt and the JSON into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
n=0
for b in ../before ../irradiant ../irradiant ../before; do
    n=$((n + 1))
    tag="$n-$(basename $b)"
    echo "== $tag" | tee -a "$OUT/speed.txt"
    $b bench --scene scenes/sibenik/sibenik.toml --size 1920x1080 --iterations 30 --warmup-ms 500 \
        --techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256, speed.probe_states = true}' \
        --json "$OUT/sibenik-$tag.json" 2>&1 | grep -v "^ *$" | tee -a "$OUT/speed.txt"
    $b bench --scene scenes/sponza/sponza.toml --size 1920x1080 --iterations 30 --warmup-ms 500 \
        --techniques 'ddgi{volume.rays_per_probe = 256, speed.probe_states = true}' \
        --json "$OUT/sponza-$tag.json" 2>&1 | grep -v "^ *$" | tee -a "$OUT/speed.txt"
done
