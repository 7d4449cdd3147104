#!/bin/bash
cd /work/wt-bunnyrel
W=/tmp/wavepath-main; S=scenes/cornell-bunny.json; R=/tmp/bunnyrel/r
for n in 1 2 3 4; do
  for d in 2 3; do
  $W render $S --width 256 --height 256 --spp 64 --seed $n --roulette-depth $d -q -o $R/wp-rr$d-$n.exr
  done
done
echo ALLDONE
