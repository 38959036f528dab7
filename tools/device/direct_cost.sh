#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: what direct light costs (frame/direct, frame/direct_reuse)
# and the path tracer's sample on the many-emitter scenes, 1920×1080, for each binary in BINS
# (default "before irradiant", from .dev/), then again in the reverse order, camera still; then
# once each with the camera swaying, and DDGI (whose probe rays sample the emitters) on
# four-halls (not with STILL_ONLY). SCENES replaces the scene list, TECHNIQUES the still rounds'
# techniques (default none), ITERATIONS the timed frames (default 15). CHECK_ORDER=1 then runs
# the last binary's still bench once more with `--check-order`, which fails where a figure
# moves with the order of the scenes. Expects .dev/ as tools/device/pack.sh lays it out;
# appends the benches' whole output to $OUT/bench.txt.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
compared_binaries
scenes=${SCENES:-many-lights,scenes/many-lights/four-halls.toml,cornell}
iterations=${ITERATIONS:-15}
techniques=${TECHNIQUES:-none}
bench() {
    local bin=$1 name=$2
    shift 2
    echo "== $name: $bin bench --size 1920x1080 --iterations $iterations $*" >> "$OUT/bench.txt"
    ../$bin bench --size 1920x1080 --iterations "$iterations" "$@" 2>&1 | tee -a "$OUT/bench.txt" \
        | grep -E "^[a-z-]+ +(none|ddgi) |pathtrace/wavefront \(1|order of the scenes|^  " | sed "s|^|$name |"
}
for round in 1 2; do
    order=("${bins[@]}"); [ $round = 2 ] && order=($reversed)
    for bin in "${order[@]}"; do
        bench "$bin" "still-$round-$bin" --scene "$scenes" --techniques "$techniques"
    done
done
if [ -n "${CHECK_ORDER:-}" ]; then
    bench "${bins[-1]}" "check-order-${bins[-1]}" --scene "$scenes" --techniques "$techniques" --check-order \
        && echo "check-order: passed" || echo "check-order: FAILED (the figures moved with the order)"
fi
[ -n "${STILL_ONLY:-}" ] && exit 0
for bin in "${bins[@]}"; do
    bench "$bin" "moving-$bin" --scene "$scenes" --techniques none --moving-camera
    bench "$bin" "ddgi-$bin" --scene scenes/many-lights/four-halls.toml --techniques ddgi
done
