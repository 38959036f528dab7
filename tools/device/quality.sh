#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (issue 15): `compare` at 256×192 against 4096-sample
# references after 300 frames, with the binary before a change (.dev/before) and after it, on
# the scenes of $SCENES; writes quality.tgz (comparison.json and the text of each) into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
for b in ../before ../irradiant; do
    tag=$(basename $b)
    for scene in ${SCENES:-cornell two-rooms box-cylinders scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml}; do
        name=$(basename $scene .toml)
        $b compare --scene $scene --size 256x192 --reference-spp 4096 --frames 300 \
            --cache "$res/cache" --techniques "${TECHNIQUES:-classic-probes,ddgi}" \
            --out "$res/compare-$tag-$name" > "$res/compare-$tag-$name.txt" 2>&1 || true
        echo "== $tag $name"; grep -v "^wrote" "$res/compare-$tag-$name.txt" | tail -n 8
    done
done
rm -rf "$res/cache"
find "$res" -name '*.png' -delete
tar -C "$res" -czf "$OUT/quality.tgz" .
