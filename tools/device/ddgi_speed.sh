#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the DDGI update on Sibenik at the paper's grids, every
# variant that BENCHMARKS.md compares, in one call (so ratios come from one machine and run).
# Expects .dev/ as tools/device/pack.sh lays it out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=../irradiant
sibenik=scenes/sibenik/sibenik.toml
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
common=(--scene "$sibenik" --size 1920x1080 --iterations 30)
# ${VARIANTS} lets a call pick extra flags; each line is one bench invocation, its words as the
# shell reads them (quote each spec: --techniques 'ddgi{volume.rays_per_probe = 64}').
default_variants="--techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256}' --vary 'speed.probe_states = [false, true]'"
while IFS= read -r flags; do
    [ -z "$flags" ] && continue
    eval "args=($flags)"
    name=$(echo "$flags" | md5sum | cut -c1-8)
    echo "== $flags" | tee -a "$OUT/ddgi-speed.txt"
    $bin bench "${common[@]}" "${args[@]}" --json "$OUT/ddgi-$name.json" 2>&1 | grep -v "^ *$" | tee -a "$OUT/ddgi-speed.txt"
done <<< "${VARIANTS:-$default_variants}"
