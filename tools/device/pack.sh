#!/usr/bin/env bash
# Packs the device kit (docs/gpu.md) into device-kit/ at the repository's
# root (ignored by git; the device tool carries it with `carry`): the
# wavepath executable and the test executables that run kernels, stripped;
# every shared library they load beyond glibc's own, the OpenCL ICD loader
# (ocl-icd's libOpenCL.so.1) among them; the scenes; run.sh; and PoCL's
# images of the renders run.sh repeats on the device, with their variances.
#   tools/device/pack.sh [BUILD_DIR]   (default: build; a Release build)
# Needs PoCL here (pocl-opencl-icd) for the reference images.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
kit=$root/device-kit
limit_mib=44 # the tool carries 64 MiB with the working tree (about 19 MiB)

executables=(wavepath wavepath_cl_tests wavepath_kernels_tests)
for e in "${executables[@]}"; do
  [[ -x $build/$e ]] || { echo "pack: error: $build/$e is missing (build first)" >&2; exit 1; }
done
rm -rf "$kit"
mkdir -p "$kit/bin" "$kit/lib" "$kit/ref"
for e in "${executables[@]}"; do
  strip --strip-unneeded -o "$kit/bin/$e" "$build/$e"
done

# Shared libraries: all that ldd resolves, less glibc's (the device's own
# glibc, which is newer, must serve the loader it comes with).
ldd "${executables[@]/#/$build/}" | awk '/=> \// {print $3}' | sort -u | while read -r lib; do
  case $(basename "$lib") in
  libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | librt.so.* | libresolv.so.* | \
    ld-linux-*.so.* | libutil.so.*) continue ;;
  esac
  cp -L "$lib" "$kit/lib/"
done
[[ -e $kit/lib/libOpenCL.so.1 ]] || cp -L /usr/lib/x86_64-linux-gnu/libOpenCL.so.1 "$kit/lib/"

cp -r "$root/scenes" "$kit/scenes"
cp "$root/tools/device/run.sh" "$kit/run.sh"

# PoCL's images: the same executable and libraries as the device run.
export LD_LIBRARY_PATH=$kit/lib OCL_ICD_VENDORS=/etc/OpenCL/vendors
cache=$(mktemp -d)
export WAVEPATH_CACHE_DIR=$cache
reference() { # NAME SCENE ARGS...
  local name=$1 scene=$2
  shift 2
  echo "$*" >"$kit/ref/$name.args"
  if ! "$kit/bin/wavepath" render "$kit/$scene" "$@" --device pthread --quiet \
    -o "$kit/ref/$name.exr" --variance "$kit/ref/$name.var.exr" >"$cache/log" 2>&1; then
    echo "pack: $name: refused on PoCL: $(tail -1 "$cache/log")"
  fi
}
reference hexroom scenes/hexroom.json --width 256 --height 256 --spp 16 --seed 7
reference hexroom-general scenes/hexroom.json --width 256 --height 256 --spp 16 --seed 7 --general
for scene in "$root"/scenes/stress/*.json; do
  name=$(basename "$scene" .json)
  reference "stress-$name" "scenes/stress/$name.json" --width 64 --height 64 --spp 32 --seed 7
done
rm -rf "$cache"

size=$(du -sm "$kit" | cut -f1)
echo "pack: $kit: ${size} MiB ($(du -sh "$kit/bin" | cut -f1) executables, $(du -sh "$kit/lib" |
  cut -f1) libraries, $(du -sh "$kit/ref" | cut -f1) reference images)"
if ((size > limit_mib)); then
  echo "pack: error: the kit is over ${limit_mib} MiB, too much to carry" >&2
  exit 1
fi
