#!/usr/bin/env bash
# Runs every benchmark program (bench/bench_*.cpp) and refreshes the benchmark
# tables of docs/benchmarks.md and the CSVs in docs/bench/. Not part of the tests.
#   bash scripts/run_benchmarks.sh [BUILD_DIR]
# Takes about 5 minutes on 2 cores (most of it the world-scale benchmark's
# 10000-body pile); progress goes to stderr.
#
# Environment:
#   MIN_TIME=0.2              seconds per micro-benchmark (steadier figures: more)
#   SKIP_BUILD=1              do not (re)build first (BUILD_DIR must hold the programs)
#   PATCHSPIN_SCALE_MAX_N=1000  skip the 10000-body world (bench_bullet_scale)
#   PATCHSPIN_MATRIX_MAX_N=1000 skip the 10000-body cells of the speed matrix
#   PATCHSPIN_MATRIX_REPETITIONS=5  repetitions per speed-matrix cell
#   PATCHSPIN_MULTIBODY_REPETITIONS=7  repetitions per multibody field
#   ONLY="bench_bullet_multibody ..."  run only these programs (sections of the others
#                             are left as they are)
#   PATCHSPIN_SCALE_REPETITIONS=3  world scale: fastest of 3 repetitions, not 9
#                             (a third of its time; ratios +-20 % on a noisy machine)
#   BENCH_DOC=path            refresh this file instead of docs/benchmarks.md (to try the script)
#
# Sections of docs/benchmarks.md, each between a pair of markers (a missing pair is reported
# and skipped; the table is then only in BUILD_DIR/bench-results):
#   <!-- bench:begin -->            <!-- bench:end -->            raw tables of the
#                                   micro-benchmarks (models, exact law, analysis, Bullet world)
#   <!-- bench-patch:begin -->      <!-- bench-patch:end -->      per patch: time against error
#   <!-- bench-simulation:begin --> <!-- bench-simulation:end --> per simulation
#   <!-- bench-scale:begin -->      <!-- bench-scale:end -->      world scale
#   <!-- bench-matrix-float:begin --> (or -double, the build's precision)
#                                   the speed matrix (bench_bullet_speed_matrix;
#                                   its instruction counts: scripts/count_instructions.sh)
#   <!-- bench-multibody-float:begin --> (or -double)
#                                   the multibody world (bench_bullet_multibody: 100
#                                   grippers, 100 feet; its counts: count_instructions.sh)
# CSVs: docs/bench/patch_error.csv, simulation_error.csv, world_scale.csv
# (scripts/make_gallery.sh plots the first two).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$root/build}" 2>/dev/null && pwd || echo "${1:-$root/build}")
min_time=${MIN_TIME:-0.2}
out=$build/bench-results
csvdir=$root/docs/bench
doc=${BENCH_DOC:-$root/docs/benchmarks.md}
if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  echo "== building (scripts/quickstart.sh build)" >&2
  BUILD_DIR=$build bash "$root/scripts/quickstart.sh" build
fi
mkdir -p "$out" "$csvdir"

# the micro-benchmarks whose raw table goes into the "bench" section, then
# the time-against-error benchmarks with their own sections
micro=(bench_models bench_exact_disk bench_exact_polygon bench_analysis bench_bullet_world)
declare -A section_of=([bench_patch_error]=bench-patch [bench_bullet_simulation]=bench-simulation
  [bench_bullet_scale]=bench-scale)
declare -A csv_of=([bench_patch_error]=patch_error.csv [bench_bullet_simulation]=simulation_error.csv
  [bench_bullet_scale]=world_scale.csv)
declare -A args_of=([bench_patch_error]="--benchmark_min_time=$min_time")
error_benches=(bench_patch_error bench_bullet_simulation bench_bullet_scale)
matrix=bench_bullet_speed_matrix
multibody=bench_bullet_multibody
# anything else named bench_* in the build joins the raw section
for exe in "$build"/bench/bench_*; do
  b=$(basename "$exe")
  [[ -x $exe && -f $exe ]] || continue
  [[ " ${micro[*]} ${error_benches[*]} $matrix $multibody " == *" $b "* ]] || micro+=("$b")
done
# ONLY: keep the listed programs of each group
if [[ -n ${ONLY:-} ]]; then
  keep() { for b in "$@"; do [[ " $ONLY " == *" $b "* ]] && echo "$b"; done; }
  mapfile -t micro < <(keep "${micro[@]}")
  mapfile -t error_benches < <(keep "${error_benches[@]}")
  [[ " $ONLY " == *" $matrix "* ]] || matrix=""
  [[ " $ONLY " == *" $multibody "* ]] || multibody=""
fi
tables=()
[[ -z $matrix ]] || tables+=("$matrix")
[[ -z $multibody ]] || tables+=("$multibody")
all=("${micro[@]}" "${error_benches[@]}" "${tables[@]}")
total=${#all[@]}
count=0
start=$SECONDS

run() {  # bench, extra args...
  local b=$1
  shift
  count=$((count + 1))
  echo "[$count/$total] $b ($((SECONDS - start)) s so far)" >&2
  if ! "$build/bench/$b" "$@" --benchmark_out="$out/$b.json" --benchmark_out_format=json \
    >"$out/$b.txt" 2>"$out/$b.err"; then
    echo "   $b failed; see $out/$b.err" >&2
    return 1
  fi
}

# replaces the generated block NAME of the benchmark document with FILE (a
# document without that block is left alone, reported)
# shellcheck source=scripts/doc_section.sh
source "$root/scripts/doc_section.sh"
replace_section() {  # name, file
  replace_doc_section "$doc" "$1" "$2" && echo "   section $1 of $doc refreshed" >&2 || true
}

stamp="Measured on $(nproc) cores ($(uname -m)), $(date -u +%Y-%m-%d)"
failed=0

# (1) micro-benchmarks: raw Google Benchmark tables
section=$(mktemp)
trap 'rm -f "$section" "$section".*' EXIT
{
  echo "$stamp; CPU time per call."
  echo "Regenerate with \`bash scripts/run_benchmarks.sh\`."
} >"$section"
incomplete=0
for b in "${micro[@]}"; do
  if [[ ! -x $build/bench/$b ]]; then
    count=$((count + 1))
    echo "[$count/$total] $b: not built, skipped" >&2
    incomplete=1
    continue
  fi
  run "$b" --benchmark_min_time="$min_time" || { failed=1; incomplete=1; continue; }
  {
    echo
    echo "\`$b\`:"
    echo
    echo '```'
    # (bench_bullet_world interleaves its repetitions in random order, which
    # shuffles the rows: back into name order)
    grep -E '^Benchmark' "$out/$b.txt" | sed 's/ *$//'
    grep -E '^BM_' "$out/$b.txt" | sed 's/ *$//' |
      if [[ $b == bench_bullet_world ]]; then sort -V -s -k1,1; else cat; fi
    echo '```'
  } >>"$section"
done
# a partial run would drop tables: then the section stays as it was
if ((incomplete)) || [[ -n ${ONLY:-} ]]; then
  ((${#micro[@]} == 0)) ||
    echo "   some micro-benchmarks did not run: section bench of $doc left as it was" >&2
else
  replace_section bench "$section"
fi

# (2) time against error: each program's own summary (everything from its
# first summary line on), CSV into docs/bench/
for b in "${error_benches[@]}"; do
  if [[ ! -x $build/bench/$b ]]; then
    count=$((count + 1))
    echo "[$count/$total] $b: not built, skipped" >&2
    continue
  fi
  # shellcheck disable=SC2086
  run "$b" ${args_of[$b]:-} --csv="$csvdir/${csv_of[$b]}" || { failed=1; continue; }
  {
    echo "$stamp. Regenerate with \`bash scripts/run_benchmarks.sh\`; data: \`docs/bench/${csv_of[$b]}\`."
    echo
    echo '```'
    awk '/^(Per patch|Per simulation|World scale)/ { on = 1 } on && !/^wrote / { print }' "$out/$b.txt" |
      sed 's/ *$//'
    echo '```'
  } >"$section.$b"
  replace_section "${section_of[$b]}" "$section.$b"
done

# (3) the speed matrix and the multibody world: their own markdown tables,
# per precision
for b in "${tables[@]}"; do
  name=$([[ $b == "$matrix" ]] && echo bench-matrix || echo bench-multibody)
  if [[ ! -x $build/bench/$b ]]; then
    count=$((count + 1))
    echo "[$count/$total] $b: not built, skipped" >&2
  elif run "$b" --markdown="$section.$name"; then
    {
      echo "$stamp. Regenerate with \`bash scripts/run_benchmarks.sh\`."
      echo
      cat "$section.$name"
    } >"$section.$name.md"
    replace_section "$name-$("$build/bench/$b" --precision)" "$section.$name.md"
  else
    failed=1
  fi
done

echo "done in $((SECONDS - start)) s: results in $out, CSVs in $csvdir" >&2
echo "plots: bash scripts/make_gallery.sh $build" >&2
exit $failed
