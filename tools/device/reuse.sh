#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: frame/direct and frame/direct_reuse before a change
# (.dev/before) and after (.dev/irradiant) in one call: the passes' cost at 1920×1080, still
# and with the camera moving, on the two many-emitter built-ins; then direct light only in the
# first frame (where the neighbours' reuse matters most) against a direct-only reference.
# Expects .dev/ as tools/device/pack.sh lays it out; writes into $OUT. BEFORE=name takes another
# binary in .dev/ as the one before.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
scenes=(many-lights scenes/many-lights/four-halls.toml)
for bin in ${BEFORE:-before} irradiant; do
    for scene in "${scenes[@]}"; do
        for motion in still moving; do
            flag=(); [ $motion = moving ] && flag=(--moving-camera)
            ../$bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques none "${flag[@]}" 2>&1 \
                | grep -E "^([a-z-]+ +none |scene +technique)" | sed "s|^|$bin $motion |" | tee -a "$OUT/reuse.txt"
        done
    done
done
for bin in ${BEFORE:-before} irradiant; do
    for scene in "${scenes[@]}"; do
        name=$(basename "${scene%.*}")
        ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
            --frames 1 --reference-spp 4096 --cache /tmp/reuse-cache --out "/tmp/reuse-$bin-$name" 2>&1 \
            | grep -E "FLIP|rror" | sed "s|^|$bin $name direct, first frame: |" | tee -a "$OUT/reuse.txt"
    done
done
