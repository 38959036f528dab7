#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: direct light from many emitters (issue 41, item 1), the
# binary before a change (.dev/before, from .dev-before/) against the current one at several
# [frame.resampling] settings, in one call. `bench`: frame/direct (+ frame/direct_reuse) at
# 1920×1080, still and with the camera moving, on the many-emitter scenes and on scenes with
# one emitter or two point lights, the path tracer's sample, and DDGI's passes where its probe
# rays sample emitters.
# `quality`: direct light only against a direct-only path-traced reference, in the first frame
# and after 64 still frames, and full GI with DDGI. Expects .dev/ as tools/device/pack.sh lays
# it out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
many=(many-lights scenes/many-lights/four-halls.toml)
few=(cornell scenes/sibenik/sibenik.toml)
# Variants of the current binary: name and [frame.resampling] table.
variants=(
    "balanced|"
    "c16|candidates = 16"
    "quality|candidates = 64
neighbours = 6
unbiased = true"
)
settings_dir=$(mktemp -d)
runs=("before|")
for v in "${variants[@]}"; do
    name=${v%%|*}
    printf '[frame.resampling]\n%s\n' "${v#*|}" > "$settings_dir/$name.toml"
    runs+=("$name|$settings_dir/$name.toml")
done
for run in "${runs[@]}"; do
    which=${run%%|*}
    file=${run#*|}
    bin=../irradiant
    extra=()
    if [ "$which" = before ]; then bin=../before; else extra=(--settings "$file"); fi
    case "${1:-bench}" in
    bench)
        for scene in "${many[@]}" "${few[@]}"; do
            for motion in still moving; do
                flag=(); [ $motion = moving ] && flag=(--moving-camera)
                $bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques none \
                    "${extra[@]}" "${flag[@]}" 2>&1 | grep -E "^([a-z-]+ +none |scene +technique)|pathtrace/trace" | sed "s|^|$which $motion |" | tee -a "$OUT/bench.txt"
            done
        done
        [ "$which" = before ] || [ "$which" = balanced ] || continue
        for scene in many-lights cornell; do
            $bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques ddgi \
                "${extra[@]}" 2>&1 | grep -E "^([a-z-]+ +ddgi |scene +technique)" | sed "s|^|$which |" | tee -a "$OUT/bench.txt"
        done
        ;;
    quality)
        for scene in "${many[@]}" cornell; do
            name=$(basename "${scene%.*}")
            for frames in 1 64; do
                $bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
                    --frames $frames --reference-spp 4096 --cache "$OUT/cache-$which" "${extra[@]}" \
                    --out "$settings_dir/$which-$name-direct-$frames" 2>&1 | tail -1 | sed "s|^|$which $name direct, $frames frames: |" | tee -a "$OUT/quality.txt"
            done
            [ "$which" = before ] || [ "$which" = balanced ] || continue
            $bin compare --scene "$scene" --techniques "ddgi,ddgi{preset = \"quality\"}" --size 320x240 \
                --frames 300 --reference-spp 4096 --cache "$OUT/cache-$which" "${extra[@]}" \
                --out "$settings_dir/$which-$name-gi" 2>&1 | tail -2 | sed "s|^|$which $name GI, 300 frames: |" | tee -a "$OUT/quality.txt"
        done
        ;;
    esac
done
rm -rf "$OUT"/cache-*
