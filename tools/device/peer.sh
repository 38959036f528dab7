#!/usr/bin/env bash
# Runs on the lent GPU (issue 42, "the peer, side by side"): Irradiant's ray throughput and
# Mitsuba 3's (cuda_ad_rgb, OptiX) on the very same rays, in one call. `irradiant bench
# --dump-rays` writes each scene's triangles and the primary and diffuse rays it timed;
# tools/mitsuba/rays.py builds one Mitsuba mesh of those triangles and times the same rays.
# Order: Irradiant, Mitsuba, Irradiant again, so that drift over the call shows. Needs
# .dev/peer.tar.xz (tools/mitsuba/pack.sh). SCENES: comma-separated, as bench takes them.
# Writes peer.tgz into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
site=$(mktemp -d)
tar -C "$site" -xJf .dev/peer.tar.xz
cd .dev/repo
res=$(mktemp -d)
rays=$(mktemp -d)
scenes=${SCENES:-cornell,many-lights,scenes/sponza/sponza.toml,scenes/sibenik/sibenik.toml,dense-cluster}
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/gpu.txt" 2>&1 || true
bench() { ../irradiant bench --size 1920x1080 --iterations 30 --warmup-ms 500 --scene "$scenes" "$@"; }
bench --dump-rays "$rays" --json "$res/irradiant-1.json" > "$res/irradiant-1.txt" 2>&1
PYTHONPATH="$site" python3 ../../tools/mitsuba/rays.py "$rays" --iterations 30 --json "$res/mitsuba.json" \
    > "$res/mitsuba.txt" 2>&1 || echo "mitsuba failed: exit $?" >> "$res/mitsuba.txt"
bench --json "$res/irradiant-2.json" > "$res/irradiant-2.txt" 2>&1
grep -h "raycast/trace" "$res"/irradiant-*.txt
cat "$res/mitsuba.txt" | tail -30
tar -C "$res" -czf "$OUT/peer.tgz" .
