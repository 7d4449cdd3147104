#!/bin/bash
# Issue #34's benchmark at 800x800: samples/s, wavepath against Mitsuba 3 llvm_ad_rgb,
# alternating, two rounds of 16 spp per renderer and scene (2026-12-08, 23:36-02:36 UTC session).
set -e
cd /work/main
out=docs/performance-runs/end-2026-12-08/size-800
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
