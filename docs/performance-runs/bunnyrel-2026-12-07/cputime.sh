#!/bin/bash
# CPU seconds (user+sys) and wall seconds of 64-spp renders, variants alternated, 3 rounds: the cost on a shared machine
cd /work/wt-bunnyrel
W=/tmp/bunnyrel/wp-rules
for scene in $@; do
for round in 1 2 3; do
  for v in "--roulette throughput" "--roulette relative" "--roulette-depth 5" "--roulette sqrt"; do
    /usr/bin/time -f "$scene round $round [$v]: cpu %U+%S s wall %e s" $W render $scene --width 256 --height 256 --spp 64 --seed $round $v -q -o /tmp/bunnyrel/cpu.exr 2>&1 | grep -v "^paths\|^wavepath:" | sed "s/.*spp, //"
  done
done
done
