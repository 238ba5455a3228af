#!/usr/bin/env bash
# The serial share of each sub-step, counted in instructions (docs/evidence/performance.md, "Threads"):
# for each sub-step of Simulation::Step (SolveStokes (33), AdvectVelocity (34), UpdateConformation
# (35), MoveParticles (36)-(38)) callgrind counts the instructions executed inside it, on one
# thread, and those executed inside OpenMP parallel regions (the inclusive cost of libgomp's
# GOMP_parallel entry points, whose outlined bodies the team shares). The rest runs on one thread
# whatever the team: its share s is the serial fraction of Amdahl's law in instructions,
#   speed-up on T threads <= 1 / (s + (1 - s) / T),
# which the script prints for T = 2 and 16. Instruction counts do not depend on the machine's load
# (a shared machine's timings do), but they weigh a memory-bound copy as little as its
# instructions: the wall-clock speed-up from 1 to 2 threads needs a quiet machine. A region whose
# if clause is false (the multiplier CG and the coupling build below 32 particles,
# MultiplierCg::kParallelParticles) runs on one thread but counts here as parallel. The last two
# columns count the calls into libgomp's region entry (GOMP_parallel) and explicit barriers
# (GOMP_barrier) over the run: each costs a fork and join or a wait on a team, whatever its work
# (bench/machine_ceiling_bench's BM_ForkJoin and BM_Barrier time them).
#
#   bench/serial_fraction.sh SCENE [--set key=value]...   # BUILD=build END=0.002 (time.end) WORK=...
#                                                         # SUBSTEPS="MoveParticles" (default: all)
#   bench/serial_fraction.sh cases/paper/5.2_pair_oldroyd_b.toml --set 'splitting.advection="wave"'
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=${BUILD:-build}
END=${END:-0.002}
WORK=${WORK:-$(mktemp -d /tmp/serial_fraction.XXXXXX)}
SCENE=$1
shift
SOLVER="$BUILD/solver/dlmfd-solve"
mkdir -p "$WORK"

echo "substep,instructions,in_parallel_regions,serial_fraction,amdahl_speedup_2,amdahl_efficiency_16,regions,barriers"
SUBSTEPS=${SUBSTEPS:-SolveStokes AdvectVelocity UpdateConformation MoveParticles}
for sub in $SUBSTEPS; do
  out="$WORK/$sub.callgrind"
  rm -rf "$WORK/run_$sub"
  OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out" \
    --toggle-collect="dlmfd::Simulation::Impl::$sub*" \
    "$SOLVER" "$SCENE" "$@" --out "$WORK/run_$sub" --threads 1 --quiet \
    --set output.fields_every=0 --set output.checkpoint_every=0 \
    --set "time.end=$END" \
    >"$WORK/$sub.log" 2>&1
  # Calls into a function: callgrind's "cfn=(id) name" (the name only at an id's first use), then
  # "calls=N ...".
  counts=$(awk '
    /^c?fn=\(/ { id = $1; sub(/^c?fn=/, "", id); if (NF > 1) names[id] = $2 }
    /^cfn=/ { callee = names[id] }
    /^calls=/ { split($1, c, "="); if (callee == "GOMP_parallel") r += c[2]
                if (callee == "GOMP_barrier") b += c[2]; callee = "" }
    END { printf "%d,%d", r, b }' "$out")
  callgrind_annotate --inclusive=yes --threshold=100 "$out" 2>/dev/null |
    awk -v name="$sub" -v counts="$counts" '
      /PROGRAM TOTALS/ { gsub(",", "", $1); total = $1 }
      /GOMP_parallel/ { v = $1; gsub(",", "", v); par += v }
      END {
        if (total == 0) { printf "%s,0,0,,,,%s\n", name, counts; exit }
        s = (total - par) / total
        sp2 = 1 / (s + (1 - s) / 2); sp16 = 1 / (s + (1 - s) / 16)
        printf "%s,%d,%d,%.4f,%.3f,%.3f,%s\n", name, total, par, s, sp2, sp16 / 16, counts
      }'
done
