#!/usr/bin/env bash
# Quick start, command 2: install what is missing, build with tests, run the whole suite.
# Under CI (CI=true) warnings are errors, the readers are fuzzed for a fixed number of inputs
# (scripts/fuzz.sh) and the suite runs a second time under ASan + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/check_format.sh
bash scripts/build.sh ON
ctest --test-dir build --output-on-failure -j2
if [ "${CI:-}" = "true" ] || [ "${PC_FUZZ_RUN:-}" = "1" ]; then
    bash scripts/fuzz.sh 200000
fi
if [ "${CI:-}" = "true" ] || [ "${PC_SANITIZE_RUN:-}" = "1" ]; then
    # -O1: Eigen at -O0 made the splitter's tests 30x slower than the sanitizers alone do.
    cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
        -DPC_SANITIZE=ON -DPC_BUILD_TESTS=ON >/dev/null
    ninja -C build-asan
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
        ctest --test-dir build-asan --output-on-failure -j2
fi
