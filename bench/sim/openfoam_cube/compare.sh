#!/usr/bin/env bash
# One run of the cube comparison (docs/benchmarks.md): OpenFOAM's buoyantBoussinesqPimpleFoam
# and buoyantBoussinesqSimpleFoam (run.sh) and thaw's bench_flow_cube on the same CELLS^3 grid,
# one core each, started together so that the three see the same load on a shared machine
# (wall-time ratios from one run; CPU seconds are the steadier figures). Also runs the
# CELLS/2 grids of all three one after another first, for the Richardson extrapolations.
# Usage: compare.sh BUILD_DIR [CELLS (32)]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "$1" && pwd)
cells=${2:-32}
half=$((cells / 2))
out=${WORK:-/tmp}/thaw_openfoam_compare
mkdir -p "$out"
echo "start $(date -u +%FT%TZ)  uptime: $(uptime)"
SOLVER=simple "$here/run.sh" "$half" | tail -1
SOLVER=pimple "$here/run.sh" "$half" 70 1 | tail -1
OMP_NUM_THREADS=1 "$build/bench/sim/bench_flow_cube" 1 1e-5 1e-4 "$half" | tail -1
echo "together $(date -u +%FT%TZ)  uptime: $(uptime)"
SOLVER=simple "$here/run.sh" "$cells" > "$out/simple.txt" &
SOLVER=pimple "$here/run.sh" "$cells" 70 1 > "$out/pimple.txt" &
OMP_NUM_THREADS=1 "$build/bench/sim/bench_flow_cube" 1 1e-5 1e-4 "$cells" > "$out/thaw.txt" &
wait
tail -n1 "$out/simple.txt" "$out/pimple.txt" "$out/thaw.txt"
echo "end $(date -u +%FT%TZ)  uptime: $(uptime)"
