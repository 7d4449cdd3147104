#!/usr/bin/env bash
# The Oclgrind step's detector must fail on each deliberate fault of the probe
# (tests/oclgrind/probe.cpp), name it, and pass the clean mode.
#
#   detector_test.sh DETECTOR PROBE [--require]
#
# Exit 77 (ctest: skipped) when oclgrind is not installed, unless --require
# (the CI step's self-test) makes that a failure.
set -uo pipefail
detector=$1 probe=$2 require=${3:-}

if ! command -v oclgrind >/dev/null; then
  if [ "$require" = --require ]; then
    echo "FAIL: oclgrind is not installed (apt-get install oclgrind, or tools/install-deps.sh)"
    exit 1
  fi
  echo "SKIPPED: oclgrind is not installed (apt-get install oclgrind, or tools/install-deps.sh)"
  exit 77
fi

failures=0
# expect MODE STATUS [TEXT]: the detector exits with STATUS and its output contains TEXT.
expect() {
  local mode=$1 want=$2 text=${3:-} output status
  output=$("$detector" "$probe" "$mode" 2>&1)
  status=$?
  if [ "$status" != "$want" ]; then
    echo "FAIL: probe $mode: detector exit status $status, expected $want"
    failures=$((failures + 1))
  elif [ -n "$text" ] && ! grep -qF -- "$text" <<<"$output"; then
    echo "FAIL: probe $mode: the report does not say '$text'"
    failures=$((failures + 1))
  elif ! grep -qF "ran on Oclgrind" <<<"$output"; then
    echo "FAIL: probe $mode: the probe did not run to its end on the Oclgrind device"
    failures=$((failures + 1))
  else
    echo "ok: probe $mode: exit status $status${text:+, reported '$text'}"
    return
  fi
  echo "---- output of: $detector $probe $mode"
  echo "$output"
  echo "----"
}

expect clean 0
expect global-oob 3 "Invalid write of size 4 at global memory address"
expect local-oob 3 "Invalid write of size 4 at local memory address"
expect race 3 "Write-write data race at global memory address"
expect api 3 "CL_INVALID_WORK_GROUP_SIZE"

if ((failures)); then
  echo "$failures of 5 probe modes went wrong"
  exit 1
fi
echo "5 passed, 0 failed"
