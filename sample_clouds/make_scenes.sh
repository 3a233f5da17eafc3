#!/usr/bin/env bash
# Regenerates the small synthetic scenes shipped here (needs the built pc_synth). The test
# tests/cli/pc_synth_eval_test.cpp checks that the shipped files are exactly what pc_synth makes.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
synth="${PC_SYNTH:-$here/../build/bin/pc_synth}"
# name | pc_synth arguments (also read by the test: keep one scene per line)
while IFS='|' read -r name args; do
  [ -z "$name" ] && continue
  # shellcheck disable=SC2086
  "$synth" $args -o "$here/$name.pcd" --truth "$here/$name.json"
done <"$here/scenes.txt"
