#!/usr/bin/env bash
# Installs the Debian packages wavepath needs, when any is missing. Idempotent:
# on a machine that has them all it does nothing and needs no network.
# --ci adds what CI checks with beyond the build (.ci/run): clang-format 14,
# chromium for the live preview's browser test (tests/app/test_cli_preview.cpp,
# skipped without it; docs/preview.md gives its download and unpack times),
# and zlib's headers for the sanitizer build's own tinyexr (docs/fuzzing.md).
# --bench adds what the benchmark against Embree needs (bench/, docs/performance.md):
# libembree-dev; neither the default nor --ci installs it.
# --fuzz adds what the libFuzzer build needs (fuzz/, docs/fuzzing.md): clang 14
# with its fuzzer runtime, and zlib's headers.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo oclgrind
  libglm-dev libstb-dev catch2 nlohmann-json3-dev libtinyexr-dev libcli11-dev
  libtinyobjloader-dev libexpat1-dev libcpp-httplib-dev
  libopenmpi-dev openmpi-bin # MPI renders (docs/multi-device.md); optional to the build
)
if [[ "${1:-}" == "--ci" ]]; then
  packages+=(clang-format-14 chromium zlib1g-dev)
fi
if [[ "${1:-}" == "--bench" ]]; then
  packages+=(libembree-dev)
fi
if [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang-14 libclang-rt-14-dev zlib1g-dev)
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
