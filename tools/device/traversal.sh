#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: ray throughput (raycast/trace: primary, diffuse, any hit), the
# path tracer's sample and DDGI's GI at the paper's Sibenik grid, 1920×1080, for each binary in
# BINS (default "before irradiant", from .dev/), then again in the reverse order, so that a
# kernel change is measured against the code before in one call. SCALE=1 adds the 10.8M-triangle
# instanced grid; SCENES replaces the scene list; DDGI=0 leaves out DDGI. Each scene's row of the frame's passes (with
# frame/direct and frame/direct_reuse) is kept too. Expects .dev/ as tools/device/pack.sh lays
# it out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
compared_binaries
scenes=${SCENES:-cornell,scenes/sponza/sponza.toml,scenes/sibenik/sibenik.toml,many-lights}
[ -n "${SCALE:-}" ] && scenes+=,scenes/scale/sibenik-grid.toml
for round in 1 2; do
    order=("${bins[@]}"); [ $round = 2 ] && order=($reversed)
    for bin in "${order[@]}"; do
        ../$bin bench --scene "$scenes" --size 1920x1080 --iterations 30 --techniques none 2>&1 \
            | grep -E "raycast|pathtrace|^[a-z-]+ +none " | sed "s|^|$round $bin |" | tee -a "$OUT/traversal.txt"
        [ "${DDGI:-1}" = 0 ] && continue
        ../$bin bench --scene scenes/sibenik/sibenik.toml --size 1920x1080 --iterations 30 \
            --techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256}' 2>&1 \
            | grep -E "^sibenik +ddgi" | sed "s|^|$round $bin |" | tee -a "$OUT/traversal.txt"
    done
done
