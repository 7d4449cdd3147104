#!/bin/bash
# alternated --profile renders: prof.sh ROUNDS BIN_A BIN_B
for r in $(seq $1); do for B in $2 $3; do for sc in hex show; do
  case $sc in hex) A="/work/wt-shade3/scenes/hexroom.json --mirror-nee off";; show) A="/work/wt-shade3/scenes/materials/showcase.json";; esac
  out=$($B render $A --width 256 --height 256 --spp 64 -o /tmp/shade3/pr.exr --profile 2>&1)
  sh=$(echo "$out" | awk '$1=="shade"{print $4}'); it=$(echo "$out" | awk '$1=="intersect"{print $4}')
  sps=$(echo "$out" | grep -o 'samples/s: [0-9.e+]*' | head -1)
  echo "$sc r$r $(basename $B) shade_ms $sh intersect_ms $it $sps load $(cut -d' ' -f1 /proc/loadavg)"
done; done; done
