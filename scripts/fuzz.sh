#!/usr/bin/env bash
# Fuzzes the readers: builds fuzz/'s libFuzzer targets with clang (ASan + UBSan) into build-fuzz/,
# writes the seed corpora (the tests' malformed and edge-case inputs, the sample clouds and JSON
# files) and runs each target for a fixed number of inputs from a fixed seed, so that a run is
# repeatable. Fails, keeping the crashing input in build-fuzz/findings/, when a target finds one.
#   bash scripts/fuzz.sh [RUNS]        (default 200000 inputs a target, as scripts/test.sh under CI)
#   bash scripts/fuzz.sh --time S      (explore for S seconds a target, random seed)
# A finding is fixed with a regression test: add the input to tests/support/corpus.h.
set -euo pipefail
cd "$(dirname "$0")/.."
limit=(-runs="${1:-200000}" -seed=1)
if [ "${1:-}" = "--time" ]; then limit=(-max_total_time="${2:?seconds}"); fi

source scripts/lib_packages.sh
install_missing fuzz clang-14 libclang-rt-14-dev libomp-14-dev

cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
    -DPC_FUZZ=ON -DPC_BUILD_TESTS=OFF >/dev/null
ninja -C build-fuzz fuzz_cloud fuzz_json fuzz_seeds
rm -rf build-fuzz/seeds build-fuzz/corpus
build-fuzz/bin/fuzz_seeds build-fuzz/seeds
mkdir -p build-fuzz/findings
status=0
for target in cloud json; do
    mkdir -p "build-fuzz/corpus/$target"  # what a run adds; the seeds stay as written
    echo "fuzz: fuzz_$target ${limit[*]}" >&2
    if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
        "build-fuzz/bin/fuzz_$target" "${limit[@]}" -max_len=16384 -rss_limit_mb=2048 -timeout=10 \
        -artifact_prefix="build-fuzz/findings/${target}_" -print_final_stats=1 \
        "build-fuzz/corpus/$target" "build-fuzz/seeds/$target" 2>"build-fuzz/fuzz_$target.log"; then
        tail -n 40 "build-fuzz/fuzz_$target.log" >&2
        echo "fuzz: fuzz_$target found an input that fails; it is in build-fuzz/findings/" >&2
        status=1
    else
        grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-fuzz/fuzz_$target.log" >&2 || true
    fi
done
exit $status
