#!/bin/bash
# Issue #34's end-of-session run: each scene's error per second side by side,
# wavepath (build/wavepath) against an earlier wavepath binary and Mitsuba 3
# llvm_ad_rgb, 256x256 at 64 spp, three alternated rounds on two threads; the
# hexroom adds wavepath with Mitsuba's estimator (--mirror-nee off).
#
#   bench/side_by_side.sh OUT_DIR BASELINE_BINARY SCENE=REFERENCE...
#
# SCENE is a path under scenes/ without .json (cornell-bunny, materials/showcase,
# hexroom); REFERENCE a long Mitsuba render of it, made by
#   python3 bench/peers.py reference --scene scenes/SCENE.json --size 256 --reference-spp 4096 --out REFERENCE
# Each scene's results.md and results.json are copied to OUT_DIR/NAME (NAME:
# the scene's file name); the full output stays in /tmp/end/NAME.
set -e
[ $# -ge 3 ] || { echo "usage: $0 OUT_DIR BASELINE_BINARY SCENE=REFERENCE..." >&2; exit 2; }
out=$1 baseline=$2
shift 2
cd "$(dirname "$0")/.."
for pair in "$@"; do
  scene=${pair%%=*}; reference=${pair#*=}; name=$(basename "$scene")
  extra=()
  [ "$name" = hexroom ] && extra=(--wp-variant='--mirror-nee off')
  uptime
  python3 bench/peers.py error --scene "scenes/$scene.json" --reference "$reference" --size 256 --spp 64 \
    --rounds 3 --modes two-threads --calibration-spp 64 --peers mitsuba --wavepath build/wavepath \
    --baseline-binary "$baseline" "${extra[@]}" --out-dir "/tmp/end/$name"
  mkdir -p "$out/$name" && cp "/tmp/end/$name/results.json" "/tmp/end/$name/results.md" "$out/$name/"
  uptime
done
