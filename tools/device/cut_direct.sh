#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: what a pixel with no history draws (frame.resampling's
# cut_candidates and cut_neighbours; issue 41, item 1), the binary before a change
# (.dev/before, from .dev-before/) against the current one, in one call. Direct light only
# against a direct-only reference in the first frame and after 64 still frames (320×240,
# 4096 samples), at `balanced` and with the `quality` preset's resampling table; then
# frame/direct + frame/direct_reuse at 1920×1080, camera still and swaying, and a frame cut at
# every pixel (64 candidates and 8 neighbours at every frame). `cut_direct.sh pan` instead: a
# 30° pan over 60 frames from a cut, FLIP against a direct-only reference every 6th frame.
# Expects .dev/ as tools/device/pack.sh lays it out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
if [ "${1:-}" = pan ]; then
    for scene in many-lights scenes/many-lights/four-halls.toml; do
        name=$(basename "${scene%.*}")
        for bin in before irradiant; do
            ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
                --frames 1 --reference-spp 1024 --over-time 60 --pan 30 --every 6 --sequence-spp 1024 \
                --cache "/tmp/pan-$name" --out "/tmp/pan-$bin-$name" > /dev/null 2>&1
            python3 -c "import json, sys; o = json.load(open(sys.argv[1]))['over_time'][0]; print(sys.argv[2], ' '.join('%.4f' % e for _, e in o['error']))" \
                "/tmp/pan-$bin-$name/comparison.json" "$name $bin" | tee -a "$OUT/pan.txt"
        done
    done
    exit 0
fi
settings=$(mktemp -d)
printf '' > "$settings/balanced.toml"
printf '[frame.resampling]\ncandidates = 64\nneighbours = 6\nunbiased = true\n' > "$settings/quality.toml"
printf '[frame.resampling]\ncandidates = 64\nneighbours = 8\n' > "$settings/cut-everywhere.toml"
for scene in many-lights scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml cornell; do
    name=$(basename "${scene%.*}")
    for run in before:balanced irradiant:balanced before:quality irradiant:quality; do
        bin=${run%%:*} variant=${run#*:}
        for frames in 1 64; do
            ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
                --frames $frames --reference-spp 4096 --cache "$settings/cache" \
                --settings "$settings/$variant.toml" --out "$settings/out" 2>&1 \
                | grep -E "FLIP|rror" | sed "s|^|$name $bin $variant $frames |" | tee -a "$OUT/flip.txt"
        done
    done
done
for scene in many-lights scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml cornell; do
    for run in before:balanced irradiant:balanced irradiant:cut-everywhere; do
        bin=${run%%:*} variant=${run#*:}
        for motion in still moving; do
            flag=(); [ $motion = moving ] && flag=(--moving-camera)
            ../$bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques none \
                --settings "$settings/$variant.toml" "${flag[@]}" 2>&1 \
                | grep -E "^[a-z-]+ +none " | sed "s|^|$bin $variant $motion |" | tee -a "$OUT/bench.txt"
        done
    done
done
