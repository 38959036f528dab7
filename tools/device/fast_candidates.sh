#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the `fast` frame preset with its emitter candidates at 8
# against 16 (issue 41, item 1), in one call. Direct light only against a direct-only reference
# (320×240, 4096 samples) in the first frame and after 16 and 64 still frames; a 30° pan over
# 60 frames from a cut, FLIP every 6th frame (1024 samples); then `frame/direct` and
# `frame/direct_reuse` at 1920×1080, camera still and swaying, twice in reverse orders.
# Expects .dev/ as tools/device/pack.sh lays it out; appends to $OUT/fast.txt.
set -uo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
work=$(mktemp -d)
# `bench --settings` lays its [frame] table over `balanced`: the whole of `fast`'s frame.
for c in 8 16; do
    printf 'area_light_samples = 1\n[resampling]\ncandidates = %s\nneighbours = 2\ncut_candidates = 32\ncut_neighbours = 4\n[taa]\nblend = 0.2\n' $c \
        | sed 's/^\[/[frame./; 1s/^/[frame]\n/' > "$work/c$c.toml"
done
scenes=(many-lights scenes/many-lights/four-halls.toml cornell)
for scene in "${scenes[@]}"; do
    name=$(basename "${scene%.*}")
    for c in 16 8; do
        for frames in 1 16 64; do
            ../irradiant compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
                --frames $frames --reference-spp 4096 --preset fast --settings "$work/c$c.toml" \
                --cache "$work/cache" --out "$work/out" 2>&1 | grep -E "FLIP|rror" \
                | sed "s|^|$name fast c$c $frames |" >> "$OUT/fast.txt"
        done
        ../irradiant compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
            --frames 1 --reference-spp 1024 --over-time 60 --pan 30 --every 6 --sequence-spp 1024 \
            --preset fast --settings "$work/c$c.toml" --cache "$work/pan-$name" --out "$work/pan" > /dev/null 2>&1
        python3 -c "import json, sys; o = json.load(open(sys.argv[1]))['over_time'][0]; e = [x for _, x in o['error']]; print(sys.argv[2], ' '.join('%.4f' % x for x in e), 'mean %.4f' % (sum(e) / len(e)))" \
            "$work/pan/comparison.json" "$name fast c$c pan" >> "$OUT/fast.txt"
    done
done
for order in "16 8" "8 16"; do
    for c in $order; do
        for motion in still moving; do
            flag=(); [ $motion = moving ] && flag=(--moving-camera)
            ../irradiant bench --scene "$(IFS=,; echo "${scenes[*]}")" --size 1920x1080 --iterations 15 \
                --techniques none --settings "$work/c$c.toml" "${flag[@]}" 2>&1 \
                | grep -E "^(scene +technique|[a-z-]+ +none )" | cut -c1-150 | sed "s|^|c$c $motion |" >> "$OUT/fast.txt"
        done
    done
done
rm -rf "$work"
cat "$OUT/fast.txt"
