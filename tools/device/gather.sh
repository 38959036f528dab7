#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (issue 15): DDGI's final gather (`gather.rays_per_pixel`).
# Its cost: `bench` of the frame with the query and with the gather ($GATHER, the variants
# beside plain ddgi) on Sibenik and Sponza at 1920×1080, the camera still and swaying; its
# quality: `compare` at 256×192 against 4096-sample references after 300 frames on $SCENES,
# every variant at the preset $PRESET (default: balanced; `bench` takes the variants' keys
# alone). BENCH=0 leaves out the bench.
# Writes gather.txt and gather.tgz (the JSON and comparison.json files) into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
nvidia-smi --query-gpu=name,driver_version --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
variants="ddgi,${GATHER:-ddgi{gather.rays_per_pixel = 1\}}"
for scene in scenes/sibenik/sibenik.toml scenes/sponza/sponza.toml; do
    [ "${BENCH:-1}" = 0 ] && break
    name=$(basename $scene .toml)
    for motion in still moving; do
        flag=""; [ $motion = moving ] && flag="--moving-camera"
        echo "== bench $name, camera $motion" | tee -a "$OUT/gather.txt"
        ../irradiant bench --scene $scene --size 1920x1080 --iterations 30 --warmup-ms 500 \
            --techniques "$variants" $flag --json "$res/bench-$name-$motion.json" 2>&1 \
            | grep -v "^ *$" | tee -a "$OUT/gather.txt"
    done
done
for scene in ${SCENES:-cornell two-rooms box-cylinders empty-box thin-frames table scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml}; do
    name=$(basename $scene .toml)
    ../irradiant compare --scene $scene --size 256x192 --reference-spp 4096 --frames 300 \
        --cache "$res/cache" --preset ${PRESET:-balanced} --techniques "$variants${EXTRA:+,$EXTRA}" \
        --out "$res/compare-$name" > "$res/compare-$name.txt" 2>&1 || true
    echo "== compare $name" | tee -a "$OUT/gather.txt"
    grep -v "^wrote" "$res/compare-$name.txt" | tail -n 6 | tee -a "$OUT/gather.txt"
done
rm -rf "$res/cache"
find "$res" -name '*.png' -delete
tar -C "$res" -czf "$OUT/gather.tgz" .
