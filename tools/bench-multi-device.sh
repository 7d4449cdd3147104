#!/usr/bin/env bash
# Samples/s of one render on one device, on two devices in one process, and
# on two MPI ranks, with the ratio of each combination to the ideal sum of
# its parts (docs/multi-device.md). On a CPU-only machine the "devices" are
# PoCL's CPU device shown twice (POCL_DEVICES="pthread pthread"), each
# limited to one thread (POCL_MAX_PTHREAD_COUNT=1), so that the two parts
# together use the machine's two cores as one device with two threads does.
#
#   tools/bench-multi-device.sh [BUILD_DIR] [SCENE] [SIZE] [SPP]
set -euo pipefail
build=${1:-build}
scene=${2:-scenes/hexroom.json}
size=${3:-256}
spp=${4:-32}
exe="$build/wavepath"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mpirun_flags="--oversubscribe"
[ "$(id -u)" = 0 ] && mpirun_flags="$mpirun_flags --allow-run-as-root"

# samples/s from the "rendered ..." line of a render's stdout
rate() { sed -n 's/^rendered .* \([0-9.e+]*\) samples\/s.*/\1/p'; }

render() { # ENV... -- ARGS...
    local env=()
    while [ "$1" != -- ]; do env+=("$1"); shift; done
    shift
    env "${env[@]}" "$exe" render "$scene" --spp "$spp" --width "$size" --height "$size" \
        --out "$out/x.exr" "$@" 2>/dev/null | rate
}

one_thread="POCL_MAX_PTHREAD_COUNT=1"
two="POCL_DEVICES=pthread pthread"
# Warm the program cache, so that no figure includes a kernel build.
render "$two" -- --device all >/dev/null

alone_a=$(render "$two" "$one_thread" -- --device 0:0)
alone_b=$(render "$two" "$one_thread" -- --device 0:1)
both=$(render "$two" "$one_thread" -- --device all)
full=$(render "POCL_DEVICES=pthread" -- --device 0:0)
mpi=""
if command -v mpirun >/dev/null; then
    mpi=$(env POCL_DEVICES=pthread "$one_thread" mpirun $mpirun_flags -np 2 \
        "$exe" render "$scene" --spp "$spp" --width "$size" --height "$size" \
        --out "$out/m.exr" 2>/dev/null | rate)
fi

echo "$scene, ${size}x${size}, $spp spp, $(nproc) cores (samples/s)"
awk -v a="$alone_a" -v b="$alone_b" -v both="$both" -v full="$full" -v mpi="$mpi" 'BEGIN {
    printf "%-46s %12s %10s\n", "configuration", "samples/s", "of ideal"
    printf "%-46s %12.4g %10s\n", "device 0:0 alone, 1 thread", a, ""
    printf "%-46s %12.4g %10s\n", "device 0:1 alone, 1 thread", b, ""
    printf "%-46s %12.4g %9.1f%%\n", "both in one process (--device all)", both, 100 * both / (a + b)
    if (mpi != "")
        printf "%-46s %12.4g %9.1f%%\n", "two MPI ranks, one 1-thread device each", mpi, 100 * mpi / (a + b)
    printf "%-46s %12.4g %9.1f%%\n", "one device, 2 threads (for comparison)", full, 100 * full / (a + b)
}'
