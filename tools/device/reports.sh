#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the comparison reports committed under docs/reports/
# (Cornell box, two-rooms, Sponza, and two-rooms' lamp switching off over time). Writes
# reports.tar into $OUT (at most 8 files come back).
set -euo pipefail
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .dev/repo
out=$(mktemp -d)
common=(--size 256x192 --reference-spp 4096 --frames 300 --cache /tmp/irradiant-cache)
../irradiant compare --scene cornell "${common[@]}" --out "$out/cornell"
../irradiant compare --scene two-rooms "${common[@]}" --out "$out/two-rooms"
../irradiant compare --scene scenes/sponza/sponza.toml "${common[@]}" --out "$out/sponza"
../irradiant compare --scene scenes/two-rooms/switch.toml "${common[@]}" --over-time 180 --every 6 --sequence-spp 1024 --out "$out/two-rooms-switch"
tar -C "$out" -cf "$OUT/reports.tar" .
