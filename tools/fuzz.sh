#!/usr/bin/env bash
# Runs the cargo-fuzz targets of fuzz/ one after another, each for SECONDS (default 1800),
# seeded with fuzz/seeds/<target> (the shipped scenes, manifests, textures and a reference),
# keeping what it learns in fuzz/corpus/<target> and any crash in fuzz/artifacts/<target>.
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`). Usage:
#   tools/fuzz.sh [SECONDS] [TARGET ...]          (default: every target)
# The log of each run, with its length and result, goes to fuzz/logs/<target>.log; record
# them in docs/reliability.md.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:-1800}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(obj gltf manifest texture reference_cache bake_cache settings)
fi
mkdir -p logs
# No sanitizer: the code is safe Rust, so what fuzzing can find is a panic, a hang or a
# runaway allocation, which libFuzzer reports without one, at several times the speed.
cargo +nightly fuzz build -s none
for target in "${targets[@]}"; do
    mkdir -p "corpus/$target" "artifacts/$target"
    start=$(date -u +%FT%TZ)
    set +e
    cargo +nightly fuzz run -s none "$target" "corpus/$target" "seeds/$target" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -max_len=262144 \
        -artifact_prefix="artifacts/$target/" -print_final_stats=1 > "logs/$target.log" 2>&1
    status=$?
    set -e
    echo "$target: started $start, ${seconds} s, exit $status, $(grep -c '' "logs/$target.log") log lines, $(ls "artifacts/$target" | wc -l) artifacts" | tee -a logs/summary.txt
done
