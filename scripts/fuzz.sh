#!/usr/bin/env bash
# patchspin fuzzing (issue 6): configure a clang build with the libFuzzer
# targets, build them, run each for N inputs and merge new inputs into the
# kept corpus fuzz/corpus/<name>/ (replayed by `ctest -L fuzz` in every build).
#
#   bash scripts/fuzz.sh [RUNS] [TARGET...]
#     RUNS     inputs per target (default 1000000)
#     TARGET   friction_q pressure pi step limits (default: all)
# Environment: FUZZ_SANITIZERS (besides the fuzzer: "address,undefined", the
# default, or "undefined", the fast mode without ASan, 5-100x more inputs per
# second; UBSan aborts on the first finding in both), FUZZ_BUILD_DIR (default
# ./build-fuzz, ./build-fuzz-fast in the fast mode), FUZZ_MAX_TIME (seconds
# per target, a guard; default 14400), FUZZ_OUT (work dir, default
# $FUZZ_BUILD_DIR/fuzz-out: crash-* files and logs land there), FUZZ_NICE
# (niceness of the fuzzer processes, default 10; one runs at a time),
# FUZZ_KEEP_GOING (1: libFuzzer's fork mode with one job at a time,
# -fork=1 -ignore_crashes=1: a failure, a timeout or an OOM is saved as
# crash-*/timeout-*/oom-* in FUZZ_OUT and the run goes on until RUNS inputs;
# the count is the parent's last "#N: cov: ..." line, the sum of the jobs'
# stat::number_of_executed_units. Default 0: stop at the first failure).
# Installs clang and libclang-rt-14-dev (libFuzzer) with apt-get if missing.
set -euo pipefail

runs=${1:-1000000}
shift || true
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sanitizers=${FUZZ_SANITIZERS:-address,undefined}
if [[ $sanitizers == undefined ]]; then
  build=${FUZZ_BUILD_DIR:-$root/build-fuzz-fast}
else
  build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
fi
niceness=${FUZZ_NICE:-10}
max_time=${FUZZ_MAX_TIME:-14400}
out=${FUZZ_OUT:-$build/fuzz-out}
targets=("$@")
if ((${#targets[@]} == 0)); then
  targets=()
  for f in "$root"/fuzz/*_fuzz.cpp; do
    n=$(basename "$f" .cpp)
    targets+=("${n%_fuzz}")
  done
fi

# Debian packages: the compiler and libFuzzer's runtime
packages=(clang libclang-rt-14-dev cmake make libeigen3-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "== installing missing Debian packages: ${missing[*]}"
  SUDO=
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null 2>&1 || { echo "error: run as root or: apt-get install ${missing[*]}" >&2; exit 1; }
    SUDO=sudo
  fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

echo "== configuring $build (clang, PATCHSPIN_BUILD_FUZZ=ON, sanitizers fuzzer,$sanitizers)"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPATCHSPIN_BUILD_FUZZ=ON \
  -DPATCHSPIN_FUZZ_SANITIZERS="$sanitizers" \
  -DPATCHSPIN_BUILD_BULLET=OFF -DPATCHSPIN_BUILD_RENDER=OFF -DPATCHSPIN_BUILD_TESTS=OFF \
  -DPATCHSPIN_BUILD_TOOLS=OFF -DPATCHSPIN_BUILD_BENCH=OFF >/dev/null
echo "== building ${targets[*]}"
cmake --build "$build" -j"${JOBS:-2}" --target $(printf '%s_fuzz ' "${targets[@]}")

mkdir -p "$out"
status=0
for t in "${targets[@]}"; do
  corpus=$root/fuzz/corpus/$t
  work=$out/$t
  mkdir -p "$corpus" "$work"
  echo "== $t: $runs inputs (at most ${max_time}s), corpus $corpus"
  # fuzz in a scratch copy of the corpus, then merge only what adds coverage
  fork=()
  if [[ ${FUZZ_KEEP_GOING:-0} == 1 ]]; then
    fork=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  fi
  set +e
  nice -n "$niceness" "$build/fuzz/${t}_fuzz" "${fork[@]}" -runs="$runs" -max_total_time="$max_time" -timeout=10 \
    -rss_limit_mb=2048 -max_len=512 -artifact_prefix="$out/$t-" -print_final_stats=1 "$work" "$corpus" \
    >"$out/$t.log" 2>&1
  rc=$?
  set -e
  if ((${#fork[@]})); then
    # fork mode: the parent's last progress line counts every job's inputs
    grep -E "^#[0-9]+: cov:" "$out/$t.log" | tail -1 | sed "s/^/   /"
    grep -E "INFO: fuzzed for|INFO: exiting" "$out/$t.log" | sed "s/^/   /"
    n=$(ls "$out" | grep -c "^$t-\(crash\|timeout\|oom\)-" || true)
    echo "   failure files: $n ($out/$t-crash-*, -timeout-*, -oom-*)"
    ((n == 0)) || status=1
    rc=0
  fi
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec" "$out/$t.log" | sed "s/^/   /" || true
  if ((rc != 0)); then
    echo "   FAILED (exit $rc): see $out/$t.log and $out/$t-crash-*" >&2
    grep -m1 "patchspin fuzz check failed\|ERROR:" "$out/$t.log" >&2 || true
    status=1
  fi
  nice -n "$niceness" "$build/fuzz/${t}_fuzz" -merge=1 -max_len=512 "$corpus" "$work" >"$out/$t.merge.log" 2>&1 || true
  echo "   corpus: $(ls "$corpus" | wc -l) files"
done
exit $status
