#!/bin/bash
# End-of-session side by side (2026-12-08, 23:36-02:36 UTC): main against 4792464
# (/tmp/wavepath-main, this session's start) and Mitsuba 3 llvm_ad_rgb (bench/side_by_side.sh).
cd /work/main && exec bench/side_by_side.sh docs/performance-runs/end-2026-12-08 /tmp/wavepath-main \
  cornell-bunny=/tmp/end/bunny-ref-4k.exr materials/showcase=/tmp/end/showcase-ref-4k.exr \
  hexroom=/tmp/end/hexroom-ref-4k.exr
