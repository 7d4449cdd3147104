#!/bin/bash
# Issue #34's benchmark at 800x800: samples/s, wavepath (build/wavepath)
# against Mitsuba 3 llvm_ad_rgb, alternating, two rounds of 16 spp per
# renderer and scene; the hexroom adds wavepath with Mitsuba's estimator
# (--mirror-nee off).
#
#   bench/throughput_800.sh OUT_DIR
#
# Each scene's results.md and results.json are copied to OUT_DIR/size-800/NAME;
# the full output stays in /tmp/end800/NAME.
set -e
[ $# -eq 1 ] || { echo "usage: $0 OUT_DIR" >&2; exit 2; }
out=$1/size-800
cd "$(dirname "$0")/.."
for scene in hexroom cornell-bunny materials/showcase; do
  name=$(basename $scene)
  extra=()
  [ "$name" = hexroom ] && extra=(--wp-variant='--mirror-nee off')
  uptime
  python3 bench/peers.py throughput --scene scenes/$scene.json --sizes 800 --spp-single 16 --rounds 2 \
    --calibration-spp 16 --peers mitsuba --wavepath build/wavepath "${extra[@]}" --out-dir /tmp/end800/$name
  mkdir -p $out/$name && cp /tmp/end800/$name/results.json /tmp/end800/$name/results.md $out/$name/
  uptime
done
