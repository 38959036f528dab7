#!/usr/bin/env bash
# Regenerates docs/reports/: the comparison reports of the Cornell box, two-rooms, Sponza,
# two-rooms' lamp switching off, SSIL against one-bounce references and over a camera pan, the
# light field's glossy reflections on the glossy Cornell box and the glossy-floor Sponza. Usage: tools/reports.sh [IRRADIANT_BINARY] [OUTPUT_FOLDER]
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
all=(--techniques none,classic-probes,ddgi,ssil,ssil+ddgi,lightfield,lightfield-traced,lightfield-naive)
"$bin" compare --scene cornell "${common[@]}" "${all[@]}" --out "$out/cornell"
"$bin" compare --scene two-rooms "${common[@]}" "${all[@]}" --out "$out/two-rooms"
# Sponza's light field as the paper's Table 1 has it: 8×2×4 probes.
lf='bake.probe_counts=[8,2,4]'
"$bin" compare --scene scenes/sponza/sponza.toml "${common[@]}" \
    --techniques "none,classic-probes,ddgi,ssil,ssil+ddgi,lightfield{$lf},lightfield-traced{$lf},lightfield-naive{$lf}" --out "$out/sponza"
# Glossy reflection of indirect light: the glossy Cornell box and the glossy-floor Sponza, the
# light field's glossy ray against its Lambertian term alone.
"$bin" compare --scene scenes/cornell-box/glossy.toml "${common[@]}" \
    --techniques "none,ddgi,lightfield,lightfield{shade.glossy=false},lightfield-traced,lightfield-naive" --out "$out/cornell-glossy"
"$bin" compare --scene scenes/sponza/glossy-floor.toml "${common[@]}" \
    --techniques "none,ddgi,lightfield{$lf},lightfield{$lf,shade.glossy=false},lightfield-traced{$lf}" --out "$out/sponza-glossy-floor"
# Screen-space GI against the light it models (one indirect bounce), visibility off and on and
# their difference (the SSIL paper's Figure 7), and over a camera pan.
one_bounce=(--reference-bounces 1 --techniques "none,ssil{visibility=false},ssil" --difference-from "ssil{visibility=false}")
"$bin" compare --scene cornell "${common[@]}" "${one_bounce[@]}" --out "$out/cornell-one-bounce"
"$bin" compare --scene scenes/sponza/sponza.toml "${common[@]}" "${one_bounce[@]}" --out "$out/sponza-one-bounce"
"$bin" compare --scene scenes/sponza/sponza.toml --size 256x192 --reference-spp 1024 --frames 60 \
    --techniques none,ssil,ddgi,ssil+ddgi --over-time 120 --every 30 --sequence-spp 1024 --pan 20 --out "$out/sponza-pan"
"$bin" compare --scene scenes/two-rooms/switch.toml "${common[@]}" --over-time 180 --every 6 --sequence-spp 1024 --out "$out/two-rooms-switch"
# The reports inline every image; the loose PNGs beside them would only double the size.
find "$out" -name '*.png' -delete
