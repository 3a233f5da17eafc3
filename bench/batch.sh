#!/usr/bin/env bash
# Many trees on all cores (issue 21): N clouds of 1M points (pc_synth apple canopies as in
# bench/run.sh, seeds 1..N) counted by pc_fruitcount through GNU parallel, one job a core and one
# thread a job, against one job at a time; and the same batch in one process (pc_fruitcount
# a.pcd b.pcd ..., OpenMP on both cores). Prints a markdown table; the ratio is the target
# (>= 1.8x the one-core throughput on 2 cores).
#   bash bench/batch.sh [N]          (default 20; clouds are made once in build-bench/batch/)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-20}
bash scripts/setup.sh
bash scripts/build.sh >/dev/null
b=$PWD/build/bin
data=build-bench/batch
mkdir -p "$data"
for s in $(seq 1 "$n"); do
  # 1M points: 1266 fruit in a canopy scaled as bench/run.sh's canopy_cloud does.
  [ -f "$data/tree_$s.pcd" ] || "$b/pc_synth" --species apple --voxel 0.0066 --fruit-count 1266 \
    --canopy 1.977,1.977,1.647 --seed "$s" -o "$data/tree_$s.pcd"
done
trees=()
for s in $(seq 1 "$n"); do trees+=("$data/tree_$s.pcd"); done
points=$("$b/pc_info" --text "${trees[0]}" | awk '$1 == "points" { print $2 }')

# seconds COMMAND...: wall time of one run
seconds() {
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >/dev/null
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }'
}
export OMP_NUM_THREADS=1
one=$(seconds parallel -j1 --halt now,fail=1 "$b/pc_fruitcount" --jsonl -q {} ::: "${trees[@]}")
two=$(seconds parallel -j2 --halt now,fail=1 "$b/pc_fruitcount" --jsonl -q {} ::: "${trees[@]}")
unset OMP_NUM_THREADS
batch=$(seconds "$b/pc_fruitcount" --jsonl -q "${trees[@]}")
# The rows must not depend on how the batch ran.
diff <(parallel -j2 --keep-order "$b/pc_fruitcount" --plain -q {} ::: "${trees[@]}") \
     <("$b/pc_fruitcount" --plain -q "${trees[@]}") >/dev/null || { echo "counts differ" >&2; exit 1; }

echo "| run ($n clouds of $points points, $(nproc) cores) | wall | clouds per second | vs one core |"
echo "| --- | ---: | ---: | ---: |"
for row in "parallel -j1, 1 thread a job:$one" "parallel -j2, 1 thread a job:$two" \
           "one process, all inputs, OpenMP:$batch"; do
  awk -v name="${row%%:*}" -v t="${row##*:}" -v base="$one" -v k="$n" \
    'BEGIN { printf "| %s | %.1f s | %.2f | %.2fx |\n", name, t, k / t, base / t }'
done
