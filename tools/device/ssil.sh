#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: screen-space indirect illumination measured (issue 12).
# The paper's Figure 9 grid on Sponza at 1280×720 and 1920×1080 (start, levels, samples,
# visibility) beside the other techniques' frames; comparisons against one-bounce and full
# path-traced references on the Cornell box and Sponza, with visibility off and on and their
# difference (the paper's Figure 7); error and flicker over a camera pan.
# With .dev/before (the binary before a change), also the rays and DDGI benchmark with it and
# without, in the order before, after, after, before (the BVH traversal is shared).
# Expects .dev/ as tools/device/pack.sh lays it out; writes results.tgz (reports' HTML left
# out: they inline the PNGs beside them) into $OUT. BENCH=0, COMPARE=0, PAN=0 or BEFORE=0 skip
# a part.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
sponza=scenes/sponza/sponza.toml
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
if [ "${BENCH:-1}" = 1 ]; then
    for size in 1280x720 1920x1080; do
        ../irradiant bench --scene "$sponza" --size "$size" --iterations 30 \
            --techniques none,ssil,ddgi,ssil+ddgi --vary 'start = ["quarter", "half"]' --vary 'levels = [4, 5]' \
            --vary 'samples = [64, 256]' --vary 'visibility = [false, true]' --json "$res/bench-$size.json" 2>&1 | tee -a "$res/bench.txt"
    done
fi
if [ "${BEFORE:-1}" = 1 ] && [ -x ../before ]; then
    i=0
    for which in before after after before; do
        i=$((i + 1))
        bin=../irradiant
        [ "$which" = before ] && bin=../before
        echo "== run $i: $which" | tee -a "$res/before-after.txt"
        $bin bench --scene "$sponza" --size 1920x1080 --iterations 30 --techniques ddgi \
            --json "$res/rays-$i-$which.json" 2>&1 | tee -a "$res/before-after.txt"
    done
fi
techniques="none,ssil{visibility=false},ssil,ddgi,ssil+ddgi"
cache=$(mktemp -d)
if [ "${COMPARE:-1}" = 1 ]; then
    for scene in cornell "$sponza"; do
        name=$(basename "$scene" .toml)
        size=640x360
        [ "$name" = cornell ] && size=480x360
        for bounces in 1 all; do
            flag=()
            [ "$bounces" = 1 ] && flag=(--reference-bounces 1)
            ../irradiant compare --scene "$scene" --size "$size" --reference-spp 4096 --frames 240 \
                --techniques "$techniques" --difference-from "ssil{visibility=false}" "${flag[@]}" \
                --cache "$cache" --out "$res/compare-$name-$bounces" 2>&1 | tee -a "$res/compare.txt"
        done
    done
fi
if [ "${PAN:-1}" = 1 ]; then
    for scene in cornell "$sponza"; do
        name=$(basename "$scene" .toml)
        ../irradiant compare --scene "$scene" --size 640x360 --reference-spp 1024 --frames 60 \
            --techniques none,ssil,ddgi,ssil+ddgi --over-time 120 --fps 60 --every 30 --sequence-spp 1024 \
            --pan 20 --cache "$cache" --out "$res/pan-$name" 2>&1 | tee -a "$res/pan.txt"
        find "$res/pan-$name" -name '*.png' -delete
    done
fi
tar -C "$res" --exclude=report.html -czf "$OUT/results.tgz" .
