#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: issue 39's large world (scenes/world/world.toml) along its
# camera path, in one call. `bench`: GI at 1920×1080 along the path for three cascades (the
# scene's default), one dense and one sparse volume over the world, the convergence rounds and
# the probe states on and off, and Sibenik's sleeping savings; `quality`: FLIP along the path
# against path-traced frames, cascades against the dense volume; `between`: the light between
# volumes on and off, its cost along the path and its FLIP along the path and on Sibenik's
# cascades; `steps`: at 1920×1080 along the path, the flicker by frames since a probe window
# stepped (seams and pops). Expects .dev/ as
# tools/device/pack.sh lays it out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=../irradiant
world=scenes/world/world.toml
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
dense='ddgi{volume.cascades = 0, volume.probe_counts = [120, 8, 120]}'
sparse='ddgi{volume.cascades = 0, volume.probe_counts = [60, 4, 60]}'
case "${1:-bench}" in
bench)
    $bin bench --scene "$world" --size 1920x1080 --iterations "${FRAMES:-1620}" --camera-path \
        --techniques ddgi --techniques "$dense" --techniques "$sparse" \
        --json "$OUT/world-path.json" 2>&1 | grep -v "^ *$" | tee "$OUT/world-path.txt"
    $bin bench --scene "$world" --size 1920x1080 --iterations "${FRAMES:-1620}" --camera-path \
        --techniques ddgi --vary 'update.convergence_rounds = [0, 3]' --vary 'speed.probe_states = [false, true]' \
        --json "$OUT/world-vary.json" 2>&1 | grep -v "^ *$" | tee "$OUT/world-vary.txt"
    $bin bench --scene "$world" --size 1920x1080 --iterations "${FRAMES:-1620}" --camera-path \
        --techniques ddgi --vary 'volume.cascades = [1, 2, 3, 4]' \
        --json "$OUT/world-cascades.json" 2>&1 | grep -v "^ *$" | tee "$OUT/world-cascades.txt"
    $bin bench --scene scenes/sibenik/sibenik.toml --size 1920x1080 --iterations 30 \
        --techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256}' \
        --vary 'speed.probe_states = [false, true]' \
        --json "$OUT/sibenik-states.json" 2>&1 | grep -v "^ *$" | tee "$OUT/sibenik-states.txt"
    ;;
quality)
    $bin compare --scene "$world" --techniques "none,ddgi,$dense" --size 320x240 \
        --over-time "${FRAMES:-1620}" --every "${EVERY:-135}" --sequence-spp "${SPP:-1024}" \
        --cache "$OUT/cache" --out "$OUT/world-path" 2>&1 | tail -40 | tee "$OUT/world-quality.txt"
    rm -rf "$OUT/cache"
    ;;
steps)
    $bin compare --scene "$world" --techniques ddgi --size 1920x1080 --over-time "${FRAMES:-1620}" \
        --every "${EVERY:-810}" --sequence-spp "${SPP:-64}" --reference-spp "${SPP:-64}" \
        --cache "$OUT/cache" --out "$OUT/steps" 2>&1 | tail -5 | tee "$OUT/steps.txt"
    cp "$OUT/steps/comparison.json" "$OUT/steps.json"
    rm -rf "$OUT/cache" "$OUT/steps"
    ;;
between)
    off='ddgi{update.light_between_volumes = false}'
    $bin bench --scene "$world" --size 1920x1080 --iterations "${FRAMES:-1620}" --camera-path \
        --techniques ddgi --vary 'update.light_between_volumes = [false, true]' \
        --json "$OUT/between-path.json" 2>&1 | grep -v "^ *$" | tee "$OUT/between-path.txt"
    $bin bench --scene scenes/sibenik/sibenik.toml --size 1920x1080 --iterations 30 \
        --techniques 'ddgi{volume.cascades = 3}' --vary 'update.light_between_volumes = [false, true]' \
        --json "$OUT/between-sibenik.json" 2>&1 | grep -v "^ *$" | tee "$OUT/between-sibenik.txt"
    $bin compare --scene "$world" --techniques "none,$off,ddgi" --size 320x240 \
        --over-time "${FRAMES:-1620}" --every "${EVERY:-135}" --sequence-spp "${SPP:-1024}" \
        --cache "$OUT/cache" --out "$OUT/between-world" 2>&1 | tail -40 | tee "$OUT/between-world.txt"
    $bin compare --scene scenes/sibenik/sibenik.toml --size 320x240 --reference-spp 4096 --frames 300 \
        --techniques "ddgi{volume.cascades = 3, update.light_between_volumes = false},ddgi{volume.cascades = 3}" \
        --cache "$OUT/cache" --out "$OUT/between-sibenik" 2>&1 | tail -30 | tee "$OUT/between-sibenik-flip.txt"
    rm -rf "$OUT/cache"
    tar czf "$OUT/between.tgz" -C "$OUT" --exclude between.tgz . 2>/dev/null || true
    ;;
esac
