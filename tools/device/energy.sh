#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (issue 15): DDGI's energy on a still scene and against the
# path tracer, for the binary before a change (.dev/before, when BEFORE=1) and after it.
# `irradiant soak --still` over two-rooms (10 000 frames, image mean every 1000) for DDGI's
# variants, then `compare` (256×192, 4096-sample references, 300 frames) on the Cornell box,
# two-rooms, box-cylinders and Sponza. Writes energy.tgz into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
nvidia-smi --query-gpu=name,driver_version --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
variants='ddgi,ddgi{volume.irradiance_gamma=1},ddgi{update.hysteresis=0.9},ddgi{update.hysteresis=0.99},classic-probes'
bins=(../irradiant)
[ -n "${BEFORE:-}" ] && bins+=(../before)
for b in "${bins[@]}"; do
    tag=$(basename $b)
    $b soak --still --frames 10000 --every 1000 --techniques "$variants" \
        --json "$res/soak-$tag.json" > "$res/soak-$tag.txt" 2>&1 || true
    for scene in cornell two-rooms box-cylinders scenes/sponza/sponza.toml; do
        name=$(basename $scene .toml)
        $b compare --scene $scene --size 256x192 --reference-spp 4096 --frames 300 \
            --cache "$res/cache" --techniques "none,classic-probes,ddgi,ddgi{volume.irradiance_gamma=1}" \
            --out "$res/compare-$tag-$name" > "$res/compare-$tag-$name.txt" 2>&1 || true
    done
done
rm -rf "$res/cache"
find "$res" -name '*.png' -delete
grep -h "frame  10000\|frame   2000" "$res"/soak-*.txt || true
tail -n 12 "$res"/compare-*.txt || true
tar -C "$res" -czf "$OUT/energy.tgz" .
