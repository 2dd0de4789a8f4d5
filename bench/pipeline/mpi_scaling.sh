#!/usr/bin/env bash
# mpirun -np 2 against one process on the default film (issue 13): the mesh and render stages'
# own wall times (as thaw run reports them: process start-up and MPI's initialisation excluded)
# in three configurations, interleaved run by run so that each sees the same load:
#   A  1 process x 1 thread      (1 core)
#   B  mpirun --bind-to none -np 2, 1 thread per rank (2 cores; Open MPI would pin each rank to
#      one core, which on a machine shared with other work leaves a rank on the busier core while
#      A and C move to whichever core is free: unbound, all three meet the same scheduler)
#   C  1 process x 2 threads     (2 cores, OpenMP)
# Parallel efficiency (the figure issue 13 asks for) = A / (2 B): the speed-up of 2 ranks over one
# process on one core, per core. B against C compares MPI with OpenMP on the same 2 cores.
# Efficiencies are given from the minima (the runs least disturbed by other work on a shared
# machine) and from the medians; CPU time (user + sys of every process) shows the overhead.
# Simulate is done once up front; each configuration re-meshes a copy of that folder, then
# renders the frames asked for (all, or e.g. --frames 0:51:4) into a copy of the meshed folder.
# Meshes and frames are checked byte-identical between A, B and C.
# Load-independent estimates (a loaded machine's wall times measure the load): the render stage's
# from the frames' CPU seconds, the mesh stage's from its farm phases' CPU seconds per rank
# (run_items/mesh/costs_rank_NNN): on an idle machine a phase lasts about as long as its busiest
# rank's CPU, so T_B ~ sum over phases of the max over ranks, T_A ~ the sum of A's phases.
# Usage: [SCENARIO=file.toml] [RUNS=3] [SKIP_RENDER=1] [CONFIGS="A B C"] bench/pipeline/mpi_scaling.sh
#        [BUILD_DIR] [extra thaw run args for the render stage, e.g. --frames 0:51:4]
# Idle-machine figures for issue 13 (1 process x 1 thread against 2 ranks x 1 thread, the whole
# default film, median of 5; about 9 minutes on the 2-core VM, ~100 s a run; nothing else may run):
#   RUNS=5 CONFIGS="A B" bench/pipeline/mpi_scaling.sh build
set -euo pipefail
build=${1:-build}
shift || true
thaw=$(realpath "$build/thaw")
work=$(mktemp -d /tmp/thaw_mpi_bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u +%H:%M) UTC)"
awk '$1 > 0.5 { print "WARNING: load " $1 " above 0.5: the wall-time efficiencies will measure the" \
  " load; the CPU-second estimates still hold" }' /proc/loadavg
scenario=()
[ -n "${SCENARIO:-}" ] && scenario=("$(realpath "$SCENARIO")")
echo "scenario: ${SCENARIO:-built-in default}"
"$thaw" run ${scenario[@]+"${scenario[@]}"} --out "$work/base" --stage simulate -q
extra=("$@")

# A stage's own time from thaw run's summary ("  mesh      1.23 s" or "  render    2 min 05 s");
# the mesh stage's from run_items/mesh/stage_s (seconds to 0.1 ms) where thaw writes it.
stage_seconds() {  # stage log
  awk -v s="$1" '$1 == s { if ($3 == "min") print $2 * 60 + $4; else print $2 }' "$2"
}
launcher() {  # A | B | C: the command prefix and the threads per process
  case $1 in
    A) echo "1" ;;
    B) echo "1 mpirun --bind-to none -np 2" ;;
    C) echo "2" ;;
  esac
}
stage() {  # config stage from_dir: runs one stage into $work/$config; prints "seconds cpu"
  local config=$1 name=$2 from=$3 threads cmd
  read -r threads cmd <<< "$(launcher "$config")"
  rm -rf "$work/$config"; cp -r "$from" "$work/$config"
  [ "$name" = mesh ] && rm -rf "$work/$config/sim/mesh"
  local args=()
  [ "$name" = render ] && args=(${extra[@]+"${extra[@]}"})
  # shellcheck disable=SC2086
  /usr/bin/time -f "%U %S" -o "$work/$config.time" $cmd "$thaw" run \
    ${scenario[@]+"${scenario[@]}"} --out "$work/$config" --stage "$name" -j "$threads" \
    ${args[@]+"${args[@]}"} > "$work/$config.log" 2>&1
  read -r user sys < "$work/$config.time"
  local seconds
  seconds=$(stage_seconds "$name" "$work/$config.log")
  # The mesh stage (~0.1 s) to 0.1 ms from the leader's note rather than the summary's 2 decimals.
  [ -f "$work/$config/run_items/$name/stage_s" ] && seconds=$(cat "$work/$config/run_items/$name/stage_s")
  echo "$seconds $(echo "$user + $sys" | bc)"
}
same() {  # dir1 dir2: byte-identical or the benchmark stops
  diff -r -q "$1" "$2" > /dev/null || { echo "MISMATCH between $1 and $2"; exit 1; }
}
# The mesh stage's critical path from its farm phases' CPU seconds (costs_rank_NNN lines "farm K
# items N cpu_s X wall_s W work_cpu_s C; ..."): sum over phases of the busiest rank's CPU in its
# items (C; the ranks' waiting and polling, which grow with the load, left out).
mesh_critical_cpu() {  # folder
  cat "$1/run_items/mesh/"costs_rank_* | tr ';' '\n' |
    awk '{ k = $2; if ($10 > m[k]) m[k] = $10 } END { for (k in m) s += m[k]; printf "%.4f", s }'
}
read -r -a configs <<< "${CONFIGS:-A B C}"
declare -A t
runs=${RUNS:-3}
for i in $(seq "$runs"); do
  for c in "${configs[@]}"; do
    t[mesh,$c]+="$(stage $c mesh "$work/base");"; rm -rf "$work/mesh_$c"; mv "$work/$c" "$work/mesh_$c"
    t[meshcp,$c]+="$(mesh_critical_cpu "$work/mesh_$c");"
  done
  for c in "${configs[@]}"; do same "$work/mesh_A/sim/mesh" "$work/mesh_$c/sim/mesh"; done
  if [ -z "${SKIP_RENDER:-}" ]; then
    for c in "${configs[@]}"; do t[render,$c]+="$(stage $c render "$work/mesh_A");"; done
    for c in "${configs[@]}"; do same "$work/A/frames" "$work/$c/frames"; done
  fi
  echo "run $i of $runs done, load $(cut -d' ' -f1 /proc/loadavg)"
done
grep -o '"distinct_meshes": [0-9]*' "$work/mesh_A/sim/mesh/manifest.json"
frames=0
[ -z "${SKIP_RENDER:-}" ] && frames=$(ls "$work/A/frames/"*.png | wc -l) && echo "frames rendered per run: $frames"

column() {  # key field(1 wall, 2 cpu) -> one value a line
  tr ';' '\n' <<< "${t[$1]}" | awk -v f="$2" 'NF { print $f }'
}
stat() {  # min | median of stdin
  sort -g | awk -v w="$1" '{ a[NR] = $1 } END { print (w == "min") ? a[1] : a[int((NR + 1) / 2)] }'
}
ratio() { echo "scale=3; $1" | bc; }
stages=(mesh)
[ -z "${SKIP_RENDER:-}" ] && stages+=(render)
declare -A v
for s in "${stages[@]}"; do
  echo "== $s stage (wall s as thaw reports it, the mesh stage to 0.1 ms; CPU s of all processes incl. start-up)"
  for c in "${configs[@]}"; do
    v[$s,$c,min]=$(column "$s,$c" 1 | stat min); v[$s,$c,med]=$(column "$s,$c" 1 | stat median)
    printf '  %s wall: %s (min %s, median %s); CPU median %s\n' "$c" \
      "$(column "$s,$c" 1 | xargs)" "${v[$s,$c,min]}" "${v[$s,$c,med]}" "$(column "$s,$c" 2 | stat median)"
  done
  for w in min med; do
    line="  $w: efficiency A / (2 B) = $(ratio "${v[$s,A,$w]} / (2 * ${v[$s,B,$w]})")"
    [ -n "${v[$s,C,$w]:-}" ] &&
      line+="; C / B (MPI vs OpenMP, same 2 cores, > 1: MPI faster) = $(ratio "${v[$s,C,$w]} / ${v[$s,B,$w]}")"
    echo "$line"
  done
done
# The mesh stage on an idle machine, from CPU seconds: A's farm phases (1 core) against B's
# critical path (each phase as long as its busiest rank).
# Per run (A and B back to back, under the same load) and over the runs' medians and minima.
mesh_a=$(column "meshcp,A" 1 | stat median); mesh_b=$(column "meshcp,B" 1 | stat median)
per_run=$(paste -d' ' <(column "meshcp,A" 1) <(column "meshcp,B" 1) |
  awk '{ printf "%.3f\n", $1 / (2 * $2) }')
echo "mesh, idle-machine estimate from CPU seconds: A's phases per run $(column "meshcp,A" 1 | xargs) s;" \
  "B's critical path per run $(column "meshcp,B" 1 | xargs) s"
echo "  efficiency per run $(xargs <<< "$per_run"): median $(stat median <<< "$per_run");" \
  "from the medians $(ratio "$mesh_a / (2 * $mesh_b)"), from the minima" \
  "$(ratio "$(column "meshcp,A" 1 | stat min) / (2 * $(column "meshcp,B" 1 | stat min))")"
if [ -z "${SKIP_RENDER:-}" ]; then
  # Per-frame costs (the scaling model's c_mean and c_max) from the frames' item notes
  # (run_items/render/frame_NNNNNN, second line "rank R wall_s W cpu_s C"), last run.
  notes() { tail -q -n 1 "$work/$1/run_items/render/"frame_*; }
  echo "per-frame CPU s, A (1 thread), last run: $(notes A | awk '{ s += $6; if ($6 > m) m = $6; if (!n++ || $6 < l) l = $6 } END { printf "mean %.3f, min %.3f, max %.3f, max/mean %.2f", s / n, l, m, m * n / s }')"
  echo "B's split, last run: $(notes B | awk '{ f[$2]++; c[$2] += $6 } END { for (r in f) printf "rank %s: %d frames, %.2f s CPU; ", r, f[r], c[r] }')"
  # The load-independent estimate of B's efficiency on an idle machine, from CPU seconds only:
  # the work B adds to the frames (sum of A's frame CPU / sum of B's), times the balance of a
  # dynamic hand-out of A's frame costs, in frame order, to 2 ranks (list scheduling: each frame
  # to the rank free first; sum / (2 x the later rank's finish)).
  added=$(ratio "$(notes A | awk '{ s += $6 } END { print s }') / $(notes B | awk '{ s += $6 } END { print s }')")
  balance=$(notes A | awk '{ if (t0 <= t1) t0 += $6; else t1 += $6; s += $6 } END { printf "%.3f", s / (2 * (t0 > t1 ? t0 : t1)) }')
  echo "render, idle-machine estimate from CPU seconds: work A/B $added x balance $balance = $(ratio "$added * $balance")"
  for w in min med; do
    echo "mesh + render, $w: efficiency A / (2 B) = $(ratio "(${v[mesh,A,$w]} + ${v[render,A,$w]}) / (2 * (${v[mesh,B,$w]} + ${v[render,B,$w]}))")"
  done
fi
echo "== issue 13 (target 0.85): wall-time efficiency A / (2 B), median of $runs runs (valid on an idle machine only)"
for s in "${stages[@]}"; do
  echo "  $s: A ${v[$s,A,med]} s, B ${v[$s,B,med]} s, efficiency $(ratio "${v[$s,A,med]} / (2 * ${v[$s,B,med]})")"
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -u +%H:%M) UTC)"
