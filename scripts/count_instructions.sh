#!/usr/bin/env bash
# The speed matrix (bench/bench_bullet_speed_matrix.cpp) and the multibody
# world (bench/bench_bullet_multibody.cpp) as instruction counts: each
# cell's or field's episode under callgrind, once per variant, and the
# patch variants' counts against stock Bullet's. Counts, unlike times, are
# the same on every run of the same build whatever else the machine does,
# so a change can be judged on a busy or noisy machine. Refreshes the
# sections bench-matrix-ir-float and bench-multibody-ir-float (or -double,
# from the programs' --precision) of docs/benchmarks.md. Not part of the
# tests.
#   bash scripts/count_instructions.sh [BUILD_DIR]
# Environment:
#   COUNT=multibody  only the multibody world (or COUNT=matrix: only the
#                  speed matrix; default both)
#   MAX_N=1000     largest N (default 1000: under callgrind the N = 1000
#                  pile takes about 2 minutes per variant on one core;
#                  10000 is possible, and slow)
#   CELLS="slipping:100:default pile:10:tight"   only these cells (the
#                  section is then not refreshed; the table goes to stdout)
#   BENCH_DOC=path refresh this file instead of docs/benchmarks.md
# Needs valgrind (Debian package valgrind; its header is what the program
# brackets the episode with).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
doc=${BENCH_DOC:-$root/docs/benchmarks.md}
max_n=${MAX_N:-1000}
what=${COUNT:-matrix multibody}
command -v valgrind >/dev/null || { echo "count_instructions: valgrind is not installed (apt-get install valgrind)" >&2; exit 2; }
[[ $max_n =~ ^[0-9]+$ ]] || { echo "count_instructions: MAX_N must be an integer, got '$max_n'" >&2; exit 2; }
for p in $what; do
  [[ $p == matrix || $p == multibody ]] || { echo "count_instructions: COUNT lists matrix and/or multibody, got '$p'" >&2; exit 2; }
  exe=$build/bench/$([[ $p == matrix ]] && echo bench_bullet_speed_matrix || echo bench_bullet_multibody)
  [[ -x $exe ]] || { echo "count_instructions: $exe is not built (cmake --build $build --target $(basename "$exe"))" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
start=$SECONDS
# shellcheck source=scripts/doc_section.sh
source "$root/scripts/doc_section.sh"

# instructions of one --count run: program, --count value, variant
count_run() {
  local out=$tmp/cg.out
  if ! valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$out" \
    "$1" --count="$2" --variant="$3" >"$tmp/run.txt" 2>"$tmp/run.err"; then
    echo "count_instructions: $(basename "$1") $2 $3 failed:" >&2
    cat "$tmp/run.err" >&2
    return 1
  fi
  local ir
  ir=$(awk '/^totals:/ { print $2; exit }' "$out")
  [[ -n $ir ]] || { echo "count_instructions: no totals in callgrind's output for $2 $3" >&2; return 1; }
  echo "$ir"
}

# the multibody world: 100 grippers and 100 feet, 180 steps each
if [[ " $what " == *" multibody "* ]]; then
  prog=$build/bench/bench_bullet_multibody
  precision=$("$prog" --precision)
  table=$tmp/multibody.md
  {
    echo "Bullet in $precision; instructions of each field's whole episode (180 steps; callgrind, \`bash scripts/count_instructions.sh\`), the patch variants against stock btMultiBodyConstraintSolver's."
    echo
    echo "| field | N | stock [instructions per step] | none opted in | ellipsoidal | exact |"
    echo "|---|---|---|---|---|---|"
  } >"$table"
  for field in grippers:100 feet:100; do
    declare -A ir=()
    for v in stock none-opted-in ellipsoidal exact; do
      echo "[multibody] $field $v ($((SECONDS - start)) s so far)" >&2
      ir[$v]=$(count_run "$prog" "$field" "$v")
    done
    IFS=: read -r name n <<<"$field"
    awk -v f="$name" -v n="$n" -v s="${ir[stock]}" -v o="${ir[none-opted-in]}" \
      -v e="${ir[ellipsoidal]}" -v x="${ir[exact]}" \
      'BEGIN { printf "| %s | %s | %.0f | %.3f | %.3f | %.3f |\n", f, n, s / 180, o / s, e / s, x / s }' >>"$table"
    unset ir
  done
  cat "$table"
  replace_doc_section "$doc" "bench-multibody-ir-$precision" "$table" &&
    echo "section bench-multibody-ir-$precision of $doc refreshed" >&2
fi
[[ " $what " == *" matrix "* ]] || { echo "done in $((SECONDS - start)) s" >&2; exit 0; }

prog=$build/bench/bench_bullet_speed_matrix
precision=$("$prog" --precision)
variants=(stock none-opted-in ellipsoidal exact)
if [[ -n ${CELLS:-} ]]; then
  read -r -a cells <<<"$CELLS"
else
  cells=()
  for bp in default tight; do
    for scene in slipping to-rest pile; do
      for n in 10 100 1000 10000; do
        ((n <= max_n)) && cells+=("$scene:$n:$bp")
      done
    done
  done
fi
total=$((${#cells[@]} * ${#variants[@]}))
done_runs=0
table=$tmp/table.md
{
  echo "Bullet in $precision; instructions of each cell's whole episode (callgrind, \`bash scripts/count_instructions.sh\`), the patch variants against stock Bullet's."
  echo
  echo "| scene | N | broadphase | stock [instructions per step] | none opted in | ellipsoidal | exact |"
  echo "|---|---|---|---|---|---|---|"
} >"$table"
worst_e=0 worst_x=0 where_e="" where_x=""
for cell in "${cells[@]}"; do
  declare -A ir=()
  for v in "${variants[@]}"; do
    done_runs=$((done_runs + 1))
    echo "[$done_runs/$total] $cell $v ($((SECONDS - start)) s so far)" >&2
    ir[$v]=$(count_run "$prog" "$cell" "$v")
  done
  IFS=: read -r scene n bp <<<"$cell"
  steps=$(case $scene in slipping) echo 48 ;; to-rest) echo 120 ;; *) echo 240 ;; esac)
  row=$(awk -v s="${ir[stock]}" -v o="${ir[none-opted-in]}" -v e="${ir[ellipsoidal]}" \
    -v x="${ir[exact]}" -v steps="$steps" \
    'BEGIN { printf "%.0f|%.3f|%.3f|%.3f", s / steps, o / s, e / s, x / s }')
  IFS='|' read -r per_step r_none r_e r_x <<<"$row"
  echo "| $scene | $n | $bp | $per_step | $r_none | $r_e | $r_x |" >>"$table"
  if awk -v a="$r_e" -v b="$worst_e" 'BEGIN { exit !(a > b) }'; then worst_e=$r_e where_e="$scene, N = $n, $bp broadphase"; fi
  if awk -v a="$r_x" -v b="$worst_x" 'BEGIN { exit !(a > b) }'; then worst_x=$r_x where_x="$scene, N = $n, $bp broadphase"; fi
  unset ir
done
{
  echo
  echo "Worst cells: ellipsoidal ${worst_e}x stock ($where_e), exact ${worst_x}x stock ($where_x)."
} >>"$table"
cat "$table"
name=bench-matrix-ir-$precision
if [[ -n ${CELLS:-} ]]; then
  echo "(CELLS given: section $name of $doc not refreshed)" >&2
else
  replace_doc_section "$doc" "$name" "$table" && echo "section $name of $doc refreshed" >&2
fi
echo "done in $((SECONDS - start)) s" >&2
