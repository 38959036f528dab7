#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: tools/reports.sh with the carried binary, the reports
# coming back as one reports.tar in $OUT (at most 8 files come back).
set -euo pipefail
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
out=$(mktemp -d)
bash .dev/repo/tools/reports.sh "$PWD/.dev/irradiant" "$out"
tar -C "$out" -cf "$OUT/reports.tar" .
