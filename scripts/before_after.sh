#!/usr/bin/env bash
# Prints the README's before/after table (Markdown) from the project's own
# programs: the coin demo's summary.json (build/demos/coin) and
# `patchspin simulate` (build/tools/patchspin), Bullet and the reference
# dynamics of Eq. (93). Nothing in the table is typed by hand.
#   bash scripts/before_after.sh [BUILD_DIR]      (default ./build)
#   bash scripts/before_after.sh --write [BUILD_DIR]   also puts the table into
#        README.md, between <!-- before-after:begin --> and <!-- before-after:end -->
# Builds the two programs it needs first (configuring BUILD_DIR as Release if
# it is not configured yet); SKIP_BUILD=1 uses them as built. Needs python3
# (Debian: python3) to read the JSON. Takes ~1 minute after the build.
#
# Rows (all in the precision of the Bullet build):
#   coin      the coin demo: R = 5 cm, H = 5 mm, 30 g, mu = 0.3, sliding at
#             0.5 m/s and spinning at 20 rad/s, 240 steps/s; exact column:
#             `patchspin simulate --engine reference --model exact`
#   spin      the same coin spinning in place at 20 rad/s: mean spin
#             deceleration omega0 / t_stop; exact: the reference dynamics
#   cube      a 10 cm cube of 1 kg on the floor (mu = 0.5) under a constant
#             couple about the vertical, 0.8x and 1.25x the exact law's
#             largest static couple mu m g a (sqrt 2 + ln(1 + sqrt 2)) / 6
#             (uniform pressure over the face); angle turned in 1 s
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
write=0
if [[ ${1:-} == --write ]]; then
  write=1
  shift
fi
build=${1:-$root/build}
command -v python3 >/dev/null || { echo "error: needs python3 (apt-get install python3)" >&2; exit 1; }
if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  if [[ ! -f $build/CMakeCache.txt ]]; then
    echo "== configuring $build (Release)" >&2
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  echo "== building coin and patchspin in $build" >&2
  cmake --build "$build" -j"${JOBS:-2}" --target coin patchspin_tool >&2
fi
coin=$build/demos/coin
tool=$build/tools/patchspin
for exe in "$coin" "$tool"; do
  [[ -x $exe ]] || { echo "error: $exe not built" >&2; exit 1; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# coin demo parameters (its defaults; the table names them)
R=0.05 H=0.005 m=0.03 mu=0.3 v0=0.5 w0=20 rate=240
echo "== coin demo (summary.json only: 2 small frames)" >&2
"$coin" --out "$out/coin" --frames 2 --size 64x36 --no-plot --quiet >&2
sim() {  # name, simulate flags...
  local name=$1
  shift
  "$tool" simulate --json "$@" >"$out/$name.json"
}
coin_flags=(--shape "cylinder:$R,$H" --mass "$m" --mu "$mu" --dt "$(python3 -c "print(1/$rate)")")
echo "== reference dynamics and Bullet runs (patchspin simulate)" >&2
sim coin_ref --engine reference --model exact "${coin_flags[@]}" --v0 "$v0,0" --omega0 $w0
for model in exact ellipsoidal stock; do
  sim "spin_$model" --engine bullet --model $model "${coin_flags[@]}" --omega0 $w0 --t-max 10
done
sim spin_ref --engine reference --model exact "${coin_flags[@]}" --omega0 $w0 --t-max 10
a=0.1 cm=1 cmu=0.5
tlim=$(python3 -c "import math; print($cmu*$cm*9.81*$a*(math.sqrt(2)+math.log(1+math.sqrt(2)))/6)")
for f in 0.8 1.25; do
  T=$(python3 -c "print($f*$tlim)")
  cube_flags=(--shape "box:$a,$a,$a" --mass "$cm" --mu "$cmu" --torque "0,0,$T" --t-max 1)
  sim "cube_${f}_ref" --engine reference --model exact "${cube_flags[@]}"
  for model in exact ellipsoidal stock; do
    sim "cube_${f}_$model" --engine bullet --model $model "${cube_flags[@]}" --dt "$(python3 -c "print(1/$rate)")"
  done
done

python3 - "$out" "$R" "$H" "$m" "$mu" "$v0" "$w0" >"$out/table.md" <<'EOF'
import json, sys, os
out = sys.argv[1]
def load(name): return json.load(open(os.path.join(out, name)))
summary = load('coin/summary.json')
# the reference runs use the script's coin: it must be the demo's
R, H, m, mu, v0, w0 = map(float, sys.argv[2:8])
p = summary['parameters']
for key, want in (('radius', R), ('height', H), ('mass', m), ('mu', mu), ('v0', v0), ('omega0', w0)):
    if abs(p[key] - want) > 1e-12 * abs(want):
        sys.exit(f'coin demo parameter {key} = {p[key]}, the script assumes {want}: update before_after.sh')
coin = summary['models']
models = ['exact', 'ellipsoidal', 'stock']
def num(x, fmt='{:.3g}'):
    return '—' if x is None else fmt.format(x)
rows = []
ref = load('coin_ref.json')
rows.append(('coin sliding and spinning: v/(Rω) when the slip has fallen to 1 %',
             num(ref['eps_stop']), [num(coin[k]['eps_stop']) for k in models]))
rows.append(('coin sliding and spinning: time to stop [s]',
             num(ref['t_stop']), [num(coin[k]['t_stop']) if coin[k]['stopped'] else 'no stop' for k in models]))
def decel(d):
    return num(w0 / d['t_stop']) if d['stopped'] and d['t_stop'] > 0 else 'no stop'
spin_ref = load('spin_ref.json')
rows.append(('coin spinning in place: mean spin deceleration [rad/s²]',
             decel(spin_ref), [decel(load(f'spin_{k}.json')) for k in models]))
rows.append(('coin sliding and spinning: largest tilt rate (rocking) [rad/s]',
             '0 (a flat body)', [num(coin[k]['max_tilt_rate'], '{:.2g}') for k in models]))
rows.append(('coin sliding and spinning: largest slip speed after it stopped (creep) [m/s]',
             '0', [num(coin[k]['max_slip_after_stop'], '{:.2g}') for k in models]))
for f, what in (('0.8', '0.8×'), ('1.25', '1.25×')):
    ref = load(f'cube_{f}_ref.json')
    rows.append((f'cube twisted on the floor at {what} the largest couple friction holds: turned in 1 s [rad]',
                 num(abs(ref['rotation']), '{:.3g}'),
                 [num(abs(load(f'cube_{f}_{k}.json')['rotation']), '{:.3g}') for k in models]))
prec = summary['precision']
print(f'| {prec} Bullet, 240 steps/s | exact (reference dynamics) | patchspin exact | patchspin ellipsoidal | stock Bullet |')
print('|---|---|---|---|---|')
for name, exact, vals in rows:
    print(f'| {name} | {exact} | ' + ' | '.join(vals) + ' |')
EOF
cat "$out/table.md"
if ((write)); then
  readme=$root/README.md
  # shellcheck source=scripts/doc_section.sh
  source "$root/scripts/doc_section.sh"
  replace_doc_section "$readme" before-after "$out/table.md" || exit 1
  echo "== README.md table written" >&2
fi
