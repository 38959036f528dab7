#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the energy DDGI's gather firefly clamp takes away (issue
# 41, item 3: "the bias this adds stated and measured"). On each scene, `render` at 320×240
# after 300 frames prints the image's mean radiance: `none` (direct light alone), `quality`
# with its clamp (64 times the probes' light at the pixel) and without (0). The clamp's bias is
# the difference of the two over the indirect light, `quality` without the clamp less `none`.
# SCENES replaces the list. Expects .dev/ as tools/device/pack.sh lays it out; writes
# clamp_bias.txt into $OUT. Not yet run on the lent GPU (2026-12-07); the same renders on
# lavapipe at 96×72 are in docs/notes/light-quality.md.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > "$OUT/gpu.txt" 2>&1 || true
scenes=${SCENES:-cornell many-lights scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml scenes/cornell-box/glossy-floor.toml scenes/sponza/glossy-floor.toml}
# The mean radiance's luminance (Rec. 709) from render's last line: "… mean radiance (r, g, b)".
mean_luminance() {
    sed -n 's/.*mean radiance (\([^,]*\), \([^,]*\), \([^)]*\)).*/\1 \2 \3/p' |
        awk '{ printf "%.6f", 0.2126 * $1 + 0.7152 * $2 + 0.0722 * $3 }'
}
render() {
    ../irradiant render --scene "$1" --technique "$2" --size 320x240 --frames 300 \
        --out "$OUT/image.png" 2>&1 | tail -1 | mean_luminance
}
printf '%-44s %10s %10s %10s %9s\n' scene none clamp_64 clamp_0 bias >> "$OUT/clamp_bias.txt"
for scene in $scenes; do
    direct=$(render "$scene" none)
    clamped=$(render "$scene" 'ddgi{preset = "quality"}')
    unclamped=$(render "$scene" 'ddgi{preset = "quality", gather.firefly_clamp = 0.0}')
    awk -v s="$scene" -v d="$direct" -v c="$clamped" -v u="$unclamped" 'BEGIN {
        printf "%-44s %10.6f %10.6f %10.6f %8.2f%%\n", s, d, c, u, 100 * (c - u) / (u - d) }' \
        >> "$OUT/clamp_bias.txt"
done
rm -f "$OUT/image.png"
cat "$OUT/clamp_bias.txt"
