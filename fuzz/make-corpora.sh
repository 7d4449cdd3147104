#!/usr/bin/env bash
# Builds the fuzzers' seed corpora from the repository's own files and the
# generated ones (wavepath_fuzz_seeds), one folder per target:
#
#   bash fuzz/make-corpora.sh BUILD_DIR OUT_DIR
#
# OUT_DIR/seeds/<target>/ gets the seeds, OUT_DIR/scene-cwd/ the test meshes
# that scene seeds name (scene_fuzzer runs there). The saved regression inputs
# (tests/data/fuzz/<target>/) are seeds too, so a fixed bug stays covered.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: make-corpora.sh BUILD_DIR OUT_DIR}
out=${2:?usage: make-corpora.sh BUILD_DIR OUT_DIR}
seeds=$out/seeds
rm -rf "$seeds" "$out/scene-cwd"
mkdir -p "$seeds"/{scene,xml,obj,ply,serialized,exr,pfm} "$out/scene-cwd"

"$build/fuzz/wavepath_fuzz_seeds" "$out/generated"
cp "$out"/generated/exr/* "$seeds/exr/"
cp "$out"/generated/pfm/* "$seeds/pfm/"
cp "$out"/generated/ply/* "$seeds/ply/"

cp scenes/*.json scenes/stress/*.json tests/oclgrind/scenes/*.json fuzz/seeds/scene/*.json \
   "$seeds/scene/"
cp tests/data/mitsuba/*.xml "$seeds/xml/"
cp tests/data/meshes/*.obj fuzz/seeds/obj/*.obj "$seeds/obj/"
cp tests/data/meshes/*.ply "$seeds/ply/"
cp tests/data/meshes/*.serialized "$seeds/serialized/"
cp tests/data/hexroom-32-ref.exr "$seeds/exr/"
cp tests/data/meshes/* "$out/scene-cwd/"

for target in scene xml obj ply serialized exr pfm; do
  if compgen -G "tests/data/fuzz/$target/*" >/dev/null; then
    cp tests/data/fuzz/"$target"/* "$seeds/$target/"
  fi
  echo "make-corpora: $target: $(ls "$seeds/$target" | wc -l) seeds," \
       "$(cat "$seeds/$target"/* | wc -c) bytes"
done
