#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: ssil+ddgi against its parents in the first 30 frames after a
# cut (issue 41, item 2) and converged: every shipped scene, `compare --over-time 30 --every 3`
# (512-sample references a compared frame) and after 300 frames (4096 samples), 320×240,
# `balanced`, the hybrid with and without `far_field_while_young` (TECHNIQUES replaces the
# list, SCENES the scenes, BIN the binary in .dev/). Expects .dev/ as tools/device/pack.sh lays
# it out; keeps each comparison.json (the FLIP of every compared frame) in $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
techniques=${TECHNIQUES:-'ddgi,ssil,ssil+ddgi,ssil+ddgi{far_field_while_young = false}'}
scenes=${SCENES:-cornell two-rooms scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml many-lights \
    scenes/many-lights/four-halls.toml}
for scene in $scenes; do
    name=$(basename "${scene%.*}")
    ../${BIN:-irradiant} compare --scene "$scene" --techniques "$techniques" --size 320x240 --frames 300 \
        --over-time 30 --every 3 --sequence-spp 512 --reference-spp 4096 --cache /tmp/cut-cache \
        --out "/tmp/cut-$name" 2>&1 | grep -E "FLIP" | sed "s|^|$name |" | tee -a "$OUT/cut.txt"
    cp "/tmp/cut-$name/comparison.json" "$OUT/$name.json"
done
