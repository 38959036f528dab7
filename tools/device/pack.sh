#!/usr/bin/env bash
# Lays out .dev/ for the lent GPU machine (which has no Rust toolchain and no ../shared):
# the release binary, the manifests, and the shared scenes at the same relative place.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --locked -p irradiant-cli
cargo build --release --locked -p irradiant --example raster_host
rm -rf .dev && mkdir -p .dev/repo .dev/shared/scenes
target="${CARGO_TARGET_DIR:-target}"
cp "$target/release/irradiant" .dev/
# The raster host (crates/irradiant/examples/raster_host/), for tools/device/embedding.sh.
cp "$target/release/examples/raster_host" .dev/
cp -r scenes .dev/repo/
cp -r ../shared/scenes/sponza-dabrovic ../shared/scenes/sibenik ../shared/scenes/cornell-box .dev/shared/scenes/
cp tools/device/*.sh .dev/
# Manifests of oracle experiments (docs/ddgi.md): SCENES=experiments/empty-box-walls.toml.
cp -r tools/device/scenes .dev/repo/experiments
# The binary before a change, for like-for-like measurements (tools/device/platform.sh).
[ -x .dev-before/irradiant ] && cp .dev-before/irradiant .dev/before
mkdir -p .dev/repo/tools && cp tools/reports.sh .dev/repo/tools/
du -sh .dev
