#!/bin/bash
# usage: ab.sh ROUNDS SCENE SPP "EXTRA ARGS" label=binary[,ENV=V] ...
rounds=$1; scene=$2; spp=$3; extra=$4; shift 4
for r in $(seq 1 $rounds); do
  for v in "$@"; do
    label=${v%%=*}; rest=${v#*=}; bin=${rest%%,*}; envs=""
    [[ "$rest" == *,* ]] && envs=${rest#*,}
    env $envs perf record -q -o /tmp/bs/ab.data $bin render $scene --width 256 --height 256 --spp $spp -o /tmp/bs/ab-$label.exr --profile-json /tmp/bs/ab.json -q $extra >/dev/null 2>&1
    tot=$(perf report -i /tmp/bs/ab.data --no-children --sort dso -n --stdio 2>/dev/null | awk '/^ +[0-9.]+%/ {s+=$2} END{print s}')
    so=$(perf report -i /tmp/bs/ab.data --no-children --sort dso -n --stdio 2>/dev/null | awk '/\.so *$/ && ($3 ~ /wave|shade|intersect|shadow|generate|accumulate/) {printf "%s:%s ", $3, $2}')
    wall=$(python3 -c "import json;d=json.load(open('/tmp/bs/ab.json'));print(round(d.get('wall_seconds',0),3), ' '.join('%s=%.0f'%(s['stage'],1000*s['device_seconds']) for s in d.get('stages',[]) if s['device_seconds']>0))" 2>/dev/null)
    echo "r$r $label load=$(cut -d' ' -f1 /proc/loadavg) total=$tot $so wall=$wall"
  done
done
