#!/usr/bin/env bash
# Runs on the lent GPU (issue 42, "how cost grows"): `irradiant bench` swept along one axis at
# a time, each point in a process of its own so that its build time and peak memory are its own.
#   PART=rays        ray throughput, BVH build and memory against triangles: Sibenik's world
#                    grown around its own camera (n × n copies, as instances and flattened into
#                    one mesh), so that every size traces the same rays; the shipped scenes as
#                    points beside it.
#   PART=probes      DDGI's update against probe count (1k to 200k, probe states on and off)
#                    and against rays per probe, Sibenik at 1920×1080.
#   PART=resolution  the frame and DDGI's resolve from 720p to 8K, Sibenik.
# PART may list several. Writes growth.tgz into $OUT: growth-<part>-<point>.json and .txt; the plots come
# from `cargo run -p irradiant-eval --example growth_plots -- DIR docs/images/growth`.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
bin=${BIN:-../irradiant}
res=$(mktemp -d)
sibenik=scenes/sibenik/sibenik.toml
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$res/growth-gpu.txt" 2>&1 || true
point() { # name, then bench arguments
    local name=$1; shift
    $bin bench --iterations ${ITERATIONS:-20} --json "$res/growth-$name.json" "$@" \
        > "$res/growth-$name.txt" 2>&1 || echo "$name failed: exit $?" | tee -a "$res/growth-$name.txt"
}
for part in ${PART:-rays probes resolution}; do
    case $part in
    rays)
        mkdir -p scenes/growth
        for n in 1 2 4 8 12; do
            for flat in false true; do
                name=sibenik-world-$n$([ $flat = true ] && echo -flat || true)
                # Sibenik's camera, lights and sky; the copies spread over +x and +z from it.
                sed -e "0,/^name = /s|^name = .*|name = \"$name\"|" \
                    -e '/^\[\[probe_volume\]\]/,$d' $sibenik > scenes/growth/$name.toml
                sed -i "/^path = /a repeat = [$n, 1, $n]\nrepeat_spacing = [42.0, 0.0, 18.0]\nflatten = $flat" \
                    scenes/growth/$name.toml
                point rays-$name --scene scenes/growth/$name.toml
            done
        done
        for s in cornell many-lights scenes/sponza/sponza.toml $sibenik dense-cluster; do
            point rays-$(basename $s .toml) --scene $s
        done
        ;;
    probes)
        for counts in "16, 4, 16" "32, 8, 32" "48, 8, 48" "64, 12, 64" "96, 12, 96" "128, 12, 128"; do
            point probes-$(echo $counts | tr -d ' ' | tr , x) --scene $sibenik \
                --techniques "ddgi{volume.probe_counts = [$counts], volume.rays_per_probe = 256}" \
                --vary 'speed.probe_states = [true, false]'
        done
        point rays-per-probe --scene $sibenik --techniques 'ddgi{volume.probe_counts = [32, 8, 32]}' \
            --vary 'volume.rays_per_probe = [32, 64, 128, 256, 512, 1024]'
        ;;
    resolution)
        for size in 1280x720 1920x1080 2560x1440 3840x2160 5120x2880 7680x4320; do
            point resolution-$size --scene $sibenik --size $size --techniques ddgi
        done
        ;;
    esac
done
grep -h "failed" "$res"/growth-*.txt || true
tar -C "$res" -czf "$OUT/growth.tgz" .
