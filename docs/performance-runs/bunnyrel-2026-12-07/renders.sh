#!/bin/bash
# Seeds of wavepath main (roulette from 1, from 5) and Mitsuba 3 on the bunny, 256x256, 64 spp
cd /work/wt-bunnyrel
W=/tmp/wavepath-main; S=scenes/cornell-bunny.json; R=/tmp/bunnyrel/r
for n in 1 2 3 4; do
  $W render $S --width 256 --height 256 --spp 64 --seed $n -q -o $R/wp-rr1-$n.exr
  $W render $S --width 256 --height 256 --spp 64 --seed $n --roulette-depth 5 -q -o $R/wp-rr5-$n.exr
  python3 bench/peers_mitsuba.py /tmp/bunnyrel/bunny.xml --spp 64 --seed $n --out $R/mts-$n.exr
done
for t in camera direct indirect; do
  for n in 1 2; do $W render $S --width 256 --height 256 --spp 64 --seed $n --path-types $t -q -o $R/wp-rr1-$t-$n.exr; done
done
for d in 1 2 3 4; do
  $W render $S --width 256 --height 256 --spp 64 --seed 1 --max-depth $d -q -o $R/wp-rr1-maxd$d-1.exr
  $W render $S --width 256 --height 256 --spp 64 --seed 1 --max-depth $d --roulette-depth 5 -q -o $R/wp-rr5-maxd$d-1.exr
done
echo ALLDONE
