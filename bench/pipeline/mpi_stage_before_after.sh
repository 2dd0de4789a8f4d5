#!/usr/bin/env bash
# The 2-rank parallel efficiency of the mesh stage (issue 13: >= 0.85) or the inspect stage, two
# builds in ONE run: for each build, A (1 process x 1 thread) and B (mpirun --bind-to none -np 2,
# 1 thread per rank), run by run interleaved (old A, old B, new A, new B; the order rotated each
# run) so that all four see the same load. Per configuration the stage's wall seconds as thaw
# times it (the leader's clock from the stage's start to every rank agreeing it is done; process
# start-up and MPI_Init are before it): the mesh stage's from run_items/mesh/stage_s (0.1 ms), the
# inspect stage's from thaw's summary (10 ms). For the mesh stage also the CPU seconds of the farm
# phases' items (run_items/mesh/costs_rank_NNN: what the work cost inside each rank, whatever the
# waiting). Efficiency = A / (2 B) from the median wall times, and (mesh) from the CPU records
# (the surfaces' items: A's against the busiest rank's; bench/pipeline/mpi_scaling.sh explains
# that estimate). The stage's outputs of all four are checked byte-identical.
# Usage: [STAGE=mesh|inspect] [RUNS=9] bench/pipeline/mpi_stage_before_after.sh OLD_BUILD NEW_BUILD
set -euo pipefail
old=$(realpath "${1:?old build dir}")
new=$(realpath "${2:?new build dir}")
runs=${RUNS:-9}
stage=${STAGE:-mesh}
work=$(mktemp -d /tmp/thaw_stage_ba.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u +%H:%M) UTC); stage: $stage"
"$new/thaw" run --out "$work/base" --stage simulate -q
[ "$stage" = inspect ] && "$new/thaw" run --out "$work/base" --stage mesh -q

# The surfaces' farm phase (the last: a build whose ranks each make the geodesic form farm no
# forms) and its busiest rank's item CPU seconds.
critical_cpu() {  # folder
  [ "$stage" = mesh ] || { echo 0; return; }
  cat "$1/run_items/mesh/"costs_rank_* | tr ';' '\n' |
    awk '{ if ($2 > k) { k = $2; m = 0 } if ($2 == k && $10 > m) m = $10 } END { printf "%.4f", m }'
}
# The surfaces' CPU per item over all ranks [ms] (a build that records items_here; else 0): what
# a surface costs in that configuration, whatever the balance between the ranks.
item_ms() {  # folder
  [ "$stage" = mesh ] || { echo 0; return; }
  cat "$1/run_items/mesh/"costs_rank_* | tr ';' '\n' |
    awk '{ if ($2 > k) { k = $2; c = 0; n = 0 } if ($2 == k) { c += $10; n += $12 } }
         END { printf "%.3f", (n > 0 ? 1000 * c / n : 0) }'
}
wall() {  # folder log: the stage's wall seconds
  if [ "$stage" = mesh ]; then cat "$1/run_items/mesh/stage_s"; else awk -v s="$stage" '$1 == s { print $2 }' "$2"; fi
}
outputs() {  # folder: the stage's outputs
  if [ "$stage" = mesh ]; then echo "$1/sim/mesh"; else echo "$1/meshes_vtp $1/meshes.pvd $1/handoff $1/plot.png"; fi
}
one() {  # build config(A|B) name: one stage; appends "wall cpu" to $work/NAME.txt
  local build=$1 config=$2 name=$3 pre=()
  [ "$config" = B ] && pre=(mpirun --bind-to none -np 2)
  rm -rf "$work/$name"
  cp -r "$work/base" "$work/$name"
  [ "$stage" = mesh ] && rm -rf "$work/$name/sim/mesh"
  "${pre[@]}" "$build/thaw" run --out "$work/$name" --stage "$stage" -j 1 > "$work/$name.log" 2>&1
  echo "$(wall "$work/$name" "$work/$name.log") $(critical_cpu "$work/$name") $(item_ms "$work/$name")" \
    >> "$work/$name.txt"
}
names=(old_A old_B new_A new_B)
for i in $(seq "$runs"); do
  for k in 0 1 2 3; do
    name=${names[$(((k + i) % 4))]}
    build=$old
    [ "${name%_*}" = new ] && build=$new
    one "$build" "${name#*_}" "$name"
  done
  for name in old_B new_A new_B; do
    read -r -a a <<< "$(outputs "$work/old_A")"
    read -r -a b <<< "$(outputs "$work/$name")"
    for j in "${!a[@]}"; do
      diff -r -q "${a[$j]}" "${b[$j]}" > /dev/null ||
        { echo "MISMATCH: $name's ${b[$j]} differs from old_A's"; exit 1; }
    done
  done
done
median() { sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }
col() { awk -v f="$2" '{ print $f }' "$work/$1.txt"; }
echo "$stage outputs byte-identical in all $runs runs (old and new, 1 process and 2 ranks)"
for name in "${names[@]}"; do
  line="$name wall s: $(col "$name" 1 | xargs) (median $(col "$name" 1 | median))"
  [ "$stage" = mesh ] && line+="; surfaces item CPU s (B: busiest rank): median $(col "$name" 2 | median), per surface $(col "$name" 3 | median) ms"
  echo "$line"
done
for b in old new; do
  line="$b: efficiency A / (2 B) from the median wall $(echo "scale=3; $(col "${b}_A" 1 | median) / (2 * $(col "${b}_B" 1 | median))" | bc)"
  [ "$stage" = mesh ] &&
    line+=", from the median item CPU $(echo "scale=3; $(col "${b}_A" 2 | median) / (2 * $(col "${b}_B" 2 | median))" | bc)"
  echo "$line"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u +%H:%M) UTC)"
