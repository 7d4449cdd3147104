#!/usr/bin/env bash
# Installs the Debian packages wavepath needs, when any is missing. Idempotent:
# on a machine that has them all it does nothing and needs no network.
# --ci adds what CI checks with beyond the build (.ci/run): clang-format 14,
# ccache for the sanitizer build (.ci/sanitizer-check),
# chromium for the live preview's browser test (tests/app/test_cli_preview.cpp,
# skipped without it; docs/preview.md gives its download and unpack times),
# and clang 15 with libclc for the kernels' GPU-target builds (.ci/gpu-targets-check,
# docs/gpu.md).
# --bench adds what the benchmarks need (bench/, docs/performance.md): libembree-dev
# (against Embree), blender and libllvm19 (bench/peers.py: Cycles, and Mitsuba 3's
# LLVM backend; Dr.Jit 1.5 fails on LLVM 16), and from PyPI mitsuba and numpy;
# neither the default nor --ci installs them.
# --fuzz adds what the libFuzzer build needs (fuzz/, docs/fuzzing.md): clang 14
# with its fuzzer runtime (zlib's headers, which the sanitizer build's own
# tinyexr needs too, are in the default list).
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo oclgrind
  libglm-dev libstb-dev catch2 nlohmann-json3-dev libtinyexr-dev libcli11-dev
  libtinyobjloader-dev libexpat1-dev libpugixml-dev libcpp-httplib-dev
  zlib1g-dev # Mitsuba's .serialized meshes (src/scene/serialized_reader.cpp)
  libopenmpi-dev openmpi-bin # MPI renders (docs/multi-device.md); optional to the build
)
if [[ "${1:-}" == "--ci" ]]; then
  packages+=(clang-format-14 chromium ccache clang-15 libclc-15)
fi
if [[ "${1:-}" == "--bench" ]]; then
  packages+=(libembree-dev blender libllvm19)
fi
if [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang-14 libclang-rt-14-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}" >&2
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
if [[ "${1:-}" == "--bench" ]] && ! python3 -c "import mitsuba, numpy" 2>/dev/null; then
  echo "install-deps: installing mitsuba numpy (pip)" >&2
  python3 -m pip install --quiet mitsuba numpy
fi
