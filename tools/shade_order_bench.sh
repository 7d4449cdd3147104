#!/bin/bash
# Shade in arrival order against shade sorted by material (--shade-order),
# side by side, alternated (docs/performance.md, "Shading sorted by
# material"):
#   tools/shade_order_bench.sh BINARY ROUNDS SPP SCENE [SCENE ...]
# Each scene first renders once at 256x256, 1 spp (PoCL compiles and caches
# its kernels), then every round renders it at SPP samples with --profile,
# arrival then sorted, and prints the stages' device milliseconds and the
# samples/s line of each run with the load.
set -euo pipefail
binary=$1
rounds=$2
spp=$3
shift 3
cd "$(dirname "$0")/.."
for scene in "$@"; do
    "$binary" render "$scene" --width 256 --height 256 --spp 1 --launch-plan stages \
        -o /tmp/shade_order_bench.pfm -q >/dev/null 2>&1
done
for round in $(seq "$rounds"); do
    for scene in "$@"; do
        for order in arrival sorted; do
            out=$("$binary" render "$scene" --width 256 --height 256 --spp "$spp" \
                --launch-plan stages --shade-order "$order" -o /tmp/shade_order_bench.pfm \
                --profile -q 2>&1)
            stages=$(echo "$out" |
                awk '/^(intersect|shade_sort|shade|shadow) /{printf "%s %s ms  ", $1, $4}')
            rate=$(echo "$out" | grep '^samples/s' | sed 's/, device busy.*//')
            echo "$(basename "$scene" .json) $order round $round load" \
                "$(cut -d' ' -f1 /proc/loadavg): $stages$rate"
        done
    done
done
