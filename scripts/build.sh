#!/usr/bin/env bash
# Configures and builds into build/ (incremental; ccache when present).
# Usage: build.sh [ON|OFF]  -- build the tests or not; without an argument an existing build/
# keeps its setting (a fresh one builds tools only), so demo.sh never undoes test.sh's build.
set -euo pipefail
cd "$(dirname "$0")/.."
args=(-S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release)
if [ $# -ge 1 ]; then
    args+=(-DPC_BUILD_TESTS="$1")
elif [ ! -f build/CMakeCache.txt ]; then
    args+=(-DPC_BUILD_TESTS=OFF)
fi
if [ "${CI:-}" = "true" ]; then args+=(-DPC_WARNINGS_AS_ERRORS=ON); fi
cmake "${args[@]}" >/dev/null
ninja -C build
