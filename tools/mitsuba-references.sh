#!/usr/bin/env bash
# Renders the Mitsuba 3 references of the agreement tests
# (tests/render/test_mitsuba_agreement.cpp) and commits nothing itself:
#
#   bash tools/mitsuba-references.sh [BUILD_DIR] [NAME ...]
#
# For each scene tests/data/mitsuba/NAME.json or NAME.xml (all of them when
# no NAME is given): `wavepath export-mitsuba` writes a JSON scene as
# Mitsuba 3 XML (an XML scene, written by hand for the Mitsuba reader, is
# rendered as it is), and tools/mitsuba_render.py renders it with the scalar_rgb variant from
# SEEDS independent seeds of SPP samples each, writing the mean image
# NAME.exr and each pixel's standard error of that mean NAME-error.exr beside
# the scene. The tests read those two files and never need Mitsuba.
# Needs `pip install mitsuba` (the references in the repository were made
# with Mitsuba 3.9.1; tests/data/mitsuba/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
seeds=${SEEDS:-16}
spp=${SPP:-2048}
dir=tests/data/mitsuba
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for scene in "$dir"/*.json "$dir"/*.xml; do names+=("$(basename "${scene%.*}")"); done
fi
scratch=$(mktemp -d "${TMPDIR:-/tmp}/mitsuba-references.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
for name in "${names[@]}"; do
  xml="$dir/$name.xml"
  if [ -f "$dir/$name.json" ]; then
    xml="$scratch/$name.xml"
    "$build/wavepath" export-mitsuba "$dir/$name.json" "$xml"
  fi
  start=$SECONDS
  python3 tools/mitsuba_render.py "$xml" --seeds "$seeds" --spp "$spp" --blocks 1 \
    --out "$scratch/$name.exr" --error-out "$scratch/$name-error.exr" >"$scratch/$name.txt"
  mv "$scratch/$name.exr" "$scratch/$name-error.exr" "$dir/"
  echo "mitsuba-references: $name: $seeds seeds x $spp spp in $((SECONDS - start)) s: $(sed -n 1p "$scratch/$name.txt")"
done
