#!/usr/bin/env bash
# patchspin quick start on Debian 12:
#   bash scripts/quickstart.sh demo   install what is missing, build (Release), run the main demo
#   bash scripts/quickstart.sh test   same set-up, then run every test with ctest, and the core
#                                     tests under the asan preset (CMakePresets.json)
# Environment: BUILD_DIR (default ./build), JOBS (default: number of cores).
set -euo pipefail

mode=${1:-demo}
case "$mode" in demo|test|build) ;; *) echo "usage: $0 demo|test|build" >&2; exit 2 ;; esac

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-$root/build}
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}

# Debian packages the project needs (build, tests, benchmarks, rendering).
packages=(
  cmake g++ make pkg-config clang-format
  libeigen3-dev libbullet-dev libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libboost-math-dev
  libosmesa6-dev libcairo2-dev libpng-dev gnuplot-nox fonts-dejavu-core
  valgrind  # scripts/count_instructions.sh: instruction counts, and the header it needs
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "== installing missing Debian packages: ${missing[*]}"
  if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null 2>&1; then
      SUDO=sudo
    else
      echo "error: packages missing (${missing[*]}) and not running as root." >&2
      echo "       run this script as root, or: apt-get install ${missing[*]}" >&2
      exit 1
    fi
  else
    SUDO=
  fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

configure_and_build() {  # dir, extra cmake args...
  local dir=$1; shift
  echo "== configuring $dir $*"
  cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  echo "== building $dir (-j$jobs)"
  cmake --build "$dir" -j"$jobs"
}

configure_and_build "$build"

if [[ $mode == build ]]; then exit 0; fi

if [[ $mode == test ]]; then
  echo "== tests (single-precision Bullet build)"
  (cd "$build" && ctest --output-on-failure -j"$jobs" --timeout 900)
  if [[ -d "$root/tests/bullet" ]] && ls "$root"/tests/bullet/*_test.cpp >/dev/null 2>&1; then
    echo "== tests of the Bullet layer against double-precision Bullet (bullet-float64)"
    # only what those tests need: no renderer, tool or benchmarks, and the
    # Bullet layer's test executables alone (not the core's, run above)
    echo "== configuring $build-double (double-precision Bullet)"
    cmake -S "$root" -B "$build-double" -DCMAKE_BUILD_TYPE=Release -DPATCHSPIN_BULLET_DOUBLE=ON \
      -DPATCHSPIN_BUILD_RENDER=OFF -DPATCHSPIN_BUILD_TOOLS=OFF -DPATCHSPIN_BUILD_BENCH=OFF >/dev/null
    echo "== building $build-double: the Bullet layer's tests (-j$jobs)"
    cmake --build "$build-double" -j"$jobs" --target patchspin_bullet_tests
    (cd "$build-double" && ctest --output-on-failure -j"$jobs" --timeout 900 -L "bullet|stress")
  fi
  # The core label again under the asan preset of CMakePresets.json: ASan +
  # UBSan (aborting on the first finding) with assertions live (no NDEBUG), at
  # -O1. It builds only patchspin::core and the core tests, in "$build-asan";
  # the same as: cmake --preset asan && cmake --build --preset asan && ctest
  # --preset asan. (The assert preset, -O3 with assertions, checks the same
  # assertions in the optimised build; it is not run here, to keep CI short.)
  for preset in asan; do
    echo "== core tests, preset $preset"
    (cd "$root" && cmake --preset "$preset" -B "$build-$preset" >/dev/null)
    cmake --build "$build-$preset" -j"$jobs" --target patchspin_core_tests
    (cd "$build-$preset" && ctest --output-on-failure -j"$jobs" --timeout 900 -L core)
  done
  exit 0
fi

# main demo
if [[ -x "$build/demos/coin" ]]; then
  exec bash "$root/scripts/demo.sh" "$build"
fi
tool="$build/tools/patchspin"
echo
echo "== patchspin friction: a disk of radius 5 cm carrying 10 N, sliding along x while spinning"
echo "   (slip direction w = (u_x, u_y, rho w_z)/r = (0.6, 0, 0.8); rho = 2R/3 by Eq. (11))"
echo
echo "-- exact law, Eq. (16): local Coulomb friction integrated over the disk"
"$tool" friction --patch disk:0.05 --model exact --loads 10,0,0 --mu 0.5 --w 0.6,0,0.8
echo
echo "-- ellipsoidal law, Eq. (41): Q = -mu Pz Pi w (uniform pressure on a centred disk: Pi = I)"
"$tool" friction --patch disk:0.05 --model ellipsoidal --loads 10,0,0 --mu 0.5 --w 0.6,0,0.8
echo
echo "-- the same disk tipped by a torque Tx = 0.05 N m (pressure higher at y < 0): Pi is no longer I"
"$tool" friction --patch disk:0.05 --model exact --loads 10,0.05,0 --mu 0.5 --w 0.6,0,0.8
cat <<'TXT'

How to read this: Q = (Px, Py, Tz/rho) is the friction force and torque about
the patch centre O. Both laws oppose the slip (Px < 0 for u_x > 0, Tz < 0 for
w_z > 0). They agree exactly for pure sliding and pure spinning (the three
fitting motions, Eq. (37)-(39)) and differ for combined slip and spin: here the
exact law's force is about a fifth smaller than the ellipsoid's (spinning lowers
the resistance to sliding), while the torques are within a few per cent.
A tipping torque makes the pressure linear, Eq. (94), and couples sliding with
spinning: Px changes although the slip is the same, and Pi gains the
off-diagonal terms of Eq. (73).
TXT
