#!/bin/bash
# usage: measure.sh ROUNDS SCENE_TAG BIN_A BIN_B ...  (alternating, perf samples in shade.so / intersect.so)
ROUNDS=$1; TAG=$2; shift 2
case $TAG in
  show) ARGS="/work/wt-shade3/scenes/materials/showcase.json --spp 64";;
  hex) ARGS="/work/wt-shade3/scenes/hexroom.json --mirror-nee off --spp 64";;
  hex32) ARGS="/work/wt-shade3/scenes/hexroom.json --mirror-nee off --spp 32";;
  show32) ARGS="/work/wt-shade3/scenes/materials/showcase.json --spp 32";;
  bunny) ARGS="/work/wt-shade3/scenes/cornell-bunny.json --spp 32";;
esac
for B in "$@"; do $B render ${ARGS%% *} --spp 1 --width 64 --height 64 ${ARGS#* } -o /tmp/shade3/warm.exr -q >/dev/null 2>&1; done
for r in $(seq $ROUNDS); do for B in "$@"; do
  out=$(perf record -q -o /tmp/shade3/m.data $B render $ARGS --width 256 --height 256 --seed 3 -o /tmp/shade3/m.exr -q 2>&1 | grep -o '[0-9.]* s,' | head -1)
  perf report -i /tmp/shade3/m.data --no-children --sort dso -n 2>/dev/null > /tmp/shade3/m.txt
  K=${K:-shade.so}; sh=$(awk -v k=$K '$3==k{print $2}' /tmp/shade3/m.txt); in=$(awk '$3=="intersect.so"{print $2}' /tmp/shade3/m.txt)
  echo "$TAG round $r $(basename $B): shade $sh intersect $in ratio $(python3 -c "print(round($sh/$in,3))") wall $out load $(cut -d' ' -f1 /proc/loadavg)"
done; done
