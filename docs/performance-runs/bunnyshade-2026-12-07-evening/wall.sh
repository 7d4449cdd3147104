#!/bin/bash
# usage: wall.sh ROUNDS SCENE "EXTRA" label=bin ...  (the brief's command, --profile; 256x256 64 spp)
rounds=$1; scene=$2; extra=$3; shift 3
for r in $(seq 1 $rounds); do for v in "$@"; do
  label=${v%%=*}; bin=${v#*=}
  out=$($bin render $scene --width 256 --height 256 --spp 64 -o /tmp/bs/wall-$label.exr --profile $extra 2>&1)
  echo "r$r $label load=$(cut -d' ' -f1 /proc/loadavg) $(echo "$out" | grep '^samples/s:') | $(echo "$out" | grep -E '^(wave|generate|intersect|shade|shadow|accumulate) ' | awk '{printf "%s=%s ", $1, $4}')"
done; done
