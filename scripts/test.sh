#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build with tests, run the whole suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh ON
ctest --test-dir build --output-on-failure -j2
