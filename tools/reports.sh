#!/usr/bin/env bash
# Regenerates docs/reports/: the comparison reports of the Cornell box, two-rooms, Sponza and
# two-rooms' lamp switching off. Usage: tools/reports.sh [IRRADIANT_BINARY] [OUTPUT_FOLDER]
# (defaults: a release build of this checkout, docs/reports). The committed reports were made
# on an NVIDIA H200 through tools/device/reports.sh, which calls this script.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-}
if [ -z "$bin" ]; then
    cargo build --release --locked -p irradiant-cli
    bin=target/release/irradiant
fi
out=${2:-docs/reports}
mkdir -p "$out"
common=(--size 256x192 --reference-spp 4096 --frames 300)
"$bin" compare --scene cornell "${common[@]}" --out "$out/cornell"
"$bin" compare --scene two-rooms "${common[@]}" --out "$out/two-rooms"
"$bin" compare --scene scenes/sponza/sponza.toml "${common[@]}" --out "$out/sponza"
"$bin" compare --scene scenes/two-rooms/switch.toml "${common[@]}" --over-time 180 --every 6 --sequence-spp 1024 --out "$out/two-rooms-switch"
# The reports inline every image; the loose PNGs beside them would only double the size.
find "$out" -name '*.png' -delete
