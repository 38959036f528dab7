#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: TAA's history, the binary before a change (.dev/before)
# against after (.dev/irradiant). MODE=speed: the frame pass by pass at 1920×1080 with the
# camera swaying (bench --moving-camera) and still, Sibenik at 32×8×32 probes × 256 rays and
# Sponza's own volume, in the order before, after, after, before; a third binary
# .dev/baseline, when there, is timed first and last with the camera swaying through
# IRRADIANT_BENCH_MOVING (issue 15's f2daeb4 with that sway backported; BENCHMARKS.md,
# 2026-11-24, 2eecf16). MODE=quality: `compare` of DDGI on the Cornell box at 256×192 against a
# 4096-sample reference at each of $BLENDS ("blend:frames"), then tools/device/quality.sh's
# scenes. Writes taa.txt (and quality.tgz) into $OUT.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
log="$OUT/taa.txt"
bench() { # binary, tag, extra flags...
    local b=$1 tag=$2
    shift 2
    # .dev/baseline (and a .dev/before older than the techniques' specs) knows only the old
    # --ddgi-* flags; the same frames through them.
    local help
    help=$($b bench --help 2>&1 || true)
    for scene in sibenik sponza; do
        # Sibenik at the paper's grid; Sponza's own volume.
        local flags
        if [[ $help == *--vary* ]]; then
            flags=(--techniques 'ddgi{volume.rays_per_probe = 256, speed.probe_states = true}')
            [ $scene = sibenik ] && flags=(--techniques 'ddgi{volume.probe_counts = [32, 8, 32], volume.rays_per_probe = 256, speed.probe_states = true}')
        else
            flags=(--ddgi-probes scene --ddgi-rays 256 --ddgi-probe-states on)
            [ $scene = sibenik ] && flags=(--ddgi-probes 32x8x32 --ddgi-rays 256 --ddgi-probe-states on)
        fi
        echo "== $tag $scene $*" | tee -a "$log"
        $b bench --scene scenes/$scene/$scene.toml --size 1920x1080 --iterations 30 \
            --warmup-ms 500 "${flags[@]}" "$@" \
            2>&1 | { grep -E "^scene +technique|^(sibenik|sponza) +ddgi +[0-9]" || true; } | tee -a "$log"
    done
}
if [ "${MODE:-speed}" = speed ]; then
    if [ -x ../baseline ]; then IRRADIANT_BENCH_MOVING=1 bench ../baseline baseline-moving; fi
    for b in ../before ../irradiant ../irradiant ../before; do
        bench $b "$(basename $b)-moving" --moving-camera
        bench $b "$(basename $b)-still"
    done
    if [ -x ../baseline ]; then IRRADIANT_BENCH_MOVING=1 bench ../baseline baseline-moving; fi
else
    res=$(mktemp -d)
    for b in ../before ../irradiant; do
        for bf in ${BLENDS:-0.1:300 0.05:300 0.01:1500}; do
            printf '[frame.taa]\nblend = %s\n' "${bf%%:*}" > "$res/blend.toml"
            echo "== $(basename $b) cornell blend ${bf%%:*}, ${bf##*:} frames" | tee -a "$log"
            $b compare --scene cornell --size 256x192 --reference-spp 4096 --frames "${bf##*:}" \
                --settings "$res/blend.toml" --cache "$res/cache" --techniques ddgi \
                --out "$res/cornell" 2>&1 | { grep -E "FLIP" || true; } | tee -a "$log"
        done
    done
    rm -rf "$res"
    TECHNIQUES=ddgi SCENES="${SCENES:-two-rooms box-cylinders scenes/sponza/sponza.toml scenes/sibenik/sibenik.toml}" \
        bash -c "cd ../.. && bash '$here/quality.sh'" 2>&1 | tee -a "$log"
fi
