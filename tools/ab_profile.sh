#!/bin/bash
# Whole-render stage times of wavepath builds side by side, alternated:
#   tools/ab_profile.sh ROUNDS SPP BINARY_A BINARY_B [...]
# Each binary first renders the hexroom at 256x256, 1 spp (PoCL compiles
# and caches its kernels for that size), then every round renders it at
# SPP samples with --profile, A B A B ..., and prints the intersect, shade
# and shadow device milliseconds and the samples/s line of each run
# (docs/performance.md, where it is used from the fourth session on).
set -euo pipefail
rounds=$1
spp=$2
shift 2
cd "$(dirname "$0")/.."
for binary in "$@"; do
    "$binary" render scenes/hexroom.json --width 256 --height 256 --spp 1 -o /tmp/ab_profile.exr -q \
        >/dev/null 2>&1
done
for round in $(seq "$rounds"); do
    for binary in "$@"; do
        out=$("$binary" render scenes/hexroom.json --width 256 --height 256 --spp "$spp" \
            -o /tmp/ab_profile.exr --profile -q 2>&1)
        stages=$(echo "$out" | awk '/^(intersect|shade|shadow) /{printf "%s %s ms  ", $1, $4}')
        rate=$(echo "$out" | grep '^samples/s' | sed 's/, device busy.*//')
        echo "$binary round $round load $(cut -d' ' -f1 /proc/loadavg): $stages$rate"
    done
done
