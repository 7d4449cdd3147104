#!/bin/bash
cd /work/wt-bunnyrel
W=/tmp/bunnyrel/wp-rules; S=scenes/cornell-bunny.json; R=/tmp/bunnyrel/r
for n in 1 2 3 4; do
  for rule in relative sqrt; do
  $W render $S --width 256 --height 256 --spp 64 --seed $n --roulette $rule -q -o $R/wp-$rule-$n.exr
  done
done
echo ALLDONE
