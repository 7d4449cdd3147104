#!/usr/bin/env bash
# The device run of wavepath's kit (docs/gpu.md): run from the kit's folder,
# it writes everything to $OUT (a folder; default ./out). Needs nothing but
# the kit, glibc and an OpenCL driver. Steps, in order of what matters most,
# each under its own timeout and all under one deadline (WP_KIT_DEADLINE
# seconds, default 420), so that a slow driver costs steps, not the run:
#   1. `wavepath devices --check` and where the driver's OpenCL library was
#      found;
#   2. the hexroom, specialised and general kernels, compared with PoCL's
#      images of the same seed (`wavepath compare`: bit-identical values,
#      and a 5-sigma z-test on the variances), with --profile per stage;
#   3. the hexroom at 800x800, 64 spp (issue #33's measure), cold, then
#      warm and alternating with
#   4. Mitsuba 3's cuda_ad_rgb on the same scene, if pack-mitsuba.sh added
#      it; `bench` (stages against the copy bandwidth); a reference image
#      from each, and both renderers' errors against wavepath's;
#   5. every stress scene, compared with PoCL's images;
#   6. a sweep of launch plan, work-group size, regeneration and pool size
#      on the hexroom, twice;
#   7. the kernel-level tests (tests/cl, tests/kernels) on the device.
# Environment:
#   WP_KIT_DEVICE  the device selector (default "NVIDIA": part of its name)
#   WP_KIT_ICD     a vendors folder for OCL_ICD_VENDORS (default: one made
#                  here naming the NVIDIA driver's libnvidia-opencl.so.1)
#   WP_KIT_QUICK=1 smaller renders and sweep, for practice on a CPU device
#   WP_KIT_PYTHON, WP_KIT_MITSUBA_VARIANT  python3 and cuda_ad_rgb by default
set -uo pipefail
kit=$(cd "$(dirname "$0")" && pwd)
out=${OUT:-$kit/out}
mkdir -p "$out"
log=$out/run.log
: >"$log"
start=$(date +%s)
deadline=$((start + ${WP_KIT_DEADLINE:-420}))
device=${WP_KIT_DEVICE:-NVIDIA}
work=$(mktemp -d)
images=$work/images
mkdir -p "$images"

say() { echo "$*" | tee -a "$log"; }
elapsed() { echo $(($(date +%s) - start)); }
# run SECONDS FILE COMMAND...: appends the command and its output to FILE and
# the log; stops it at SECONDS or at the deadline, whichever comes first.
run() {
  local limit=$1 file=$2
  shift 2
  local left=$((deadline - $(date +%s)))
  if ((left < 5)); then
    say "skipped (deadline): $*"
    echo "skipped (deadline): $*" >>"$file"
    return 124
  fi
  ((limit > left)) && limit=$left
  echo "\$ $*" >>"$file"
  local t0 status t
  t0=$(date +%s%N)
  timeout --kill-after=5 "$limit" "$@" >>"$file" 2>&1
  status=$?
  t=$((($(date +%s%N) - t0) / 1000000))
  echo "(exit $status, $t ms)" >>"$file"
  say "[$(elapsed) s] exit $status in $t ms: $*"
  return $status
}

# The libraries the kit carries first, then the driver's folder (its OpenCL
# library loads others beside it: libnvidia-ptxjitcompiler, ...).
export LD_LIBRARY_PATH=$kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
if [[ -n "${WP_KIT_ICD:-}" ]]; then
  export OCL_ICD_VENDORS=$WP_KIT_ICD
  say "ICD: $OCL_ICD_VENDORS (WP_KIT_ICD)"
else
  found=""
  # Where NVIDIA's container runtimes and Debian/Ubuntu packages put it.
  for dir in /usr/local/nvidia/lib64 /usr/local/nvidia/lib /usr/lib/x86_64-linux-gnu \
    /usr/lib/x86_64-linux-gnu/nvidia/current /usr/lib64 /usr/lib /usr/local/cuda/compat \
    /usr/local/cuda/lib64; do
    [[ -e $dir/libnvidia-opencl.so.1 ]] && { found=$dir/libnvidia-opencl.so.1; break; }
  done
  [[ -z $found ]] && found=$(ldconfig -p 2>/dev/null | awk '/libnvidia-opencl.so.1 /{print $NF; exit}')
  if [[ -z $found ]]; then
    found=$(find / -xdev -name 'libnvidia-opencl.so.1' 2>/dev/null | head -1)
  fi
  say "NVIDIA OpenCL library: ${found:-not found}"
  for f in /etc/OpenCL/vendors/*.icd; do [[ -e $f ]] && say "system ICD $f: $(cat "$f")"; done
  mkdir -p "$work/vendors"
  echo "${found:-libnvidia-opencl.so.1}" >"$work/vendors/nvidia.icd"
  [[ -n $found ]] && export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$(dirname "$found")
  export OCL_ICD_VENDORS=$work/vendors
fi
export WAVEPATH_CACHE_DIR=$work/cache # a fresh program cache: the cold builds are measured
wp=$kit/bin/wavepath
say "kit: $kit; device selector: $device; $(uname -m); $(ldd --version 2>&1 | head -1)"
command -v nvidia-smi >/dev/null &&
  nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv >>"$log" 2>&1

# 1. The devices, and each one's self-check (specialised against general
# kernels, docs/gpu.md); a failed check warns and renders fall back.
run 120 "$out/devices.txt" "$wp" devices --check || say "FAIL devices --check"
cat "$out/devices.txt" >>"$log"

# compare NAME SCENE ARGS...: renders SCENE as the reference ref/NAME.exr was
# (ref/NAME.args holds the arguments) and compares.
compare() {
  local name=$1 scene=$2
  local args
  args=$(cat "$kit/ref/$name.args")
  # shellcheck disable=SC2086 # the arguments are words
  run 120 "$out/renders.txt" "$wp" render "$kit/$scene" $args --device "$device" --profile \
    -o "$images/$name.exr" --variance "$images/$name.var.exr"
  local rendered=$?
  if [[ -e $kit/ref/$name.exr ]]; then
    ((rendered == 0)) || { say "FAIL $name: did not render on the device"; return 1; }
    run 60 "$out/compare.txt" "$wp" compare "$images/$name.exr" "$kit/ref/$name.exr" \
      --variance "$images/$name.var.exr" "$kit/ref/$name.var.exr" --sigma 5 ||
      say "FAIL $name: differs from PoCL's image beyond noise"
  else
    # PoCL refused it (a degenerate scene): the device must refuse it too.
    ((rendered != 0)) && say "ok $name: refused, as on PoCL" ||
      say "FAIL $name: rendered, though PoCL refused it"
  fi
}

# 2. The hexroom, specialised and general.
compare hexroom scenes/hexroom.json
compare hexroom-general scenes/hexroom.json

# 3 and 4. Issue #33's measure: the hexroom at 800x800 and 64 spp, wavepath
# (its launch plan chosen by device, --profile on the first warm render)
# and Mitsuba 3's cuda_ad_rgb (pack-mitsuba.sh) alternating on the same GPU;
# `bench` (the stages against the copy bandwidth); a reference of many
# samples from each for the error and the agreement of the two renderers.
if [[ -n "${WP_KIT_QUICK:-}" ]]; then
  hsize=128 hspp=4 href=16 mspp=1 mref=2 mrepeats=1
else
  hsize=800 hspp=64 href=1024 mspp=64 mref=1024 mrepeats=3
fi
hexroom() { # OUTPUT SPP SEED [ARGS...]
  local name=$1 spp=$2 seed=$3
  shift 3
  run 120 "$out/headline.txt" "$wp" render "$kit/scenes/hexroom.json" --width $hsize \
    --height $hsize --spp "$spp" --seed "$seed" --device "$device" --quiet \
    -o "$images/$name.exr" "$@"
}
mitsuba_ready=""
if [[ -e $kit/mitsuba.tar.xz ]]; then
  mkdir -p "$work/site"
  tar -C "$work/site" -xJf "$kit/mitsuba.tar.xz" && mitsuba_ready=1
  # Dr.Jit opens the driver's libcuda and OptiX libraries by name; give it
  # the paths beside the OpenCL library.
  driver_dir=$(dirname "${found:-/usr/local/nvidia/lib64/x}")
  for lib in libcuda.so.1 libnvoptix.so.1; do
    say "$lib: $(ls "$driver_dir/$lib" 2>/dev/null || ldconfig -p 2>/dev/null |
      awk -v l="$lib" '$1 == l {print $NF; exit}')"
  done
  [[ -e $driver_dir/libcuda.so.1 ]] && export DRJIT_LIBCUDA_PATH=$driver_dir/libcuda.so.1
  [[ -e $driver_dir/libnvoptix.so.1 ]] && export DRJIT_LIBOPTIX_PATH=$driver_dir/libnvoptix.so.1
else
  say "no mitsuba.tar.xz in the kit: Mitsuba's side is skipped"
fi
mitsuba() { # SPP REPEATS OUTPUT [ARGS...]
  [[ -n $mitsuba_ready ]] || return 0
  local spp=$1 repeats=$2 name=$3
  shift 3
  PYTHONPATH=$work/site${PYTHONPATH:+:$PYTHONPATH} run 120 "$out/mitsuba.txt" \
    "${WP_KIT_PYTHON:-python3}" "$kit/mitsuba/mitsuba_gpu.py" "$kit/mitsuba/hexroom.xml" \
    --spp "$spp" --repeats "$repeats" --out "$images/$name.exr" \
    --variant "${WP_KIT_MITSUBA_VARIANT:-cuda_ad_rgb}" "$@" || say "FAIL mitsuba: see mitsuba.txt"
}
hexroom wp-hexroom $hspp 1 # the cold build
for round in 1 2 3; do
  if ((round < 3)); then
    mitsuba $mspp $mrepeats mi-hexroom
  else
    mitsuba $mspp $mrepeats mi-hexroom --reference-spp $mref \
      --reference-out "$images/mi-hexroom-ref.exr"
  fi
  if ((round == 1)); then
    hexroom wp-hexroom $hspp $((round + 1)) --profile
  else
    hexroom wp-hexroom $hspp $((round + 1))
  fi
done
hexroom wp-hexroom-ref $href 99
[[ -e $out/mitsuba.txt ]] && cat "$out/mitsuba.txt" >>"$log"
run 120 "$out/bench.txt" "$wp" bench "$kit/scenes/hexroom.json" --size $hsize --spp $hspp \
  --device "$device"
for image in wp-hexroom mi-hexroom mi-hexroom-ref; do
  [[ -e $images/$image.exr ]] && run 30 "$out/headline.txt" "$wp" compare \
    "$images/$image.exr" "$images/wp-hexroom-ref.exr"
done
[[ -e $images/mi-hexroom-ref.exr ]] && run 30 "$out/headline.txt" "$wp" compare \
  "$images/wp-hexroom.exr" "$images/mi-hexroom-ref.exr"

# 5. The stress scenes.
for ref in "$kit"/ref/stress-*.args; do
  name=$(basename "$ref" .args)
  compare "$name" "scenes/stress/${name#stress-}.json"
done

# 6. Launch plans, work-group sizes, regeneration and pool on the hexroom:
# samples/s of each, everything else as the device's plan has it.
if [[ -n "${WP_KIT_QUICK:-}" ]]; then
  size=128 spp=4 groups="64 128"
else
  size=1024 spp=64 groups="32 64 128 256"
fi
sweep() { # ARGS...: one render of the sweep
  run 60 "$out/sweep.txt" "$wp" render "$kit/scenes/hexroom.json" --width $size --height $size \
    --spp $spp --device "$device" -o "$work/sweep.exr" --quiet "$@"
}
for repeat in 1 2; do
  for plan in stages bounce wave; do
    sweep --launch-plan $plan
  done
  for group in $groups; do
    echo "# WAVEPATH_WORK_GROUP_SIZE=$group" >>"$out/sweep.txt"
    WAVEPATH_WORK_GROUP_SIZE=$group sweep
  done
  sweep --no-regeneration
  sweep --pool $((size * size / 4))
done
awk '/^# /{env=$0} /^\$ /{cmd=$0} /^rendered/{print env; print cmd; print; env=""}' \
  "$out/sweep.txt" >>"$log"

# 7. The kernel-level tests on the device: last, as the longest step.
for t in "$kit"/bin/wavepath_*_tests; do
  WAVEPATH_TEST_DEVICE=$device run 150 "$out/tests.txt" "$t" --reporter compact
done

tar -C "$work" -czf "$out/images.tar.gz" images
say "done in $(elapsed) s; FAILs: $(grep -c '^FAIL' "$log")"
rm -rf "$work"
grep -q '^FAIL' "$log" && exit 1
exit 0
