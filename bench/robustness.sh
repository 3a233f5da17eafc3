#!/usr/bin/env bash
# The condition matrix of docs/robustness.md: the scenes of bench/robustness/scenes.txt counted by
# each method, scored against their truth. One command:
#     bash bench/robustness.sh [--split tune|held-out|held-out-N|all] [--methods "default word ..."]
#                              [--write-docs] [--rows FILE (only summarise rows written before)]
#                              [--jobs N (scenes counted N at a time; their seconds then share
#                              the cores)] [--ids FILE (only the scenes whose ids FILE lists)]
#                              [--name NAME (the run's name: rows in build/robustness/rows-NAME.csv,
#                              each scene's report, cloud and stderr in build/robustness/NAME/;
#                              default the split's name, or "ids")]
# Methods: default (pc_fruitcount -i SCENE), word (the default plus the scene's --fruit-color word;
# needs a pc_fruitcount that has the option), nocolor (--no-color: the geometry alone), radius
# (the default plus --fruit-radius: the median radius of the fruit present, as a user who knows
# their fruit would give it), and any
# preset name (--preset NAME); x:OPT,OPT,... tries options (x:--no-knn,--eps,3xs).
# Scores: F1 of one-to-one matching at IoU > 0.5 and count error, both against the fruit present in
# the cloud (a fruit the export lost cannot be counted). Rows: build/robustness/rows-SPLIT.csv.
# A/B runs of two builds on the same scenes: copy one build's bin/ with `cp -a` (a newer pc_synth
# would make the scenes again) and run each with its own --name, e.g.
#     PC_BIN=/tmp/old-bin bash bench/robustness.sh --ids ids.txt --name old --methods default
# The scenes themselves are made once, in build/robustness/scenes/ (PC_SCENES=DIR: elsewhere).
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib_scenes.sh
split=tune
methods="default word dense paper-dense paper-sparse"
write_docs=0
from_rows=
jobs=1
ids=
name=
while [ $# -gt 0 ]; do
  case $1 in
    --jobs) jobs=$2; shift 2 ;;
    --split) split=$2; shift 2 ;;
    --methods) methods=$2; shift 2 ;;
    --write-docs) write_docs=1; shift ;;
    --rows) from_rows=$2; shift 2 ;;
    --ids) ids=$2; shift 2 ;;
    --name) name=$2; shift 2 ;;
    *) echo "robustness.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
b=${PC_BIN:-build/bin}  # another build's binaries: PC_BIN=DIR (rebuild build/ while a run goes on)
if [ -n "$from_rows" ]; then
  rows=$from_rows
else
[ -x $b/pc_fruitcount ] || { bash scripts/setup.sh >/dev/null && bash scripts/build.sh >/dev/null; }
if [ -n "$ids" ]; then
  [ -r "$ids" ] || { echo "robustness.sh: cannot read the ids file '$ids'" >&2; exit 2; }
  name=${name:-ids}
fi
name=${name:-$split}
dir=build/robustness
scenes=${PC_SCENES:-$dir/scenes}
runs=$dir/$name
mkdir -p "$scenes" "$runs"
rows=$dir/rows-$name.csv
echo "id,split,family,mode,r_over_s,noise,colour,units,method,present,count,f1,count_error,seconds,warnings" >"$rows"
# the colour words pc_fruitcount knows (scenes of other colours have no `word` row)
words=$($b/pc_fruitcount --help | tr -s ' \n' ' ' | grep -o -- '--fruit-color arg[^:]*: [a-z, ]*' || true)

# held-out parts drawn and not yet scored: "all" leaves them out; score each once by name, when a
# changed method is final, then take it off this list
unscored="held-out-53"
# score_scene LINE: one scenes.txt line counted by each method; its rows in $runs/ID.rows
score_scene() {
  local id part family mode rs noise colour units args stem present method extra start end score out
  local count f1 warnings
  IFS='|' read -r id part family mode rs noise colour units args <<<"$1"
  stem=$scenes/$id
  rm -f "$runs/$id.rows"
  if [ ! -f "$stem.json" ] || [ $b/pc_synth -nt "$stem.json" ]; then
    # shellcheck disable=SC2086
    $b/pc_synth $args -o "$stem.pcd" --truth "$stem.json"
  fi
  present=$(grep -m1 '"fruit_present"' "$stem.json" | tr -dc '0-9')
  for method in $methods; do
    case $method in
      default) extra=() ;;
      word) grep -qw -- "$colour" <<<"$words" || continue; extra=(--fruit-color "$colour") ;;
      nocolor) extra=(--no-color) ;;
      radius) extra=(--fruit-radius "$(python3 -c 'import json, statistics, sys
t = json.load(open(sys.argv[1]))
print(statistics.median(f["radius"] for f in t["fruits"] if f["points"] > 0))' "$stem.json")") ;;
      cores) extra=(--rule cores) ;;
      x:*) IFS=, read -r -a extra <<<"${method#x:}" ;;
      *) extra=(--preset "$method") ;;
    esac
    # the method's files: ID.out.pcd, ID.report.json, ID.err for the default, ID.METHOD.* for
    # the others (so that the default's stay to be read after a run of several methods)
    out=$runs/$id
    [ "$method" = default ] || out=$runs/$id.${method//[^A-Za-z0-9_-]/_}
    start=$(date +%s.%N)
    if $b/pc_fruitcount -i "$stem.pcd" "${extra[@]}" --cloud "$out.out.pcd" -o "$out.report.json" 2>"$out.err"; then
      end=$(date +%s.%N)
      score=$($b/pc_eval -i "$out.out.pcd" --truth "$stem.json" --gt "$present" --csv | tail -n 1)
      count=$(echo "$score" | cut -d, -f3); f1=$(echo "$score" | cut -d, -f11)
    else
      end=$(date +%s.%N); count=-1; f1=0
    fi
    warnings=$(grep -c 'warning' "$out.err" || true)
    awk -v a="$start" -v b="$end" -v c="$count" -v p="$present" -v f1="$f1" -v w="$warnings" \
        -v row="$id,$part,$family,$mode,$rs,$noise,$colour,$units,$method" \
        'BEGIN { e = p > 0 ? (c - p) / p : 0; printf "%s,%s,%s,%.4f,%.4f,%.2f,%s\n", row, p, c, f1, e, b - a, w }' >>"$runs/$id.rows"
  done
}
export -f score_scene
export b scenes runs methods words
listed=" $(tr -s ' \t\n' ' ' <"${ids:-/dev/null}") "
selected=()
while IFS= read -r line; do
  part=$(cut -d'|' -f2 <<<"$line")
  if [ -n "$ids" ]; then  # the listed scenes of the parts scored so far
    [[ "$listed" == *" ${line%%|*} "* ]] || continue
    if [[ " $unscored " == *" $part "* ]]; then
      echo "robustness.sh: scene ${line%%|*} left out: $part is scored only by name" >&2
      continue
    fi
  else
    case $split in  # "all" is every part scored so far: the unscored held-out parts only by name
      all) [[ " $unscored " == *" $part "* ]] && continue ;;
      *) [ "$part" = "$split" ] || continue ;;
    esac
  fi
  selected+=("$line")
done <bench/robustness/scenes.txt
[ ${#selected[@]} -gt 0 ] || { echo "robustness.sh: no scene selected" >&2; exit 2; }
printf '%s\n' "${selected[@]}" | xargs -d '\n' -P "$jobs" -I{} bash -c 'score_scene "$1"' _ {}
for line in "${selected[@]}"; do
  cat "$runs/${line%%|*}.rows" >>"$rows"
done
fi

# Summary: each method on the tune and held-out parts, then the first method per condition.
table=$(awk -F, -v first="${methods%% *}" '
  NR == 1 { next }
  function add(key) { n[key]++; f[key] += $12; e = $13 < 0 ? -$13 : $13; ae[key] += e
                      if (e > 0.2) off[key]++; if (e > 0.2 && $15 == 0) silent[key]++
                      if ($11 <= 0) zero[key]++; t[key] += $14
                      if (!(key in worst) || $12 < worst[key]) worst[key] = $12 }
  function rank(part) { return part == "tune" ? 0 : part == "held-out" ? 1 : 1 + substr(part, 10) }
  function sorted(prefix, out,   k, m, i, j, x) {
    m = 0; for (k in n) if (index(k, prefix) == 1) out[++m] = k
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (out[j] < out[i]) { x = out[i]; out[i] = out[j]; out[j] = x }
    return m }
  { add("M|" $9 "|" $2); add("M|" $9 "|all")
    if ($9 == first) { add("C|family " $3 "|" $2); add("C|mode " $4 "|" $2); add("C|r/s " sprintf("%02d", $5) "|" $2)
                       add("C|noise " $6 "|" $2); add("C|colour " $7 "|" $2); add("C|units " $8 "|" $2) } }
  END {
    print "| Method | Part | Scenes | Mean F1 | Worst F1 | Mean abs count error | Off > 20 % | ... with no warning | Zero counts | Mean s |"
    print "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    m = sorted("M|", K)
    for (i = 1; i <= m; i++) { split(K[i], p, "|")
      printf "| %s | %s | %d | %.3f | %.3f | %.1f%% | %d | %d | %d | %.2f |\n", p[2], p[3], n[K[i]], f[K[i]] / n[K[i]], worst[K[i]],
        100 * ae[K[i]] / n[K[i]], off[K[i]], silent[K[i]], zero[K[i]], t[K[i]] / n[K[i]] }
    print ""
    np = 0; for (k in n) { split(k, p, "|"); if (!(p[3] in seen) && p[3] != "all") { seen[p[3]] = 1; parts[++np] = p[3] } }
    for (i = 1; i <= np; i++) for (j = i + 1; j <= np; j++) if (rank(parts[j]) < rank(parts[i])) { x = parts[i]; parts[i] = parts[j]; parts[j] = x }
    print "Method `" first "` by condition (r/s: fruit radius in point spacings; per part: scenes, mean F1, worst F1, off by > 20 %):"
    print ""
    head = "| Condition |"; rule = "| --- |"
    for (i = 1; i <= np; i++) { head = head " " parts[i] " | F1 | worst | off |"; rule = rule " ---: | ---: | ---: | ---: |" }
    print head; print rule
    m = sorted("C|", K)
    for (i = 1; i <= m; i++) { split(K[i], p, "|"); c = p[2]; if (c in shown) continue; shown[c] = 1
      line = "| " c " |"
      for (q = 1; q <= np; q++) { a = "C|" c "|" parts[q]
        line = line (n[a] ? sprintf(" %d | %.3f | %.3f | %d |", n[a], f[a] / n[a], worst[a], off[a]) : " 0 | - | - | - |") }
      print line }
  }' "$rows")
echo "$table"
if [ $write_docs = 1 ]; then
  how="--split $split"
  [ -n "$ids" ] && how="--ids $ids"
  [ -n "$from_rows" ] && how="--rows $from_rows"
  stamp="Generated by \`bash bench/robustness.sh $how --methods \"$methods\" --write-docs\` at commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown) on $(nproc) cores (whole process per scene, this shared VM). Rows: \`$rows\`. F1 and count error against the fruit present in each cloud."
  write_generated docs/robustness.md "Robustness" "$(printf '%s\n\n%s' "$stamp" "$table")"
fi
