#!/usr/bin/env bash
# Draws the figures of docs/evidence/validation_paper.md (paper, section 5) from the runs of bench/paper_cases.sh
# (runs/paper/<case>[@advection]) into docs/figures/. A case that has not been run is skipped with
# a message. Usage: bench/paper_figures.sh [DLMFD_BINARY]   (default build/client/dlmfd)
set -uo pipefail
cd "$(dirname "$0")/.."
dlmfd=${1:-build/client/dlmfd}
runs=runs/paper
out=docs/figures
mkdir -p "$out"

have() {  # have RUN...: true when every run has particles.h5
  local r
  for r in "$@"; do
    if [[ ! -f $runs/$r/particles.h5 ]]; then echo "skipped (not run): $r" >&2; return 1; fi
  done
}
chart() { "$dlmfd" chart --width 800 --height 480 "$@" > /dev/null || echo "chart failed: $*" >&2; }
picture() {  # picture RUN STEP FILE [dlmfd plot options]: that step's snapshot with the particles
  local run=$1 step=$2 file=$3
  shift 3
  if [[ -f $runs/$run/fields/snap_$(printf %06d "$step").h5 ]]; then
    "$dlmfd" plot "$runs/$run" --snapshot "$step" --out "$out/$file" --width 400 --height 900 "$@" > /dev/null ||
      echo "plot failed: $run $step" >&2
  else
    echo "skipped (no snapshot at step $step): $run" >&2
  fi
}

# 5.1a, figure 3: the three mesh / time-step runs, Newtonian and lambda = 0.01.
labels=(--label "+ h=1/96 dt=0.001" --label "+++ h=1/96 dt=0.0004" --label "++ h=1/128 dt=0.0004")
for kind in newtonian_disk disk; do
  set3=(5.1a_${kind}_rho1.5_h96_dt1e-3 5.1a_${kind}_rho1.5_h96_dt4e-4 5.1a_${kind}_rho1.5_h128_dt4e-4)
  name=${kind/_disk/}
  [[ $kind == disk ]] && name=oldroyd_b
  if have "${set3[@]}"; then
    for q in u v omega; do
      chart "${set3[@]/#/$runs/}" "${labels[@]}" --y "$q" --title "5.1a $name: $q (figure 3)" \
        -o "$out/5.1a_${name}_$q.png"
    done
    chart "${set3[@]/#/$runs/}" "${labels[@]}" --x x --y y --equal --title "5.1a $name: trajectory" \
      -o "$out/5.1a_${name}_trajectory.png"
  fi
done
# Figures 4-6: trA at t = 0.3 (the speed with arrows for the Newtonian run), close-ups: trA - 2 on
# a log scale (it spans decades near the disk) with ten isovalues, as the paper's figures show.
near=(--window 0,1.7,1.5,4.7)
picture 5.1a_newtonian_disk_rho1.5_h96_dt1e-3 300 5.1a_newtonian_h96_dt1e-3_speed_t0.3.png --quantity speed --arrows 12 "${near[@]}"
picture 5.1a_disk_rho1.5_h96_dt1e-3 300 5.1a_oldroyd_b_h96_dt1e-3_trA_t0.3.png --quantity trA-2 --log --isolines 10 "${near[@]}"
picture 5.1a_disk_rho1.5_h128_dt4e-4 750 5.1a_oldroyd_b_h128_dt4e-4_trA_t0.3.png --quantity trA-2 --log --isolines 10 "${near[@]}"
picture 5.1a_disk_rho1.5_h96_dt4e-4 750 5.1a_oldroyd_b_h96_dt4e-4_trA_t0.3.png --quantity trA-2 --log --isolines 10 "${near[@]}"

# 5.1b, figure 7: rho_p = 1.02, lambda = 0.3, trA at t = 3.1.
if have 5.1b_disk_rho1.02_lambda0.3; then
  chart $runs/5.1b_disk_rho1.02_lambda0.3 --y v --title "5.1b: v" -o "$out/5.1b_v.png"
  picture 5.1b_disk_rho1.02_lambda0.3 7750 5.1b_trA_t3.1.png --quantity trA-2 --log --isolines 10
  picture 5.1b_disk_rho1.02_lambda0.3 7750 5.1b_trA_t3.1_close.png --quantity trA-2 --log --isolines 10 --window 0,0.3,1.5,2.3
fi

# 5.2, figures 8 and 9: the Newtonian and the Oldroyd-B pair.
for r in 5.2_pair_newtonian@wave 5.2_pair_oldroyd_b@wave; do
  name=${r%@*}
  if have "$r"; then
    label=(--label "${name#5.2_pair_} (${r#*@} advection)")
    for q in y u v omega gap; do chart "$runs/$r" "${label[@]}" --y "$q" --title "$name: $q" -o "$out/${name}_$q.png"; done
    chart "$runs/$r" "${label[@]}" --x x --y y --equal --title "$name: trajectories" -o "$out/${name}_trajectory.png"
  fi
done
for t in 0.5 1.5 2.5 5; do
  picture 5.2_pair_newtonian@wave "$(awk -v t=$t 'BEGIN { printf "%d", t / 0.0004 + 0.5 }')" \
    "5.2_pair_newtonian_speed_t$t.png" --quantity speed --arrows 12
done
for t in 0.5 9.5 25; do
  picture 5.2_pair_oldroyd_b@wave "$(awk -v t=$t 'BEGIN { printf "%d", t / 0.0004 + 0.5 }')" "5.2_pair_oldroyd_b_trA_t$t.png" --quantity trA-2 --log --isolines 10
done

# 5.2 from figure 9's caption positions (y = 7.7 and 6.6).
r=5.2_pair_oldroyd_b_caption_start@wave
if have "$r"; then
  for q in y v gap; do chart "$runs/$r" --label "caption start (wave advection)" --y "$q" --title "5.2 Oldroyd-B, caption start: $q" -o "$out/5.2_caption_start_$q.png"; done
fi
picture "$r" 23750 5.2_caption_start_trA_t9.5.png --quantity trA-2 --log --isolines 10

# Single disks in Stokes flow against Faxen's law (5.2 and 5.3c liquids, Newtonian).
if have faxen_disk_w2 faxen_disk_w1; then
  chart $runs/faxen_disk_w2 $runs/faxen_disk_w1 --label "W = 2, eta = 0.12 (Faxen 0.287)" \
    --label "W = 1, eta = 0.1 (Faxen 0.186)" --y v --title "one disk, Newtonian: v" -o "$out/faxen_disk_v.png"
fi

# 5.1b mesh study (wave advection, to t = 2).
if have "5.1b_mesh_h96@wave" "5.1b_mesh_h128@wave"; then
  chart "$runs/5.1b_mesh_h96@wave" "$runs/5.1b_mesh_h128@wave" --label "h = 1/96, h_p = 1/70" \
    --label "h = 1/128, h_p = 1/120" --y v --title "5.1b mesh study: v" -o "$out/5.1b_mesh_v.png"
fi

# 5.3 (figures 10, 11) and 5.4 (figure 12).
for r in 5.3a_eleven_disks@wave 5.3b_eleven_disks_lambda3.5@wave 5.3c_eleven_disks_narrow@wave; do
  name=${r%%_*}
  if have "$r"; then
    chart "$runs/$r" --label "$name" --y y --title "$name: y of the eleven disks" -o "$out/${name}_y.png"
    chart "$runs/$r" --label "$name" --x x --y y --equal --title "$name: trajectories" -o "$out/${name}_trajectory.png"
  fi
done
picture 5.3a_eleven_disks@wave 2500 5.3a_trA_t1.png --quantity trA-2 --log --isolines 10
picture 5.3a_eleven_disks@wave 39000 5.3a_trA_t15.6.png --quantity trA-2 --log --isolines 10
picture 5.3b_eleven_disks_lambda3.5@wave 39000 5.3b_trA_t15.6.png --quantity trA-2 --log --isolines 10
picture 5.3b_eleven_disks_lambda3.5@wave 45500 5.3b_trA_t18.2.png --quantity trA-2 --log --isolines 10  # the last snapshot (t = 18.2)
picture 5.3c_eleven_disks_narrow@wave 52500 5.3c_trA_t21.png --quantity trA-2 --log --isolines 10  # the last snapshot (t = 21.0)
picture 5.4_fluidized_bed_102 5000 5.4_trA_t2.png --quantity trA-2 --log --isolines 10
