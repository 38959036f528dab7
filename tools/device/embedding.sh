#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (tools/device/pack.sh lays out .dev/, with the raster host
# example as .dev/raster_host): the embedding API's overhead at 1920×1080 (issue 40). The raster
# host's frames (its G-buffer rasterized, HostGi recording into its encoder) and Irradiant's own
# frames of the same scene on the same device, every pass timed, in one call; the host's
# G-buffer handed over (host/import) and drawn into Irradiant's own (--native).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$OUT/embedding.txt"
for scene in ${SCENES:-scenes/sibenik/sibenik.toml cornell}; do
    for mode in imported native; do
        echo "== $scene, $mode" | tee -a "$OUT/embedding.txt"
        flag=$([ "$mode" = native ] && echo --native || true)
        ../raster_host --scene "$scene" --size 1920x1080 --frames ${FRAMES:-120} --timings $flag \
            --out "$OUT/raster-$(basename "$scene" .toml)-$mode.png" 2>&1 | tee -a "$OUT/embedding.txt"
    done
done
