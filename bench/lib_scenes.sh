# Shared by bench/reproduce_table2.sh and bench/dense_bunches.sh (source it; needs build/bin).
# score_scenes CSV LABEL PRESET_SOLID PRESET_DEGRADED SEED...
#   Generates (once, cached in build/scenes/) peach, apple and plum in the explicit, implicit and
#   degraded modes for each seed, counts each with pc_fruitcount (PRESET_SOLID for explicit and
#   implicit clouds, PRESET_DEGRADED for degraded ones), scores with pc_eval and appends rows:
#   label,species,mode,seed,preset,fruit_present,count,gt_count,recovery,precision,recall,f1,merged,split,seconds
score_scenes() {
  local csv=$1 label=$2 solid=$3 degraded=$4
  shift 4
  local b=build/bin dir=build/scenes species mode seed preset stem start end present
  mkdir -p "$dir"
  [ -f "$csv" ] || echo "label,species,mode,seed,preset,fruit_present,count,gt_count,recovery,precision,recall,f1,merged,split,seconds" >"$csv"
  for species in peach apple plum; do
    for mode in explicit implicit degraded; do
      preset=$solid
      [ "$mode" = degraded ] && preset=$degraded
      for seed in "$@"; do
        stem="$dir/${species}_${mode}_$seed"
        if [ ! -f "$stem.json" ] || [ "$b/pc_synth" -nt "$stem.json" ]; then
          $b/pc_synth --species "$species" --mode "$mode" --seed "$seed" -o "$stem.pcd" --truth "$stem.json"
        fi
        start=$(date +%s.%N)
        $b/pc_fruitcount --preset "$preset" -i "$stem.pcd" --cloud "$stem.$preset.pcd" --plain >/dev/null
        end=$(date +%s.%N)
        present=$(grep -m1 '"fruit_present"' "$stem.json" | tr -dc '0-9')
        $b/pc_eval -i "$stem.$preset.pcd" --truth "$stem.json" --preset "$preset" --csv | tail -n 1 \
          | awk -F, -v l="$label" -v s="$species" -v m="$mode" -v seed="$seed" -v p="$preset" -v fp="$present" \
                -v t="$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" \
                '{printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%.2f\n", l, s, m, seed, p, fp, $3, $4, $5, $9, $10, $11, $12, $13, t}' \
          >>"$csv"
      done
    done
  done
}

# write_generated DOC TITLE BLOCK [NAME]: replaces the text between the markers of DOC (or creates
# DOC); NAME tells a page's blocks apart (<!-- BEGIN generated NAME -->). The block goes to awk in
# a file, not as an argument: one argument holds at most 128 KiB (the matrix's tables of 4940
# scenes are more, and `awk -v` failed with "Argument list too long").
write_generated() {
  local doc=$1 title=$2 text=$3 name=${4:+ $4} blockfile
  local begin="<!-- BEGIN generated$name -->" end="<!-- END generated$name -->"
  blockfile=$(mktemp)
  printf '%s\n%s\n%s\n' "$begin" "$text" "$end" >"$blockfile"
  if [ -f "$doc" ] && grep -qF "$begin" "$doc"; then
    if ! awk -v blockfile="$blockfile" -v begin="$begin" -v end="$end" '
      $0 == begin { while ((getline line < blockfile) > 0) print line; skip = 1; next }
      $0 == end { skip = 0; next }
      !skip { print }' "$doc" >"$doc.tmp"; then
      rm -f "$blockfile" "$doc.tmp"
      echo "write_generated: $doc not written" >&2
      return 1
    fi
    mv "$doc.tmp" "$doc"
  elif [ -f "$doc" ]; then
    { printf '\n'; cat "$blockfile"; } >>"$doc"
  else
    { printf '# %s\n\n' "$title"; cat "$blockfile"; } >"$doc"
  fi
  rm -f "$blockfile"
  echo "written: $doc" >&2
}
