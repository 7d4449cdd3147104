#!/bin/bash
# End-of-session side by side (2026-12-07, night session): main against 93b5efb
# (/tmp/wavepath-main, this session's start) and Mitsuba 3 llvm_ad_rgb (bench/side_by_side.sh,
# whose commands this run used, written out here at the time).
cd /work/main && exec bench/side_by_side.sh docs/performance-runs/end-2026-12-07-night /tmp/wavepath-main \
  cornell-bunny=/tmp/end/bunny-ref-4k.exr materials/showcase=/tmp/end/showcase-ref-256-4k.exr \
  hexroom=/tmp/end/hexroom-ref-4k.exr
