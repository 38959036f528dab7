#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: issue 41's table for one binary (`table.sh irradiant` or
# `table.sh before`, from .dev-before/): every technique at its default against 4096-sample
# path-traced references (320×240, 300 frames) on every shipped scene, the many-emitter
# built-ins and Sibenik lit by its stained glass; then, on the scenes of many emitters, direct
# light only against a direct-only reference in the first frame and after 64 still frames, and
# frame/direct's cost at 1920×1080. References are cached in $CACHE (default /tmp/table-cache),
# so that a second call on the same machine compares the other binary against the same ones.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=${1:-irradiant}
cache=${CACHE:-/tmp/table-cache}
mkdir -p /tmp/table
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
small='none,ddgi,ddgi{preset = "quality"},ssil,ssil+ddgi,lightfield'
# The light field's default grid of these scenes needs more texture layers than the adapter has.
large='none,ddgi,ddgi{preset = "quality"},ssil,ssil+ddgi,lightfield{bake.probe_counts = [8, 4, 8]}'
many=(many-lights scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml)
for scene in cornell two-rooms scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml "${many[@]}"; do
    name=$(basename "${scene%.*}")
    techniques=$small
    case $name in sibenik | stained-glass | many-lights | four-halls) techniques=$large ;; esac
    ../$bin compare --scene "$scene" --techniques "$techniques" --size 320x240 --frames 300 \
        --reference-spp 4096 --cache "$cache" --out "/tmp/table/$bin-$name" 2>&1 | grep -E "FLIP|rror" | sed "s|^|$bin $name |" | tee -a "$OUT/table-$bin.txt"
done
for scene in "${many[@]}"; do
    name=$(basename "${scene%.*}")
    for frames in 1 64; do
        ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
            --frames $frames --reference-spp 4096 --cache "$cache" --out "/tmp/table/$bin-$name-direct" 2>&1 \
            | grep -E "FLIP|rror" | sed "s|^|$bin $name direct, $frames frames: |" | tee -a "$OUT/table-$bin.txt"
    done
    ../$bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques none 2>&1 \
        | grep -E "^([a-z-]+ +none |scene +technique)|pathtrace/trace" | sed "s|^|$bin |" | tee -a "$OUT/table-$bin.txt"
done
