#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: GI in glossy reflections (issue 39, 003 §4.4) in one call.
# Their cost at 1920×1080 with `reflections.enabled` off and on (balanced and quality) on
# Sibenik, Sponza and the glossy manifests; their FLIP against the path tracer at 320×240 on
# the glossy manifests, for ddgi and ssil+ddgi. `reflections.sh shipped`: their FLIP on the
# shipped scenes (not glossy by name) at `balanced`, off and on. Expects .dev/ as tools/device/pack.sh lays it
# out; writes into $OUT (reflections.tgz holds everything).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=../irradiant
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
if [ "${1:-}" = shipped ]; then
    for scene in cornell two-rooms scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml; do
        name=$(basename "$scene" .toml)
        $bin compare --scene "$scene" --size 320x240 --reference-spp "${SPP:-4096}" --frames 300 \
            --techniques 'ddgi{reflections.enabled = false},ddgi' \
            --cache "$OUT/cache" --out "$OUT/$name" 2>&1 | tail -3 | tee "$OUT/$name.txt"
        rm -rf "$OUT/$name"
    done
    rm -rf "$OUT/cache"
    exit 0
fi
glossy="scenes/cornell-box/glossy-floor.toml,scenes/cornell-box/glossy.toml,scenes/cornell-box/mirror.toml,scenes/sponza/glossy-floor.toml"
for preset in balanced quality; do
    $bin bench --scene "scenes/sibenik/sibenik.toml,scenes/sponza/sponza.toml,$glossy" \
        --size 1920x1080 --iterations 30 --techniques "ddgi{preset = \"$preset\"}" \
        --vary 'reflections.enabled = [false, true]' \
        --json "$OUT/bench-$preset.json" 2>&1 | grep -v "^ *$" | tee "$OUT/bench-$preset.txt"
done
IFS=, read -ra scenes <<< "$glossy"
for scene in "${scenes[@]}"; do
    name=$(basename "$(dirname "$scene")")-$(basename "$scene" .toml)
    $bin compare --scene "$scene" --size 320x240 --reference-spp "${SPP:-4096}" --frames 300 \
        --techniques 'ddgi{reflections.enabled = false},ddgi,ssil+ddgi{ddgi.reflections.enabled = false},ssil+ddgi,ddgi{preset = "quality", reflections.enabled = false},ddgi{preset = "quality"}' \
        --cache "$OUT/cache" --out "$OUT/$name" 2>&1 | tail -8 | tee "$OUT/$name.txt"
done
rm -rf "$OUT/cache"
tar czf "$OUT/reflections.tgz" -C "$OUT" --exclude reflections.tgz . 2>/dev/null || true
