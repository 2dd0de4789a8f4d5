#!/usr/bin/env bash
# mpirun -np 2 against one process on the default film (issue 13): wall time of the mesh and render
# stages in fair pairings on a 2-core machine, and per-frame costs for the scaling model in
# docs/benchmarks.md.
#   A  1 process x 1 thread           vs  B  2 ranks x 1 thread   (1 core vs 2 cores: efficiency)
#   C  1 process x 2 threads          vs  B                        (same 2 cores: MPI vs OpenMP)
# Simulate is done once up front (rank 0 alone); the mesh stage is then re-done from that folder
# by A and B (MESH_RUNS times each, alternating: the stage's own time as thaw reports it, without
# the process start-up), and every configuration renders the same frames into a copy of the
# meshed folder. The load of the machine (other engineers compiling) is printed before and
# after: compare ratios of one run.
# Usage: [SCENARIO=file.toml] [MESH_RUNS=5] [SKIP_RENDER=1] bench/pipeline/mpi_scaling.sh
#        [BUILD_DIR] [extra thaw run args, e.g. --frames 0:51:2]
set -euo pipefail
build=${1:-build}
shift || true
thaw=$(realpath "$build/thaw")
work=$(mktemp -d /tmp/thaw_mpi_bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
now() { date +%s.%N; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
scenario=()
[ -n "${SCENARIO:-}" ] && scenario=("$(realpath "$SCENARIO")")
echo "scenario: ${SCENARIO:-built-in default}"
t0=$(now); "$thaw" run ${scenario[@]+"${scenario[@]}"} --out "$work/base" --stage simulate -q; t1=$(now)
echo "simulate (serial, rank 0): $(echo "$t1 - $t0" | bc) s"
mesh_stage() {  # name, launcher...: re-meshes a copy of base; prints "stage-seconds cpu-seconds"
  local name=$1; shift
  rm -rf "$work/$name"; cp -r "$work/base" "$work/$name"; rm -rf "$work/$name/sim/mesh"
  /usr/bin/time -f "%U %S" -o "$work/$name.mtime" "$@" "$thaw" run ${scenario[@]+"${scenario[@]}"} \
    --out "$work/$name" --stage mesh -j 1 > "$work/$name.mlog" 2>&1
  read -r user sys < "$work/$name.mtime"
  echo "$(awk '$1 == "mesh" {print $2}' "$work/$name.mlog") $(echo "$user + $sys" | bc)"
}
ma=(); mb=()
for i in $(seq "${MESH_RUNS:-5}"); do
  ma+=("$(mesh_stage MA)"); mb+=("$(mesh_stage MB mpirun -np 2)")
  diff -r -q "$work/MA/sim/mesh" "$work/MB/sim/mesh" >/dev/null || { echo "MESH MISMATCH"; exit 1; }
done
median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
mesh_a=$(printf '%s\n' "${ma[@]}" | cut -d' ' -f1 | median)
mesh_b=$(printf '%s\n' "${mb[@]}" | cut -d' ' -f1 | median)
echo "mesh stage A 1 process x 1 thread: $(printf '%s\n' "${ma[@]}" | cut -d' ' -f1 | xargs) s (median $mesh_a s), CPU $(printf '%s\n' "${ma[@]}" | cut -d' ' -f2 | xargs) s"
echo "mesh stage B mpirun -np 2 x 1    : $(printf '%s\n' "${mb[@]}" | cut -d' ' -f1 | xargs) s (median $mesh_b s), CPU $(printf '%s\n' "${mb[@]}" | cut -d' ' -f2 | xargs) s (byte-identical meshes)"
echo "mesh stage parallel efficiency A / (2 B), medians: $(echo "scale=3; $mesh_a / (2 * $mesh_b)" | bc)"
grep -o '"distinct_meshes": [0-9]*' "$work/MA/sim/mesh/manifest.json"
rm -rf "$work/base/sim/mesh"; mv "$work/MA/sim/mesh" "$work/base/sim/mesh"
cp "$work/MA/run_manifest.json" "$work/base/run_manifest.json"
[ -n "${SKIP_RENDER:-}" ] && { echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"; exit 0; }
frames=$(grep -c "\"step\":" "$work/base/sim/mesh/manifest.json")
render() {  # name, threads, launcher...: renders into a copy of base, prints the wall time
  local name=$1 threads=$2; shift 2
  rm -rf "$work/$name"; cp -r "$work/base" "$work/$name"
  # wall time on stdout; CPU time (user + sys of every process, mpirun's ranks included) to
  # $work/$name.cpu: on a loaded machine the CPU time shows the overhead, the wall time the share
  /usr/bin/time -f "%e %U %S" -o "$work/$name.time" \
    "$@" "$thaw" run ${scenario[@]+"${scenario[@]}"} --out "$work/$name" --stage render -q -j "$threads" ${extra[@]+"${extra[@]}"}
  read -r wall user sys < "$work/$name.time"
  echo "$user + $sys" | bc > "$work/$name.cpu"
  echo "$wall"
}
extra=("$@")
a=$(render A 1)
b=$(render B 1 mpirun -np 2)
c=$(render C 2)
for f in "$work/A/frames/"*.png; do cmp -s "$f" "$work/B/frames/$(basename "$f")" || { echo "MISMATCH $f"; exit 1; }; done
n=$(ls "$work/A/frames/" | wc -l)
t3=$(now); film=yes; "$thaw" run ${scenario[@]+"${scenario[@]}"} --out "$work/A" --stage film -q 2>/dev/null || film=no; t4=$(now)
echo "frames rendered: $n of $frames (byte-identical between A and B)"
echo "render A 1 process x 1 thread : $a s wall, $(cat "$work/A.cpu") s CPU ($(echo "scale=3; $(cat "$work/A.cpu") / $n" | bc) s CPU per frame)"
echo "render B 2 ranks x 1 thread   : $b s wall, $(cat "$work/B.cpu") s CPU"
echo "render C 1 process x 2 threads: $c s wall, $(cat "$work/C.cpu") s CPU"
echo "CPU overhead B/A (MPI, 1.0 = none): $(echo "scale=3; $(cat "$work/B.cpu") / $(cat "$work/A.cpu")" | bc)"
[ $film = yes ] && echo "film encode (rank 0): $(echo "$t4 - $t3" | bc) s"
echo "parallel efficiency B vs A (2 cores vs 1): $(echo "scale=3; $a / (2 * $b)" | bc)"
echo "B vs C on the same 2 cores (C/B, > 1: MPI faster): $(echo "scale=3; $c / $b" | bc)"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
