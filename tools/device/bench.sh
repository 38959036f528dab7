#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (see BENCHMARKS.md for how): prints the adapter, times every
# pass at 1920×1080 (ray casting and the path tracer on three scenes; the DDGI frame on
# Sibenik at the paper's probe grids and ray counts, and on the other scenes' own volumes),
# and renders the pictures of the README and docs/. Expects .dev/ as tools/device/pack.sh lays
# it out; writes into $OUT two tars (at most 8 files come back): bench.tar (the figures: text
# and JSON) and images.tar (the pictures).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=../irradiant
res=$(mktemp -d)
sponza=scenes/sponza/sponza.toml
sibenik=scenes/sibenik/sibenik.toml
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
$bin info | tee "$res/info.txt"
if [ "${BENCH:-1}" = 1 ]; then
$bin bench --scene cornell,$sponza,$sibenik --size 1920x1080 --iterations 30 --json "$res/bench.json" | tee "$res/bench.txt"
$bin bench --scene $sibenik --size 1920x1080 --iterations 30 --techniques ddgi --vary 'volume.probe_counts = [[16, 8, 16], [32, 8, 32]]' --vary 'volume.rays_per_probe = [32, 64, 128, 256]' --vary 'speed.probe_states = [false, true]' --vary 'speed.probes_per_group = [1, 4]' --json "$res/ddgi-sibenik.json" | tee "$res/ddgi.txt"
$bin bench --scene cornell,two-rooms,$sponza --size 1920x1080 --iterations 30 --techniques 'ddgi{volume.rays_per_probe = 256}' --vary 'speed.probe_states = [false, true]' --json "$res/ddgi-scenes.json" | tee -a "$res/ddgi.txt"
# What the shadow queue and the BVH build effort each buy, same call.
$bin bench --scene $sibenik --size 1920x1080 --iterations 30 --techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256}' --vary 'speed.probe_states = [false, true]' --vary 'speed.probes_per_group = [1, 4]' --vary 'speed.shadow_queue = [false, true]' --json "$res/ddgi-queue.json" | tee "$res/ddgi-queue.txt"
for q in balanced quality; do
    $bin bench --scene $sibenik --size 1920x1080 --iterations 30 --bvh-quality $q --techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256, speed.probes_per_group = 4}' --vary 'speed.probe_states = [false, true]' --json "$res/bvh-$q.json" | tee "$res/bvh-$q.txt"
done
fi
if [ "${RENDER:-1}" = 1 ]; then
    img=$(mktemp -d)
    $bin render --scene cornell --technique path --spp 4096 --size 512x512 --out "$img/cornell.png"
    $bin render --scene $sponza --technique path --spp 2048 --size 640x400 --out "$img/sponza.png"
    $bin render --scene $sibenik --technique path --spp 2048 --size 640x400 --out "$img/sibenik.png"
    $bin render --scene cornell --technique ddgi --frames 200 --size 512x512 --out "$img/cornell-ddgi.png"
    $bin render --scene cornell --technique ddgi --frames 200 --size 512x512 --show-probes --out "$img/cornell-ddgi-probes.png" --dump-atlas "$img"
    $bin render --scene $sponza --technique ddgi --frames 300 --size 640x400 --out "$img/sponza-ddgi.png"
    $bin render --scene $sibenik --technique ddgi --frames 300 --size 640x400 --out "$img/sibenik-ddgi.png"
    for w in classic backface chebyshev full; do
        $bin render --scene two-rooms --technique "ddgi{update.weights = \"$w\"}" --frames 300 --size 480x360 --out "$img/two-rooms-$w.png"
    done
    $bin render --scene two-rooms --technique path --spp 4096 --size 480x360 --out "$img/two-rooms-path.png"
    $bin render --scene box-cylinders --technique 'ddgi{update.weights = "classic"}' --frames 300 --size 480x360 --out "$img/box-cylinders-classic.png"
    $bin render --scene box-cylinders --technique ddgi --frames 300 --size 480x360 --out "$img/box-cylinders-ddgi.png"
    $bin render --scene box-cylinders --technique path --spp 4096 --size 480x360 --out "$img/box-cylinders-path.png"
    $bin render --scene $sibenik --technique none --frames 2 --size 640x400 --out "$img/sibenik-direct.png"
    # An animation: the lamp walks down Sibenik's nave; 4 s at 15 frames a second.
    mkdir -p "$img/anim"
    $bin render --scene $sibenik --time 4 --fps 15 --frames 61 --size 240x150 --sequence --out "$img/anim/sibenik.png"
    tar -C "$img" -cf "$OUT/images.tar" .
fi
tar -C "$res" -cf "$OUT/bench.tar" .
