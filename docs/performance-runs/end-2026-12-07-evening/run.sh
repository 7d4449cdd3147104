#!/bin/bash
# End-of-session side by side (2026-12-07): main against 89ccb40 and Mitsuba 3.
set -e
cd /work/main
for s in cornell-bunny:bunny-ref-4k materials/showcase:showcase-ref-256-4k hexroom:hexroom-ref-4k; do
  scene=${s%%:*}; ref=${s##*:}; name=$(basename $scene)
  extra=()
  [ "$name" = hexroom ] && extra=(--wp-variant='--mirror-nee off' --peers mitsuba)
  uptime
  python3 bench/peers.py error --scene scenes/$scene.json --reference /tmp/end/$ref.exr --size 256 --spp 64 \
    --rounds 3 --modes two-threads --calibration-spp 64 --peers mitsuba --wavepath build/wavepath \
    --baseline-binary /tmp/wavepath-main "${extra[@]}" --out-dir /tmp/end/$name
  uptime
done
