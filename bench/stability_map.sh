#!/usr/bin/env bash
# Stability map of the Oldroyd-B scheme (issue 6, point 2; docs/evidence/stability.md, "Stability map"):
# which combinations of Deborah number, time step and mesh survive on four demanding cases (one of
# them with two viscosity splittings), and
# how the others fail; each in every representation of the conformation tensor that
# REPRESENTATIONS lists (fluid.conformation: standard, log, sqrt; issue 17, point 4).
# Every run uses the wave-like advection and one thread; JOBS run at a time.
#   cross  cases/verification/stability_cross_slot.toml: planar extension at a stagnation point,
#          eps = 1, so Wi = lambda (Oldroyd-B's stress there is unbounded for Wi > 1/2); to t = 6.
#   disk   paper 5.1b: one disk (rho_p = 1.02) settling in the 1.5 x 6 channel, to t = 0.5;
#          De = lambda U / D with U = 1.39 (our terminal speed at lambda = 0.3, docs/evidence/validation_paper.md).
#   pair   paper 5.2: two disks in the 2 x 8 box (eta = 0.12), to t = 2;
#          De = lambda U / D with U = 0.39 (our mean fall speed at lambda = 1.4).
#   wk     start-up Poiseuille (cases/verification/waters_king.toml: beta = 1/9, all the viscosity in
#          step (33), alpha = 1, beta = 0), to t = 10; De = E = lambda eta / (rho H^2) = lambda.
#   wkhalf the same flow with the viscosity split alpha = beta = 1/2.
#   diskpaper, pairpaper  disk and pair under the paper's coupling of the constraint
#          (splitting.constraint = paper, alpha = beta = 1/2; the default is incremental, alpha = 1,
#          beta = 0: docs/evidence/stability.md, "The coupling of the constraint"), standard representation.
# For each family: 2 meshes x 4-5 time steps x 3-6 relaxation times, reaching time steps far beyond
# the paper's; the particle mesh follows the velocity mesh (h_p = h 96/70, the paper's ratio).
# Output: docs/stability/map.csv (one row per run: outcome, steps, extremes of trA and eig A, the
# reason, the final particle heights), a Markdown table on stdout, and
# docs/figures/stability_<family>_h<cells>[_<representation>].png (no suffix for standard): De
# against dt on one mesh, one point per run, one series per outcome (completed, or the kind of
# failure).
#   bench/stability_map.sh            # SOLVE=build/solver/dlmfd-solve DLMFD=build/client/dlmfd
#                                     # WORK=runs/stability_map JOBS=2 ONLY=<grep -E on run names>
#                                     # REPRESENTATIONS="standard log sqrt"
# Runs whose summary.json exists in WORK are not run again (a second call only redraws).
set -euo pipefail
cd "$(dirname "$0")/.."
SOLVE=$(realpath "${SOLVE:-build/solver/dlmfd-solve}")
DLMFD=${DLMFD:-build/client/dlmfd}
WORK=${WORK:-runs/stability_map}
JOBS=${JOBS:-2}
REPRESENTATIONS=${REPRESENTATIONS:-standard log sqrt}
DATA=docs/stability
mkdir -p "$WORK" "$DATA" docs/figures

# family|scene|De per unit lambda|end time|meshes h|time steps|relaxation times|extra overrides
FAMILIES=(
  "cross|cases/verification/stability_cross_slot.toml|1|6|0.0625 0.03125|0.01 0.03 0.1 0.3|0.3 1 3 10 30 100|"
  "disk|cases/paper/5.1b_disk_rho1.02_lambda0.3.toml|6.95|0.5|0.041666666666666664 0.020833333333333332|0.001 0.004 0.016 0.064|0.3 1 3 10 30 100|"
  "pair|cases/paper/5.2_pair_oldroyd_b.toml|1.95|2|0.041666666666666664 0.020833333333333332|0.0004 0.0032 0.0256 0.1|1.4 14 140|"
  "wk|cases/verification/waters_king.toml|1|10|0.03125 0.015625|0.005 0.01 0.02 0.04 0.08|1 3 10|"
  "wkhalf|cases/verification/waters_king.toml|1|10|0.03125 0.015625|0.005 0.01 0.02 0.04 0.08|1 3 10|--set splitting.alpha=0.5 --set splitting.beta=0.5"
  "diskpaper|cases/paper/5.1b_disk_rho1.02_lambda0.3.toml|6.95|0.5|0.041666666666666664 0.020833333333333332|0.001 0.004 0.016 0.064|0.3 1 3 10 30 100|--set splitting.constraint=paper"
  "pairpaper|cases/paper/5.2_pair_oldroyd_b.toml|1.95|2|0.041666666666666664 0.020833333333333332|0.0004 0.0032 0.0256 0.1|1.4 14 140|--set splitting.constraint=paper"
)

# name|family|scene|h|dt|lambda|De|representation|overrides (standard runs keep their names)
for family in "${FAMILIES[@]}"; do
  IFS='|' read -r fam scene de_per_lambda end hs dts lams extra <<< "$family"
  for rep in $REPRESENTATIONS; do
    # The families under the paper's coupling only compare couplings: the standard representation.
    case $fam in *paper) [ "$rep" = standard ] || continue ;; esac
    suffix=""
    [ "$rep" = standard ] || suffix="_$rep"
    for h in $hs; do
      for dt in $dts; do
        for lam in $lams; do
          cells=$(awk -v h="$h" 'BEGIN { printf "%d", 1 / h + 0.5 }')
          hp=$(awk -v h="$h" 'BEGIN { printf "%.12g", h * 96 / 70 }')
          de=$(awk -v l="$lam" -v k="$de_per_lambda" 'BEGIN { printf "%.4g", l * k }')
          sets="--set splitting.advection=wave --set domain.h=$h --set time.dt=$dt --set time.end=$end"
          sets+=" --set fluid.relaxation_time=$lam --set fluid.conformation=$rep"
          sets+=" --set output.fields_every=0 --set output.checkpoint_every=0 $extra"
          case $fam in
            disk* | pair*) sets+=" --set particle_mesh.h=$hp" ;;
            wk*) sets+=" --set domain.size=[$(awk -v h="$h" 'BEGIN { printf "%.10g", 4 * h }'),2.0]" ;;
          esac
          echo "${fam}_c${cells}_dt${dt}_lambda${lam}${suffix}|$fam|$scene|$h|$dt|$lam|$de|$rep|$sets"
        done
      done
    done
  done
done | grep -E -- "${ONLY:-.}" > "$WORK/runs.txt"

run_one() {
  local name family scene h dt lam de rep sets
  IFS='|' read -r name family scene h dt lam de rep sets <<< "$1"
  [ -f "$WORK/$name/summary.json" ] && return 0
  rm -rf "${WORK:?}/${name:?}"
  # shellcheck disable=SC2086  # sets is a list of flags
  "$SOLVE" "$scene" --out "$WORK/$name" --threads 1 --quiet $sets > "$WORK/$name.log" 2>&1 || true
  echo "done $name" >&2
}
export -f run_one
export SOLVE WORK
# shellcheck disable=SC2016  # $1 expands in the child bash
tr '\n' '\0' < "$WORK/runs.txt" | OMP_WAIT_POLICY=passive xargs -0 -P "$JOBS" -I{} bash -c 'run_one "$1"' _ {}

rm -f "$DATA"/*_chart.csv
python3 - "$WORK" "$DATA" <<'PY'
import csv, json, math, os, sys
work, data = sys.argv[1], sys.argv[2]

def outcome(summary):
    if summary is None:
        return 'no summary'
    if summary.get('status') == 'completed':
        return 'completed'
    r = summary.get('reason', '').lower()
    for key, kind in (('positive definite', 'A not SPD'), ('not converged', 'solver not converged'),
                      ('breakdown', 'solver not converged'), ('blow-up', 'NaN'), ('not finite', 'NaN'),
                      ('overlap', 'overlap'),
                      ('would need more than', 'velocity blow-up'), ('crosses the', 'particle blow-up')):
        if key in r:
            return 'failed: ' + kind
    return 'failed: other'

rows = []
for line in open(os.path.join(work, 'runs.txt')):
    name, family, scene, h, dt, lam, de, rep, _ = line.rstrip('\n').split('|')
    d = os.path.join(work, name)
    try:
        s = json.load(open(os.path.join(d, 'summary.json')))
    except (OSError, ValueError):
        s = None
    max_tr, min_eig = 0.0, math.inf
    try:
        for r in csv.DictReader(open(os.path.join(d, 'diagnostics.csv'))):
            for k, f in (('max_trA', max), ('min_eig_A', min)):
                try:
                    v = float(r[k])
                except (KeyError, ValueError):
                    continue
                if k == 'max_trA':
                    max_tr = max(max_tr, v)
                else:
                    min_eig = min(min_eig, v)
    except OSError:
        pass
    heights = ' '.join(f"{p['position'][1]:.5f}" if p['position'][1] is not None else 'nan'
                       for p in (s or {}).get('particles', []))
    rows.append({'family': family, 'conformation': rep, 'cells': round(1 / float(h)), 'h': h, 'dt': dt,
                 'lambda': lam, 'De': de, 'outcome': outcome(s), 'steps': s['steps'] if s else '',
                 'time': s['time'] if s else '', 'end_time': s['end_time'] if s else '',
                 'max_trA': f'{max_tr:.4g}', 'min_eig_A': f'{min_eig:.3g}' if math.isfinite(min_eig) else '',
                 'y_final': heights, 'reason': (s or {}).get('reason', '')})
fields = list(rows[0].keys())
with open(os.path.join(data, 'map.csv'), 'w', newline='') as f:
    w = csv.DictWriter(f, fieldnames=fields)
    w.writeheader()
    w.writerows(rows)
# One CSV per family, mesh and representation for the charts: one series per outcome.
for family, cells, rep in sorted({(r['family'], r['cells'], r['conformation']) for r in rows}):
    suffix = '' if rep == 'standard' else '_' + rep
    with open(os.path.join(data, f'{family}_h{cells}{suffix}_chart.csv'), 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['outcome', 'dt', 'De'])
        for r in rows:
            if (r['family'], r['cells'], r['conformation']) == (family, cells, rep):
                w.writerow([r['outcome'], r['dt'], r['De']])
print('| family | representation | h | dt | lambda | De | outcome | steps | t reached | max trA | min eig A | reason |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|')
for r in rows:
    reason = r['reason'].replace('|', '/')
    if len(reason) > 160:
        reason = reason[:157] + '...'
    print(f"| {r['family']} | {r['conformation']} | 1/{r['cells']} | {r['dt']} | {r['lambda']} | {r['De']} | "
          f"{r['outcome']} | {r['steps']} | {r['time']} | {r['max_trA']} | {r['min_eig_A']} | {reason} |")

# Per family and representation: outcomes, and where the standard run and this one both completed,
# how far apart they end: the largest relative difference of max trA and of the final particle
# heights (in units of the particle diameter 0.2 of the disk and pair scenes).
print()
print('| family | representation | runs | completed | both completed with standard | max trA: largest relative '
      'difference | final heights: largest difference / D | min eig A: smallest |')
print('|---|---|---|---|---|---|---|---|')
key = lambda r: (r['family'], r['cells'], r['dt'], r['lambda'])
standard = {key(r): r for r in rows if r['conformation'] == 'standard'}
for family in dict.fromkeys(r['family'] for r in rows):
    for rep in dict.fromkeys(r['conformation'] for r in rows):
        mine = [r for r in rows if (r['family'], r['conformation']) == (family, rep)]
        if not mine:
            continue
        done = [r for r in mine if r['outcome'] == 'completed']
        pairs = [(r, standard[key(r)]) for r in done
                 if key(r) in standard and standard[key(r)]['outcome'] == 'completed']
        dtr = max((abs(float(r['max_trA']) / float(q['max_trA']) - 1) for r, q in pairs), default=0.0)
        dy = max((abs(float(a) - float(b)) / 0.2 for r, q in pairs
                  for a, b in zip(r['y_final'].split(), q['y_final'].split())), default=0.0)
        eig = min((float(r['min_eig_A']) for r in done if r['min_eig_A']), default=math.nan)
        print(f'| {family} | {rep} | {len(mine)} | {len(done)} | {len(pairs)} | {dtr:.3g} | '
              f"{dy:.3g} | {eig:.3g} |")
PY

rm -f docs/figures/stability_*.png
for chart in "$DATA"/*_chart.csv; do
  stem=$(basename "$chart" _chart.csv)  # FAMILY_hCELLS or FAMILY_hCELLS_REPRESENTATION
  family=${stem%%_h*}
  rest=${stem#*_h}
  cells=${rest%%_*}
  rep=standard
  [ "$rest" = "$cells" ] || rep=${rest#*_}
  "$DLMFD" chart --csv "$chart" --xcol dt --ycol De --group outcome --points --logx --logy \
    --title "stability map: $family, h = 1/$cells, $rep" --width 800 --height 560 \
    -o "docs/figures/stability_$stem.png" >/dev/null
done
echo "wrote $DATA/map.csv and docs/figures/stability_<family>_h<cells>[_<representation>].png" >&2
