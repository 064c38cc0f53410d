#!/usr/bin/env bash
# Runs every benchmark program and refreshes the README's benchmark section
# (between the "bench:begin" and "bench:end" markers). Not part of the tests.
#   bash scripts/run_benchmarks.sh [BUILD_DIR]
# Set MIN_TIME (seconds per benchmark, default 0.2) for steadier figures.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
min_time=${MIN_TIME:-0.2}
out=$build/bench-results
mkdir -p "$out"
BUILD_DIR=$build bash "$root/scripts/quickstart.sh" build

section=$(mktemp)
{
  echo "Measured on $(nproc) cores ($(uname -m)), $(date -u +%Y-%m-%d); CPU time per call."
  echo "Regenerate with \`bash scripts/run_benchmarks.sh\`."
  for b in bench_models bench_exact_disk bench_exact_polygon bench_analysis bench_bullet_world; do
    exe=$build/bench/$b
    [[ -x $exe ]] || continue
    echo "running $b" >&2
    "$exe" --benchmark_min_time="$min_time" --benchmark_out="$out/$b.json" --benchmark_out_format=json \
      >"$out/$b.txt" 2>"$out/$b.err"
    echo
    echo "\`$b\`:"
    echo
    echo '```'
    grep -E '^(Benchmark|BM_|-)' "$out/$b.txt" | grep -v '^-' | sed 's/ *$//'
    echo '```'
  done
} >"$section"

readme=$root/README.md
awk -v file="$section" '
  /<!-- bench:begin -->/ { print; while ((getline line < file) > 0) print line; skip = 1; next }
  /<!-- bench:end -->/ { skip = 0 }
  !skip { print }
' "$readme" >"$readme.tmp" && mv "$readme.tmp" "$readme"
rm -f "$section"
echo "README benchmark section refreshed from $out" >&2
