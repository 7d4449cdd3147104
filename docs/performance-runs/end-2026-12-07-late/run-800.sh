#!/bin/bash
# Issue #34's benchmark at 800x800: samples/s, wavepath against Mitsuba 3 llvm_ad_rgb,
# alternating, two rounds of 16 spp per renderer and scene (2026-12-07, third session).
cd /work/main && exec bench/throughput_800.sh docs/performance-runs/end-2026-12-07-late
