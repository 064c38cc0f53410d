#!/usr/bin/env bash
# The multithreaded world's tests under ThreadSanitizer: two of a
# PatchSolverPoolMt's solvers solve disjoint islands on two threads
# (MultithreadedWorld.TwoThreadsSolveDisjointIslandsAsOneThread); TSan
# reports any data race in patchspin's code (Bullet's own libraries are not
# instrumented). Debian's Bullet; float, or double with --double.
#   bash scripts/tsan_multithreaded.sh [--double] [build-dir]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
double=OFF
if [[ "${1:-}" == "--double" ]]; then
  double=ON
  shift
fi
build=${1:-$root/build-tsan}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
  -DCMAKE_CXX_FLAGS="-fsanitize=thread" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
  -DPATCHSPIN_BULLET_DOUBLE=$double -DPATCHSPIN_BUILD_RENDER=OFF -DPATCHSPIN_BUILD_TOOLS=OFF \
  -DPATCHSPIN_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --target multithreaded_world_test multithreaded_world_two_threads_test
TSAN_OPTIONS="halt_on_error=1 ${TSAN_OPTIONS:-}" ctest --test-dir "$build" -R MultithreadedWorld \
  --output-on-failure
