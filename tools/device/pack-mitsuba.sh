#!/usr/bin/env bash
# Adds Mitsuba 3 to the device kit (docs/gpu.md), for run.sh's side-by-side
# step: the mitsuba and drjit wheels from PyPI for the device's Python,
# trimmed to what the cuda_ad_rgb variant needs to render the hexroom as
# `wavepath export-mitsuba` writes it, as device-kit/mitsuba.tar.xz (about
# 16 MiB; the whole wheel, 63 MiB, is more than the device tool carries);
# and the hexroom at 800x800 as Mitsuba XML in device-kit/mitsuba/.
#   tools/device/pack-mitsuba.sh [BUILD_DIR] [PYTHON_VERSION]
# (defaults: build, 3.12: the device's python3). Run after pack.sh.
# What is cut: the other variants' modules, the biggest plugins that a
# surface-only RGB scene cannot use (volumes, curves, sky models, measured
# BSDFs), headers, type stubs and srgb.coeff (the spectral variants' RGB
# upsampling, loaded only by them).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
python_version=${2:-3.12}
kit=$root/device-kit
mitsuba_version=3.9.1 drjit_version=1.5.0
[[ -d $kit ]] || { echo "pack-mitsuba: error: $kit is missing (run pack.sh first)" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tag=cp${python_version/./}
python3 -m pip download --quiet --no-deps --only-binary=:all: --python-version "$python_version" \
  --implementation cp --platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 \
  --platform manylinux_2_17_x86_64 -d "$work/wheels" \
  "mitsuba==$mitsuba_version" "drjit==$drjit_version"
mkdir "$work/site"
for wheel in "$work"/wheels/*-"$tag"-*.whl; do
  (cd "$work/site" && python3 -m zipfile -e "$wheel" .)
done

cd "$work/site/mitsuba"
find . -name '*.so' -path './*_ad_*' ! -name 'cuda_ad_rgb.*' -delete
rm -f scalar_spectral*.so scalar_mono*.so
rm -rf include pkgconfig cmake mitsuba_stubs data/srgb.coeff data/sunsky
# Plugins: Mitsuba instantiates some the XML never names (merge, for one),
# so the cut is a list of what no surface-only RGB scene can use.
unused=(ellipsoids ellipsoidsmesh volpath volpathmis bsplinecurve linearcurve sdfgrid sunsky
  timed_sunsky ptracer cylinder principled principledthin hair measured measured_polarized
  gridvolume pplastic aov batch projector polarizer retarder)
for name in "${unused[@]}"; do
  rm -f "plugins/$name.so"
done
cd "$work/site"
rm -rf drjit/include drjit/cmake share ./*.dist-info/RECORD
find . -name '*.pyi' -delete
tar -cf - mitsuba drjit ./*.dist-info | xz -T2 -6 >"$kit/mitsuba.tar.xz"

mkdir -p "$kit/mitsuba"
"$build/wavepath" export-mitsuba "$root/scenes/hexroom.json" "$kit/mitsuba/hexroom.xml" \
  --width 800 --height 800 --spp 64 >/dev/null
cp "$root/tools/device/mitsuba_gpu.py" "$kit/mitsuba/"
echo "pack-mitsuba: $kit/mitsuba.tar.xz: $(du -sh "$kit/mitsuba.tar.xz" | cut -f1) (mitsuba" \
  "$mitsuba_version, drjit $drjit_version, Python $python_version); kit $(du -sh "$kit" | cut -f1)"
