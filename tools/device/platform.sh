#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the platform change measured like for like (issue 10). The
# same benchmarks with the binary before the change (.dev/before, if present) and after it, in
# the order before, after, after, before, so that drift between runs shows; then TAA's FLIP
# against the path tracer, on and off, on the Cornell box, two-rooms and Sponza.
# Expects .dev/ as tools/device/pack.sh lays it out; writes results.tar into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
sibenik=scenes/sibenik/sibenik.toml
sponza=scenes/sponza/sponza.toml
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
../irradiant info > "$res/info.txt" 2>&1
bench=(bench --scene "$sibenik" --size 1920x1080 --iterations 30 --techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256}' --vary 'speed.probe_states = [false, true]')
if [ "${BENCH:-1}" = 1 ]; then
    order=(after)
    [ -x ../before ] && order=(before after after before)
    i=0
    for which in "${order[@]}"; do
        i=$((i + 1))
        bin=../irradiant
        [ "$which" = before ] && bin=../before
        echo "== run $i: $which" | tee -a "$res/bench.txt"
        $bin "${bench[@]}" --json "$res/bench-$i-$which.json" 2>&1 | tee -a "$res/bench.txt"
    done
fi
if [ "${TAA:-1}" = 1 ]; then
    cache=$(mktemp -d)
    for scene in cornell two-rooms "$sponza"; do
        name=$(basename "$scene" .toml)
        for taa in on off; do
            flag=()
            [ "$taa" = off ] && flag=(--no-taa)
            ../irradiant compare --scene "$scene" --size 320x240 --reference-spp 4096 --frames 300 \
                --techniques none,ddgi "${flag[@]}" --cache "$cache" --out "$res/taa-$name-$taa" 2>&1 | tee -a "$res/taa.txt"
            find "$res/taa-$name-$taa" -name '*.png' -delete
        done
    done
fi
tar -C "$res" -cf "$OUT/results.tar" .
