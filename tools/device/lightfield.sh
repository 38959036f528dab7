#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: light-field probes measured (issue 11). The rows of the
# paper's Table 1 we can reproduce at 1920×1080 — the Cornell box with 2×2×2 probes at 1024²,
# Sponza with 8×2×4 probes at 512² and 1024² — each with the fast path (prefiltered
# Lambertian + a filtered glossy ray; also with a glossy ray on every specular surface), the Lambertian term alone (irradiance a 4×4 block, a 2×2 block, every pixel) and the traced algorithm; the
# glossy-floor Sponza; bake time and memory (counters bake_ms, bake_bytes); and the agreement of
# light-field rays with the BVH (`irradiant agreement`, a million rays from the surfaces seen at
# 1920×1080, each bake once through lightfield-traced: agreement.txt and agreement-*.json). Then
# docs/reports/ regenerated (tools/reports.sh) unless REPORTS=0. Writes results.tgz and
# reports.tar into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
variants() {
    local base=$1
    echo "lightfield{$base},lightfield{$base,shade.glossy_max_roughness=1.0},lightfield{$base,shade.glossy=false},lightfield{$base,shade.glossy=false,shade.irradiance_block=2},lightfield{$base,shade.glossy=false,shade.irradiance_block=1},lightfield-traced{$base}"
}
if [ "${BENCH:-1}" = 1 ]; then
    ../irradiant bench --scene cornell --size 1920x1080 --iterations 30 \
        --techniques "$(variants 'bake.probe_counts=[2,2,2],bake.resolution=1024')" \
        --json "$res/bench-cornell.json" 2>&1 | tee -a "$res/bench.txt"
    ../irradiant agreement --scene cornell --size 1920x1080 --rays 1000000 \
        --techniques 'lightfield-traced{bake.probe_counts=[2,2,2],bake.resolution=1024}' \
        --json "$res/agreement-cornell.json" 2>&1 | tee -a "$res/agreement.txt"
    for resolution in 512 1024; do
        ../irradiant bench --scene scenes/sponza/sponza.toml --size 1920x1080 --iterations 30 \
            --techniques "$(variants "bake.probe_counts=[8,2,4],bake.resolution=$resolution"),ddgi" \
            --json "$res/bench-sponza-$resolution.json" 2>&1 | tee -a "$res/bench.txt"
        ../irradiant agreement --scene scenes/sponza/sponza.toml --size 1920x1080 --rays 1000000 \
            --techniques "lightfield-traced{bake.probe_counts=[8,2,4],bake.resolution=$resolution}" \
            --json "$res/agreement-sponza-$resolution.json" 2>&1 | tee -a "$res/agreement.txt"
    done
    ../irradiant bench --scene scenes/sponza/glossy-floor.toml --size 1920x1080 --iterations 30 \
        --techniques "$(variants 'bake.probe_counts=[8,2,4],bake.resolution=1024')" \
        --json "$res/bench-sponza-glossy-floor.json" 2>&1 | tee -a "$res/bench.txt"
fi
tar -C "$res" -czf "$OUT/results.tgz" .
if [ "${REPORTS:-1}" = 1 ]; then
    out=$(mktemp -d)
    # What finished within the call comes back (each report is complete once written).
    timeout "${REPORTS_SECONDS:-420}" bash tools/reports.sh "$PWD/../irradiant" "$out" 2>&1 | tail -60 || true
    tar -C "$out" -cf "$OUT/reports.tar" .
fi
