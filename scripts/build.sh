#!/usr/bin/env bash
# Configures and builds into build/ (incremental; ccache when present). Usage: build.sh [ON|OFF tests]
set -euo pipefail
cd "$(dirname "$0")/.."
tests=${1:-OFF}
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPC_BUILD_TESTS="$tests" \
    -DPC_WARNINGS_AS_ERRORS="$werror" >/dev/null
ninja -C build
