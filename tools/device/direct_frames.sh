#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: direct light only against a direct-only path-traced
# reference (320×240, 4096 samples) after each count of still frames in FRAMES (default
# "1 16 64"), for each binary in BINS (default "before irradiant", from .dev/) on each scene in
# SCENES (default the many-emitter scenes, the stained-glass Sibenik and the Cornell box), in
# one call (issue 41, item 1). Expects .dev/ as tools/device/pack.sh lays it out; appends
# "scene binary frames FLIP…" lines to $OUT/flip.txt.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
compared_binaries
scenes=(${SCENES:-many-lights scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml cornell})
work=$(mktemp -d)
for scene in "${scenes[@]}"; do
    name=$(basename "${scene%.*}")
    for frames in ${FRAMES:-1 16 64}; do
        for bin in "${bins[@]}"; do
            ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
                --frames "$frames" --reference-spp 4096 --cache "$work/cache" --out "$work/out" 2>&1 \
                | grep -E "FLIP|rror" | sed "s|^|$name $bin $frames |" | tee -a "$OUT/flip.txt"
        done
    done
done
rm -rf "$work"
