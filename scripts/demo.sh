#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build, and run the main job on a shipped sample.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
set -x
# The counting chain through pipes (paper-dense preset) on the shipped sample: 12 fruit.
b=build/bin
$b/pc_convert -i sample_clouds/fruit_small.ply | $b/pc_colorfilter --preset paper-dense \
    | $b/pc_knn_outlier --preset paper-dense | $b/pc_dbscan --preset paper-dense \
    | $b/pc_recursive_split --preset paper-dense | $b/pc_count --plain
# The same chain in one process, with the report against the ground truth.
$b/pc_fruitcount -i sample_clouds/fruit_small.ply --preset paper-dense --gt 12 -o build/fruit_small_report.json
grep -E '"(count|gt|error|recovery)"' build/fruit_small_report.json
