#!/usr/bin/env bash
# Stability study of the viscoelastic scheme (docs/evidence/stability.md): how far in Deborah / Weissenberg
# number (and in time step) each case gets, what fails first and how the run reports it.
#   usage: bench/stability_study.sh [DLMFD_SOLVE] [WORK_DIR]
#   DLMFD_SOLVE defaults to build/solver/dlmfd-solve; WORK_DIR to a fresh temporary directory.
#   JOBS (default 2) runs at a time, each with one OpenMP thread; ONLY (a grep -E pattern on the run
#   names, default all) picks a subset, e.g. ONLY='^wk_' .
# Families (each run short: a few hundred steps on a coarse grid):
#   disk   paper 5.1b sedimenting disk at h = 1/48, h_p = 1/35, dt = 1e-3, t <= 0.2, growing lambda;
#          De = lambda |V| / D with the disk's final speed V.
#   cross  cases/verification/stability_cross_slot.toml (planar stagnation flow, eps ~ 1), t <= 3,
#          growing lambda; Wi = lambda eps with the nominal eps = U / (L/2) = 1.
#   wk     cases/verification/waters_king.toml at ny = 128 (h = 1/64), t <= 10, growing dt: the
#          limit of the explicit polymer force in (33); E = 1, beta = 1/9.
# Columns: exit status and summary.json status/reason, steps done, min over the run of min_eig_A,
# max of max_trA, max of the engine's elastic Courant number lambda dt max|L|_F (diagnostics.csv),
# the elastic wave Courant number c dt / h with c = sqrt(eta_p / (rho lambda)), and max CFL.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
SOLVE=$(realpath "${1:-$ROOT/build/solver/dlmfd-solve}")
WORK=${2:-$(mktemp -d /tmp/dlmfd_stability.XXXXXX)}
JOBS=${JOBS:-2}
mkdir -p "$WORK"
echo "dlmfd-solve: $SOLVE   runs in: $WORK" >&2

DISK="$ROOT/cases/paper/5.1b_disk_rho1.02_lambda0.3.toml"
CROSS="$ROOT/cases/verification/stability_cross_slot.toml"
WK="$ROOT/cases/verification/waters_king.toml"
NOOUT="--set output.fields_every=0 --set output.checkpoint_every=0"

# name|scene|overrides
{
  for lam in 0.3 1 3 10 30 100; do
    echo "disk_lambda$lam|$DISK|--set fluid.relaxation_time=$lam --set domain.h=0.020833333333333333 --set particle_mesh.h=0.028571428571428571 --set time.dt=0.001 --set time.end=0.2 $NOOUT"
  done
  for lam in 0.3 1 3 10 30 100; do
    echo "cross_lambda$lam|$CROSS|--set fluid.relaxation_time=$lam --set time.end=3 $NOOUT"
  done
  for dt in 0.005 0.01 0.02 0.04; do
    echo "wk_dt$dt|$WK|--set domain.h=0.015625 --set domain.size=[0.0625,2.0] --set time.dt=$dt --set time.end=10 $NOOUT"
  done
} | grep -E -- "${ONLY:-.}" > "$WORK/runs.txt"

run_one() {
  local line=$1 name scene sets rc
  name=${line%%|*}; line=${line#*|}; scene=${line%%|*}; sets=${line#*|}
  rm -rf "${WORK:?}/${name:?}"
  set +e -f  # -f: the overrides hold brackets, which must not glob
  # shellcheck disable=SC2086
  "$SOLVE" "$scene" --out "$WORK/$name" --threads 1 --quiet $sets 2> "$WORK/$name.log"
  rc=$?
  set -e +f
  echo "$rc" > "$WORK/$name.rc"
  echo "done $name (exit $rc)" >&2
}
export -f run_one
export SOLVE WORK
# shellcheck disable=SC2016  # $1 expands in the child bash
tr '\n' '\0' < "$WORK/runs.txt" | xargs -0 -P "$JOBS" -I{} bash -c 'run_one "$1"' _ {}

python3 - "$WORK" <<'PY'
import csv, json, math, os, sys
work = sys.argv[1]
names = [l.split('|')[0] for l in open(os.path.join(work, 'runs.txt')) if l.strip()]
print('| run | lambda | dt | De/Wi | exit | status | steps | min eig A | max trA | elastic Courant | wave Courant | max CFL | reason |')
print('|---|---|---|---|---|---|---|---|---|---|---|---|---|')
for name in names:
    d = os.path.join(work, name)
    rc = open(d + '.rc').read().strip()
    try:
        s = json.load(open(os.path.join(d, 'summary.json')))
    except (OSError, ValueError):
        print(f'| {name} | | | | {rc} | (no summary) | | | | | | | {open(d + ".log").read().strip()[-200:]} |')
        continue
    scene = open(os.path.join(d, 'scene.toml')).read()
    def key(section, k):
        sec = False
        for line in scene.splitlines():
            t = line.strip()
            if t.startswith('['):
                sec = t == f'[{section}]'
            elif sec and t.startswith(k + ' ') or sec and t.startswith(k + '='):
                return float(t.split('=', 1)[1].split('#')[0])
        raise KeyError(section + '.' + k)
    lam, dt = key('fluid', 'relaxation_time'), key('time', 'dt')
    eta, beta, rho, h = key('fluid', 'viscosity'), key('fluid', 'solvent_ratio'), key('fluid', 'density'), key('domain', 'h')
    wave = math.sqrt((1 - beta) * eta / (rho * lam)) * dt / h
    mins, maxs, courant, cfl = math.inf, 0.0, 0.0, 0.0
    with open(os.path.join(d, 'diagnostics.csv')) as f:
        for row in csv.DictReader(f):
            def val(k):
                try:
                    return float(row[k])
                except (KeyError, ValueError):
                    return math.nan
            if not math.isnan(val('min_eig_A')): mins = min(mins, val('min_eig_A'))
            maxs = max(maxs, val('max_trA')) if not math.isnan(val('max_trA')) else maxs
            courant = max(courant, val('elastic_courant')) if not math.isnan(val('elastic_courant')) else courant
            cfl = max(cfl, val('cfl')) if not math.isnan(val('cfl')) else cfl
    if name.startswith('disk'):
        v = s['particles'][0]['velocity']
        de = f'De {lam * math.hypot(*v) / 0.2:.3g}'
    elif name.startswith('cross'):
        de = f'Wi {lam * 1.0:.3g}'
    else:
        de = f'E {lam * eta / (rho * 1.0):.3g}'
    reason = s.get('reason', '').replace('|', '/')
    print(f'| {name} | {lam:g} | {dt:g} | {de} | {rc} | {s["status"]} | {s["steps"]} | {mins:.3g} | {maxs:.4g} | '
          f'{courant:.3g} | {wave:.3g} | {cfl:.3g} | {reason} |')
PY
