#!/usr/bin/env bash
# Runs on the lent NVIDIA machine (issue 15): `irradiant oracle` — DDGI's probes and query
# against the path tracer — on each scene of $SCENES after each frame count of $FRAMES, for the
# DDGI variants $VARIANTS (default: ddgi) at the preset $PRESET (default: balanced). $BIN picks
# the binary (../irradiant or ../before).
# Writes oracle-<tag>.tgz (oracle.json, histograms, worst probes, error maps) into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
res=$(mktemp -d)
nvidia-smi --query-gpu=name,driver_version --format=csv > "$res/nvidia-smi.txt" 2>&1 || true
bin=${BIN:-../irradiant}
scenes=${SCENES:-"cornell two-rooms box-cylinders empty-box thin-frames scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml"}
for frames in ${FRAMES:-300}; do
    for scene in $scenes; do
        name=$(basename $scene .toml)
        /usr/bin/time -f "%e s" $bin oracle --scene $scene --size 256x192 --frames $frames \
            --average 16 --probe-samples ${PROBE_SAMPLES:-2048} --query-samples ${QUERY_SAMPLES:-512} \
            --preset ${PRESET:-balanced} --techniques "${VARIANTS:-ddgi}" --out "$res/$name-$frames" \
            > "$res/$name-$frames.txt" 2>&1 || true
        echo "== $name, $frames frames"; tail -n +2 "$res/$name-$frames.txt"
    done
done
tar -C "$res" -czf "$OUT/oracle-${TAG:-run}.tgz" .
