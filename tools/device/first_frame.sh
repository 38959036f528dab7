#!/usr/bin/env bash
# Runs on the lent NVIDIA machine: the first frame after a cut (issue 41, item 1), binaries
# against each other in one call. RUNS lists "binary:settings" pairs (default "before:-
# irradiant:-"): a binary in .dev/ and a settings file (a path from .dev/repo; "-": none), e.g.
# RUNS="before:- irradiant:- irradiant:experiments/more.toml".
# - Direct light only against a direct-only reference (320×240, 4096 samples), in the first
#   frame and after 64 still frames (FRAMES), on each scene in SCENES (default the
#   many-emitter scenes, the stained-glass Sibenik, the Cornell box and Sibenik's two point
#   lights): flip.txt.
# - DDGI's full light against a full reference in the first frame (GI_SCENES): gi.txt.
# - A frame cut at every pixel at 1920×1080 (compare's first frame: its passes' ms, one
#   profiled frame, so the call's first processes may read a cold start), and a
#   swaying view (bench --moving-camera, 30 frames), where the pixels a view uncovers have no
#   history: cost.txt, in two rounds, the runs in order and then reversed.
# PARTS (default "flip gi cost") picks which of the three run; every command's whole output
# goes to log.txt.
# Expects .dev/ as tools/device/pack.sh lays it out; writes into $OUT.
set -euo pipefail
source "$(dirname "$0")/setup.sh"
cd .dev/repo
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv > "$OUT/nvidia-smi.txt" 2>&1 || true
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
runs=(${RUNS:-before:- irradiant:-})
for run in "${runs[@]}"; do
    [[ $run == *:?* ]] || { echo "RUNS: '$run' is not binary:settings (settings '-' for none)" >&2; exit 2; }
done
reversed_runs=($(printf '%s\n' "${runs[@]}" | tac))
printf '' > "$work/-.toml"
settings_of() { [ "$1" = - ] && echo "$work/-.toml" || echo "$1"; }
parts=" ${PARTS:-flip gi cost} "
scenes=(${SCENES:-many-lights scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml cornell scenes/sibenik/sibenik.toml})
if [[ $parts == *" flip "* ]]; then
    for scene in "${scenes[@]}"; do
        name=$(basename "${scene%.*}")
        for run in "${runs[@]}"; do
            bin=${run%%:*} settings=${run#*:}
            for frames in ${FRAMES:-1 64}; do
                ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 320x240 \
                    --frames "$frames" --reference-spp 4096 --cache "$work/cache" \
                    --settings "$(settings_of "$settings")" --out "$work/out" 2>&1 | tee -a "$OUT/log.txt" \
                    | { grep -E "FLIP|rror|panic" || true; } | sed "s|^|$name $bin $settings frames=$frames |" | tee -a "$OUT/flip.txt" || true
            done
        done
    done
fi
if [[ $parts == *" gi "* ]]; then
    for scene in ${GI_SCENES:-cornell scenes/sibenik/stained-glass.toml}; do
        name=$(basename "${scene%.*}")
        for run in "${runs[@]}"; do
            bin=${run%%:*} settings=${run#*:}
            ../$bin compare --scene "$scene" --techniques ddgi --size 320x240 --frames 1 \
                --reference-spp 4096 --cache "$work/cache" --settings "$(settings_of "$settings")" \
                --out "$work/out" 2>&1 | tee -a "$OUT/log.txt" \
                | { grep -E "FLIP|rror|panic" || true; } | sed "s|^|$name $bin $settings |" | tee -a "$OUT/gi.txt" || true
        done
    done
fi
if [[ $parts == *" cost "* ]]; then
    for round in 1 2; do
        order=("${runs[@]}")
        [ $round = 2 ] && order=("${reversed_runs[@]}")
        for scene in scenes/many-lights/four-halls.toml scenes/sibenik/stained-glass.toml; do
            name=$(basename "${scene%.*}")
            for run in "${order[@]}"; do
                bin=${run%%:*} settings=${run#*:}
                ../$bin compare --scene "$scene" --techniques none --reference-bounces 0 --size 1920x1080 \
                    --frames 1 --reference-spp 4 --cache "$work/cache" --settings "$(settings_of "$settings")" \
                    --out "$work/cut" >> "$OUT/log.txt" 2>&1 || continue
                python3 -c "import json, sys; p = dict(json.load(open(sys.argv[1]))['results'][0]['passes']); print(sys.argv[2], ' '.join('%s %.3f' % (k, p.get(k, 0)) for k in ('frame/direct', 'frame/direct_reuse', 'frame/taa')))" \
                    "$work/cut/comparison.json" "round $round $name $bin $settings cut frame" | tee -a "$OUT/cost.txt" || true
                ../$bin bench --scene "$scene" --size 1920x1080 --iterations 30 --techniques none \
                    --moving-camera --settings "$(settings_of "$settings")" 2>&1 \
                    | tee -a "$OUT/log.txt" | { grep -E "^scene |^[a-z0-9-]+ +none " || true; } \
                    | sed "s|^|round $round $name $bin $settings swaying |" | tee -a "$OUT/cost.txt" || true
            done
        done
    done
fi
