#!/usr/bin/env bash
# Samples/s of one render on one device, on two devices in one process, and
# on two MPI ranks, with the ratio of each combination to its ideal
# (docs/multi-device.md). Each configuration runs ROUNDS times, interleaved
# with the others so that a change of the machine's load hits them alike;
# the table shows medians.
#
# On a CPU-only machine the devices are PoCL's CPU device. Two of them in one
# process (POCL_DEVICES="pthread pthread") share PoCL's one pool of worker
# threads (one per core), so their ideal is one device with that pool: the
# ratio measures what the split costs. Two MPI ranks are two processes with
# a pool each; with POCL_MAX_PTHREAD_COUNT=1 each has one core's thread, and
# their ideal is the sum of two one-thread devices.
#
#   tools/bench-multi-device.sh [BUILD_DIR] [SCENE] [SIZE] [SPP] [ROUNDS]
set -euo pipefail
build=${1:-build}
scene=${2:-scenes/hexroom.json}
size=${3:-256}
spp=${4:-32}
rounds=${5:-3}
exe="$build/wavepath"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mpirun_flags=(--oversubscribe)
[ "$(id -u)" = 0 ] && mpirun_flags+=(--allow-run-as-root)
args=(render "$scene" --spp "$spp" --width "$size" --height "$size")

# samples/s from the "rendered ..." line of a render's stdout
rate() { sed -n 's/^rendered .* \([0-9.e+]*\) samples\/s.*/\1/p'; }

run_config() { # NAME: one line of samples/s on stdout
    case "$1" in
    one-thread) POCL_DEVICES=pthread POCL_MAX_PTHREAD_COUNT=1 "$exe" "${args[@]}" --out "$out/a.exr" ;;
    one-device) POCL_DEVICES=pthread "$exe" "${args[@]}" --out "$out/b.exr" ;;
    two-devices) POCL_DEVICES="pthread pthread" "$exe" "${args[@]}" --device all --out "$out/c.exr" ;;
    two-ranks) POCL_DEVICES=pthread POCL_MAX_PTHREAD_COUNT=1 mpirun "${mpirun_flags[@]}" -np 2 \
        "$exe" "${args[@]}" --out "$out/d.exr" ;;
    esac 2>/dev/null | rate
}

configs=(one-thread one-device two-devices)
command -v mpirun >/dev/null && configs+=(two-ranks)
run_config two-devices >/dev/null # fill the program cache: no figure includes a build
declare -A runs
for ((r = 0; r < rounds; ++r)); do
    for c in "${configs[@]}"; do
        runs[$c]+="$(run_config "$c") "
    done
done
median() { tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

echo "$scene, ${size}x${size}, $spp spp, $(nproc) cores, median of $rounds; load average $(cut -d' ' -f1-3 /proc/loadavg)"
awk -v t="$(median <<<"${runs[one-thread]}")" -v d="$(median <<<"${runs[one-device]}")" \
    -v m="$(median <<<"${runs[two-devices]}")" -v r="$(median <<<"${runs[two-ranks]:-}")" \
    -v all_t="${runs[one-thread]}" -v all_d="${runs[one-device]}" -v all_m="${runs[two-devices]}" \
    -v all_r="${runs[two-ranks]:-}" 'BEGIN {
    printf "%-52s %10s %-12s %8s  %s\n", "configuration", "samples/s", "ideal", "of ideal", "runs"
    printf "%-52s %10.4g %-12s %8s  %s\n", "A: one device, one thread", t, "", "", all_t
    printf "%-52s %10.4g %-12s %8s  %s\n", "B: one device, all cores", d, "", "", all_d
    printf "%-52s %10.4g %-12s %7.1f%%  %s\n", "two devices, one process (shared PoCL pool)", m, "B", 100 * m / d, all_m
    if (r != "")
        printf "%-52s %10.4g %-12s %7.1f%%  %s\n", "two MPI ranks, one thread each", r, "2 x A", 100 * r / (2 * t), all_r
}'
