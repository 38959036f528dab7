#!/usr/bin/env bash
# Packs Mitsuba 3 and Dr.Jit for the lent GPU, which has no network (tools/device/peer.sh):
# the wheels for its Python (3.12) from PyPI, trimmed to what tools/mitsuba/rays.py uses: the
# cuda_ad_rgb variant (scalar_rgb beside it), the two plugins a bare mesh loads (diffuse,
# uniform); no other variant, plugin, spectral data, header or type stub. The result is
# .dev/peer.tar.xz (about 15 MB), small enough to carry with the binary. Run after
# tools/device/pack.sh, which lays out .dev/.
set -euo pipefail
cd "$(dirname "$0")/../.."
work=$(mktemp -d)
pip download --quiet --no-deps --only-binary=:all: --python-version 3.12 \
    --platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 \
    --dest "$work" mitsuba==3.9.1 drjit==1.5.0
mkdir "$work/site"
for wheel in "$work"/*.whl; do (cd "$work/site" && unzip -q -o "$wheel"); done
cd "$work/site"
rm -rf mitsuba/llvm_* mitsuba/cuda_ad_mono* mitsuba/cuda_ad_spectral* mitsuba/include mitsuba/cmake \
    mitsuba/pkgconfig mitsuba/mitsuba_stubs drjit/include drjit/cmake ./*.dist-info
find mitsuba/plugins -name "*.so" ! -name diffuse.so ! -name uniform.so -delete
rm -rf mitsuba/data
find . -name "*.pyi" -delete
tar cf - mitsuba drjit | xz -6 -T2 > "$OLDPWD/.dev/peer.tar.xz"
rm -rf "$work"
ls -la "$OLDPWD/.dev/peer.tar.xz"
