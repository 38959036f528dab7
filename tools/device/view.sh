#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (tools/device/pack.sh lays out .dev/): what the viewer's
# panel costs at 1920×1080 (issue 38). The same scripted frames of DDGI, offscreen, with and
# without the panel, in the order with / without / without / with so that a drifting clock
# shows; then bench's own frame time of the same technique for scale.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=../irradiant
frames=${FRAMES:-600}
script=$(mktemp --suffix=.toml)
printf '[[step]]\nframes = %d\n[[step]]\nquit = true\n' "$frames" > "$script"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$OUT/view.txt"
for scene in ${SCENES:-scenes/sibenik/sibenik.toml cornell}; do
    for panel in "" --no-panel --no-panel ""; do
        echo "== $scene ${panel:-with the panel}" | tee -a "$OUT/view.txt"
        $bin view --offscreen --size 1920x1080 --scene "$scene" --script "$script" $panel --out-dir /tmp 2>&1 | tee -a "$OUT/view.txt"
    done
    $bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques ddgi > "$OUT/bench-$(basename "$scene" .toml).txt" 2>&1
    grep -E 'frame ms|ddgi ' "$OUT/bench-$(basename "$scene" .toml).txt" | tee -a "$OUT/view.txt"
done
