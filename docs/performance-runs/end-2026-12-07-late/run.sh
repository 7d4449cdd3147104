#!/bin/bash
# End-of-session side by side (2026-12-07, third session, 20:34-23:34 UTC): main against b1fa640
# (/tmp/wavepath-main, this session's start) and Mitsuba 3 llvm_ad_rgb.
# References: python3 bench/peers.py reference --scene S --size 256 --reference-spp 4096 --out R
set -e
cd /work/main
out=docs/performance-runs/end-2026-12-07-late
for s in cornell-bunny:bunny-ref-4k materials/showcase:showcase-ref-4k hexroom:hexroom-ref-4k; do
  scene=${s%%:*}; ref=${s##*:}; name=$(basename $scene)
  extra=()
  [ "$name" = hexroom ] && extra=(--wp-variant='--mirror-nee off')
  uptime
  python3 bench/peers.py error --scene scenes/$scene.json --reference /tmp/end/$ref.exr --size 256 --spp 64 \
    --rounds 3 --modes two-threads --calibration-spp 64 --peers mitsuba --wavepath build/wavepath \
    --baseline-binary /tmp/wavepath-main "${extra[@]}" --out-dir /tmp/end/$name
  mkdir -p $out/$name && cp /tmp/end/$name/results.json /tmp/end/$name/results.md $out/$name/
  uptime
done
