#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: tools/reports.sh with the carried binary, the reports
# coming back as one reports.tar in $OUT (at most 8 files come back).
set -euo pipefail
source "$(dirname "$0")/setup.sh"
out=$(mktemp -d)
bash .dev/repo/tools/reports.sh "$PWD/.dev/irradiant" "$out"
tar -C "$out" -cf "$OUT/reports.tar" .
