#!/bin/bash
# The new default against main's binary, alternated, on the three scenes.
cd /work/wt-relmse
WP=/tmp/relmse/wp-new
OUT=/tmp/relmse/confirm2
mkdir -p $OUT
uptime > $OUT/uptime-start.txt
python3 bench/peers.py error --scene scenes/materials/showcase.json --reference /tmp/showcase-ref-256-4k.exr \
  --size 256 --spp 64 --rounds 3 --modes two-threads --calibration-spp 64 --peers mitsuba \
  --wavepath $WP --wp-variant='--roulette-depth 1' --baseline-binary /tmp/relmse-wp-main --out-dir $OUT/showcase > $OUT/showcase.log 2>&1
uptime > $OUT/uptime-mid.txt
for s in hexroom cornell-bunny; do
python3 bench/peers.py error --scene scenes/$s.json --reference /tmp/shading-refs/$s-128-1024.exr \
  --spp 64 --rounds 3 --modes two-threads --calibration-spp 64 --peers mitsuba \
  --wavepath $WP --baseline-binary /tmp/relmse-wp-main --out-dir $OUT/$s > $OUT/$s.log 2>&1
done
uptime > $OUT/uptime-end.txt
