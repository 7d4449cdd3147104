#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each (default 600), at most JOBS at a
# time (default 2), niced, and prints libFuzzer's final statistics for each:
#
#   bash fuzz/run-fuzzers.sh BUILD_DIR OUT_DIR [SECONDS] [JOBS] [TARGET...]
#
# BUILD_DIR is a -DWAVEPATH_FUZZ=ON build (docs/fuzzing.md). Under OUT_DIR:
# seeds/ and scene-cwd/ (from fuzz/make-corpora.sh, run first), corpus/<target>/
# (the inputs each run found, kept for the next run), artifacts/<target>/
# (crash-*, timeout-*, oom-*: the findings) and logs/<target>.log.
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:?usage: run-fuzzers.sh BUILD_DIR OUT_DIR [SECONDS] [JOBS] [TARGET...]}")
out=$(realpath -m "${2:?usage: run-fuzzers.sh BUILD_DIR OUT_DIR [SECONDS] [JOBS] [TARGET...]}")
seconds=${3:-600}
jobs=${4:-2}
shift $(($# < 4 ? $# : 4))
targets=("$@")
((${#targets[@]})) || targets=(scene xml obj ply serialized exr pfm)
dicts=$(realpath fuzz/dictionaries)

bash fuzz/make-corpora.sh "$build" "$out"

# Longest input per target: a few times the largest seed, so that mutations
# can grow a file, without letting the fuzzer spend its time on huge inputs.
declare -A max_len=([scene]=16384 [xml]=16384 [obj]=8192 [ply]=8192 [serialized]=8192 [exr]=16384 [pfm]=4096)

run_one() {
  local target=$1
  mkdir -p "$out/corpus/$target" "$out/artifacts/$target" "$out/logs"
  local dict=()
  [ -f "$dicts/$target.dict" ] && dict=(-dict="$dicts/$target.dict")
  # scene_fuzzer and xml_fuzzer name mesh files relative to their working
  # directory (xml_fuzzer writes its input there as fuzz.xml).
  local cwd=$out
  [ "$target" = scene ] && cwd=$out/scene-cwd
  [ "$target" = xml ] && cwd=$out/xml-cwd && mkdir -p "$cwd" && cp "$out"/scene-cwd/* "$cwd/"
  (cd "$cwd" && nice -n 10 "$build/fuzz/${target}_fuzzer" \
     -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len="${max_len[$target]}" \
     -print_final_stats=1 -artifact_prefix="$out/artifacts/$target/" "${dict[@]}" \
     "$out/corpus/$target" "$out/seeds/$target") >"$out/logs/$target.log" 2>&1 || true
}

running=0
for target in "${targets[@]}"; do
  run_one "$target" &
  running=$((running + 1))
  if ((running >= jobs)); then
    wait -n
    running=$((running - 1))
  fi
done
wait

status=0
for target in "${targets[@]}"; do
  log=$out/logs/$target.log
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  findings=$(ls "$out/artifacts/$target" | wc -l)
  echo "$target: ${execs:-?} executions, ${rate:-?}/s, findings: $findings; last: $last"
  ((findings == 0)) || status=1
done
exit $status
