#!/usr/bin/env bash
# The differentially heated cube at Ra 1e5, Pr 0.71 with OpenFOAM v1912 (Debian `openfoam`,
# scripts/setup-bench) on a uniform CELLS^3 mesh, serial, laminar, second-order central schemes,
# then the hot wall's Nusselt number per written iteration or time (nusselt.py). SOLVER=pimple
# (default): buoyantBoussinesqPimpleFoam marched from rest at Courant number 0.5 (as thaw's
# solver is) to END free-fall times, T written every WRITE; SOLVER=simple:
# buoyantBoussinesqSimpleFoam, steady SIMPLE, at most END iterations (it stops earlier on its
# residualControl), T written every WRITE iterations. With THAW_BUILD set, thaw's bench_flow_cube runs right after in the same
# run, on the same core count (THAW_THREADS, default 1), on the grids THAW_GRIDS (default "16 32").
# Usage: [SOLVER=pimple|simple] run.sh [CELLS (32) [END (pimple 100, simple 4000)
#        [WRITE (pimple 1, simple 25)]]]
# Work files go to ${WORK:-/tmp}/thaw_openfoam_cube_SOLVER_CELLS (removed first).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
solver=${SOLVER:-pimple}
case $solver in
  pimple) end=${2:-100} write_every=${3:-1} app=buoyantBoussinesqPimpleFoam ;;
  simple) end=${2:-4000} write_every=${3:-25} app=buoyantBoussinesqSimpleFoam ;;
  *) echo "run.sh: SOLVER is pimple or simple, not '$solver'" >&2; exit 2 ;;
esac
cells=${1:-32}
work=${WORK:-/tmp}/thaw_openfoam_cube_${solver}_$cells
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}  # Debian's etc/ (controlDict)
command -v $app >/dev/null ||
  { echo "run.sh: OpenFOAM not found (scripts/setup-bench installs Debian's openfoam)" >&2; exit 2; }

mkdir -p "$(dirname "$work")"
rm -rf "$work"
cp -r "$here/case" "$work"
rm -r "$work/system/simple" "$work/system/pimple"
cp "$here/case/system/$solver/"* "$work/system/"
sed -i "s/CELLS/$cells/g" "$work/system/blockMeshDict"
sed -i "s/ITERATIONS/$end/;s/WRITE/$write_every/" "$work/system/controlDict"
echo "uptime: $(uptime)"
(cd "$work" && blockMesh > log.blockMesh)
start=$(date +%s.%N)
/usr/bin/time -f "%e %U %S" -o "$work/time.txt" \
  bash -c "cd '$work' && $app > log.solver"
end=$(date +%s.%N)
read -r wall user sys < "$work/time.txt"
last=$(grep -E '^Time = ' "$work/log.solver" | tail -1 | awk '{print $3}')
# the final iteration is written when SIMPLE stops on residualControl
python3 "$here/nusselt.py" "$work" "$work/log.solver" > "$work/nusselt.txt"
python3 - "$work/nusselt.txt" "$solver" "$cells" "$last" "$wall" "$user" "$sys" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1])]
solver, cells, last = sys.argv[2:5]
wall, user, sys_s = map(float, sys.argv[5:8])
tric = 4.3370  # Tric, Labrosse & Betrouni (2000), hot-wall mean Nu at Ra 1e5 (from memory)
it, cpu, hot, cold = rows[-1][0], float(rows[-1][1]), float(rows[-1][2]), float(rows[-1][3])
def settled(tol):  # the first written row from which on Nu stays within tol of the last
    at = 0
    for i, r in enumerate(rows):
        if abs(float(r[2]) - hot) > tol * hot:
            at = i + 1
    s = rows[min(at, len(rows) - 1)]
    return f"{s[0]} ({float(s[1]):.2f} cpu s, {float(s[4]):.0f} wall s)"
print(f"openfoam {solver} cube {cells}^3  last {last}  wall {wall:.1f} s  cpu {user + sys_s:.1f} s  "
      f"Nu hot {hot:.5f} cold {cold:.5f}  error {100 * (hot - tric) / tric:+.3f} %  "
      f"settled 1e-3 at {settled(1e-3)}, 1e-4 at {settled(1e-4)}")
PY
if [[ -n "${THAW_BUILD:-}" ]]; then
  echo "uptime: $(uptime)"
  # shellcheck disable=SC2086
  "$THAW_BUILD/bench/sim/bench_flow_cube" "${THAW_THREADS:-1}" 1e-5 1e-4 ${THAW_GRIDS:-16 32}
fi
