#!/usr/bin/env bash
# Regenerates the README gallery's plots (issue 5) into docs/img/:
#   bifurcation_force.png  limit directions against F, thin disk, T = 0 (Fig. 11 analogue)
#   bifurcation_plane.png  number and types of limit directions over (F, T) (Fig. 13 analogue)
#   thick_disk_cycles.png  limit directions and limit cycles against F, issue 34's
#                          thick disk (its cycle dies at F = 0.1345 mu m g)
#   pareto_exact.png       time against error of the exact law's accuracy knob
#   pareto_patch.png       per patch: time per friction-block solve against the
#                          impulse's error, ellipsoidal / exact / stock point friction
#   pareto_sim_coin.png, pareto_sim_coin_limit.png, pareto_sim_pushed.png
#                          per simulation: CPU time per simulated second against the
#                          error vs the reference dynamics, one point per time step
# from `patchspin sweep`, the benchmark JSON in BUILD_DIR/bench-results and the
# CSVs in docs/bench/ (all three from scripts/run_benchmarks.sh).
# Runs in about a minute on 2 cores (the thick disk's cycle search takes most;
# the thin-disk sweeps skip it with --cycle-seeds 0). The gnuplot scripts (.gp, data inline) that
# the plot functions write next to each PNG are removed unless KEEP_GP=1.
#
# usage: scripts/make_gallery.sh BUILD_DIR
#   BUILD_DIR/tools/patchspin     the tool (sweep)
#   BUILD_DIR/demos/plots         the plot driver (demos/plots.cpp); override with PLOTS=path
#   BUILD_DIR/bench-results/bench_exact_{disk,polygon}.json   Google Benchmark JSON output
# Needs gnuplot (gnuplot-nox) and python3.
set -euo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build=$(cd "$1" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
tool="$build/tools/patchspin"
plots="${PLOTS:-$build/demos/plots}"
bench="$build/bench-results"
img="$root/docs/img"
for f in "$tool" "$plots"; do
  [[ -x "$f" ]] || { echo "$0: missing executable $f (build it first)" >&2; exit 1; }
done
mkdir -p "$img"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# thin disk of Sect. 6.1/6.3: R = 0.05 m, m = 1 kg, Jz = m R^2 / 2, centre of
# mass in the patch plane, uniform pressure. --scaled: F in mu m g, T in m g R.
disk=(--patch disk:0.05 --mass 1 --inertia 0.00125 --com 0,0,0 --mu 0.3 --scaled --quiet --cycle-seeds 0)

# (1) Fig. 11: F from 0 to 1.5 mu m g at T = 0 (bifurcations at F = 1/9 and 1
# in the paper's ellipsoidal analysis, Sect. 6.1)
for model in ellipsoidal exact; do
  "$tool" sweep "${disk[@]}" --model "$model" --F 0:1.5:151 --out "$work/force_$model.csv"
done
"$plots" force --out "$img/bifurcation_force.png" --size 900x600 \
  --title "thin disk, T = 0: limit directions against F" \
  --force-label "F / ({/Symbol m} m g)" \
  --panel "ellipsoidal=$work/force_ellipsoidal.csv" --panel "exact=$work/force_exact.csv"

# (2) Fig. 13: the (F, T) plane; T up to 0.3 m g R, beyond the no-tipping
# bound |T| <= m g R / 4 of Sect. 6.3 (tipping points are marked)
for model in ellipsoidal exact; do
  "$tool" sweep "${disk[@]}" --model "$model" --F 0:1.2:41 --T 0:0.3:31 --out "$work/plane_$model.csv"
done
"$plots" plane --out "$img/bifurcation_plane.png" --size 900x600 \
  --title "thin disk with torque: limit directions over (F, T)" \
  --force-label "F / ({/Symbol m} m g)" --torque-label "T / (m g R)" \
  --panel "ellipsoidal=$work/plane_ellipsoidal.csv" --panel "exact=$work/plane_exact.csv"

# (2b) issue 34's thick disk (R = 1 m, centre of mass 0.4 m up, mu = 0.5,
# Jz = 0.5 kg m^2): under the exact law a limit cycle around each pole for
# 0 < F < 0.1345 mu m g, which dies in a saddle-node on the cycle
# (docs/notes/2026-11-28-thick-disk-cycle-bifurcation.md)
thick=(--patch disk:1 --mass 1 --inertia 0.5 --com 0,0,0.4 --mu 0.5 --scaled --quiet)
for model in ellipsoidal exact; do
  "$tool" sweep "${thick[@]}" --model "$model" --F 0:0.4:41 --out "$work/thick_$model.csv" >/dev/null
done
"$plots" force --out "$img/thick_disk_cycles.png" --size 900x500 --component 3 \
  --title "thick disk (R = 1 m, h = 0.4 m): limit directions and cycles against F" \
  --force-label "F / ({/Symbol m} m g)" \
  --panel "ellipsoidal=$work/thick_ellipsoidal.csv" --panel "exact=$work/thick_exact.csv"

# (3) Pareto: the benchmarks that report max_rel_err (the accuracy knob of the
# exact law) -> model,time,error,label with time per evaluation in seconds
python3 - "$bench" "$work/pareto.csv" <<'EOF'
import json, re, sys
bench, out = sys.argv[1], sys.argv[2]
scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
rows = []
for name in ("bench_exact_disk", "bench_exact_polygon"):
    with open(f"{bench}/{name}.json") as f:
        data = json.load(f)
    for b in data["benchmarks"]:
        if b.get("run_type") != "iteration" or "max_rel_err" not in b:
            continue
        t = b["real_time"] * scale[b["time_unit"]]
        if name == "bench_exact_disk":
            # BM_ExactDiskBasisTol/<-log10 tol>
            model, tol = "exact disk", int(b["name"].rsplit("/", 1)[1])
        else:
            # BM_ExactPolygonBasisFarBranch/octagon:k/jacobian:j/tol_exp:n
            args = dict(kv.split(":") for kv in b["name"].split("/")[1:])
            if args["jacobian"] != "0":
                continue
            model = "exact octagon" if args["octagon"] == "1" else "exact rectangle"
            model += " (far branch)"
            tol = int(args["tol_exp"])
        rows.append((model, tol, t, b["max_rel_err"]))
if not rows:
    sys.exit("make_gallery: no benchmark with max_rel_err in " + bench)
with open(out, "w") as f:
    f.write("model,time,error,label\n")
    # per model from loose to tight tolerance, so each line runs along its knob
    for model, tol, t, err in sorted(rows, key=lambda r: (r[0], r[1])):
        f.write(f'"{model}",{t:.6g},{err:.6g},tol 1e-{tol}\n')
EOF
"$plots" pareto --csv "$work/pareto.csv" --out "$img/pareto_exact.png" --size 900x600 \
  --title "exact law: time against error over the tolerance knob" \
  --time-label "time per evaluation (value only) [s]" --error-label "max relative error"

# (4) per patch and per simulation, from the CSVs of bench_patch_error and
# bench_bullet_simulation (docs/bench/, committed with the tables of docs/benchmarks.md)
csv="$root/docs/bench"
"$plots" pareto-patch --csv "$csv/patch_error.csv" --out "$img/pareto_patch.png" --size 900x600 \
  --title "per patch: friction-block solve (disk, rectangle, hexagon pooled)"
"$plots" pareto-sim --csv "$csv/simulation_error.csv" --scene "coin from 1" --out "$img/pareto_sim_coin.png" \
  --size 900x700 --title "free coin started at v = R omega"
"$plots" pareto-sim --csv "$csv/simulation_error.csv" --scene "coin from 0.653" \
  --out "$img/pareto_sim_coin_limit.png" --size 900x700 --title "free coin started on the limit ratio 0.653"
"$plots" pareto-sim --csv "$csv/simulation_error.csv" --scene "pushed disk" --out "$img/pareto_sim_pushed.png" \
  --size 900x700 --title "pushed disk, Sect. 6.1 Case 3"

made=(bifurcation_force bifurcation_plane thick_disk_cycles pareto_exact pareto_patch pareto_sim_coin pareto_sim_coin_limit
  pareto_sim_pushed)
if [[ "${KEEP_GP:-0}" != 1 ]]; then
  for f in "${made[@]}"; do rm -f "$img/$f.gp"; done
fi
echo "make_gallery: wrote $(printf "$img/%s.png " "${made[@]}")"
