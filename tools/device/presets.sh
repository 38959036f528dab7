#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: which of DDGI's `quality` pieces helps or hurts under many
# emitters (issue 41, item 3): `balanced`, `quality`, `quality` less each piece, and `balanced`
# plus each piece, on the many-emitter scenes and the Cornell box, one compare a scene
# (320×240, 300 frames, 4096-sample references); BINS="before irradiant" compares two binaries,
# BENCH=1 also times `quality` at 1920×1080 (BENCH_TECHNIQUES: others instead; BENCH_SCENES:
# only those scenes), TECHNIQUES
# replaces the list. The binaries share the references (CACHE: a folder that outlives the
# call, so that a second call with other techniques renders none again). Expects .dev/ as tools/device/pack.sh lays it
# out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
q='preset = "quality"'
techniques="ddgi,ddgi{$q}"
techniques+=",ddgi{$q, gather.rays_per_pixel = 0}"
techniques+=",ddgi{$q, update.traced_bounce = false, update.blind_bounces = 0}"
techniques+=",ddgi{$q, update.hysteresis = 0.97, update.distance_hysteresis = 0.97}"
techniques+=",ddgi{gather.rays_per_pixel = 1, gather.pixel_interval = 2, gather.history_frames = 64}"
techniques+=",ddgi{update.traced_bounce = true}"
bins=${BINS:-irradiant}
bench_techniques="ddgi{$q}"
bench_techniques=${BENCH_TECHNIQUES:-$bench_techniques}
techniques=${TECHNIQUES:-$techniques}
for bin in $bins; do
for scene in ${SCENES:-many-lights scenes/many-lights/four-halls.toml cornell}; do
    # scenes/sponza/glossy-floor.toml → sponza-glossy-floor: two manifests share a file name.
    name=$(echo "${scene%.*}" | sed 's|^scenes/||; s|/|-|g')
    ../$bin compare --scene "$scene" --techniques "$techniques" --size 320x240 --frames 300 \
        --reference-spp 4096 --cache "${CACHE:-$OUT/cache}" --out "$OUT/$bin-$name" 2>&1 | grep -E "FLIP" | sed "s|^|$bin $name |" | tee -a "$OUT/presets.txt"
    if [ -n "${BENCH:-}" ] && { [ -z "${BENCH_SCENES:-}" ] || [[ " $BENCH_SCENES " == *" $scene "* ]]; }; then
        ../$bin bench --scene "$scene" --size 1920x1080 --iterations 30 --warmup-ms 500 \
            --techniques "$bench_techniques" --json "$OUT/bench-$bin-$name.json" \
            > "$OUT/bench-$bin-$name.txt" 2>&1
    fi
done
done
rm -rf "$OUT"/cache
find "$OUT" -name "*.png" -delete
