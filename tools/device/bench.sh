#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (see BENCHMARKS.md for how): prints the adapter, times every
# pass on Sponza, Sibenik and the Cornell box at 1920×1080, and renders the README's pictures.
# Expects .dev/ as tools/device/pack.sh lays it out; writes into $OUT.
set -euo pipefail
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
cd .dev/repo
bin=../irradiant
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
$bin info | tee "$OUT/info.txt"
$bin bench --scene cornell,scenes/sponza/sponza.toml,scenes/sibenik/sibenik.toml --size 1920x1080 --iterations 30 --json "$OUT/bench.json" | tee "$OUT/bench.txt"
if [ "${RENDER:-1}" = 1 ]; then
    $bin render --scene cornell --spp 4096 --size 512x512 --out "$OUT/cornell.png"
    $bin render --scene scenes/sponza/sponza.toml --spp 2048 --size 640x400 --out "$OUT/sponza.png"
    $bin render --scene scenes/sibenik/sibenik.toml --spp 2048 --size 640x400 --out "$OUT/sibenik.png"
fi
