#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: which of DDGI's passes a change of the emitter sampling
# moves, on one scene (SCENE, default the stained-glass Sibenik): `balanced`, `quality`, and
# `quality` without its final gather, its reflections or its traced bounce, for the binary before
# the change (.dev/before) and the current one, against one shared 4096-sample reference
# (320×240, 300 frames). Writes $OUT/gi.txt.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
scene=${SCENE:-scenes/sibenik/stained-glass.toml}
q='preset = "quality"'
techniques="ddgi,ddgi{$q},ddgi{$q, gather.rays_per_pixel = 0},ddgi{$q, reflections.enabled = false}"
techniques+=",ddgi{$q, update.traced_bounce = false, update.blind_bounces = 0}"
mkdir -p /tmp/gi
for bin in before irradiant; do
    ../$bin compare --scene "$scene" --techniques "$techniques" --size 320x240 --frames 300 \
        --reference-spp 4096 --cache /tmp/gi-cache --out "/tmp/gi/$bin" 2>&1 | grep -E "FLIP|rror" | sed "s|^|$bin |" | tee -a "$OUT/gi.txt"
done
