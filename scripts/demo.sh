#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build, and run the main job on a shipped sample.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh OFF
set -x
build/bin/pc_convert -i sample_clouds/fruit_small.ply | build/bin/pc_info --text
