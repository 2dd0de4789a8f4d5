#!/usr/bin/env bash
# Process start-up of thaw's commands (whole process, hyperfine): the light launcher `thaw`
# (simulate, render, materials) against libexec/thaw-full, which loads VTK, CGAL's GMP/MPFR, Qt and
# MPI, on the same trivial command, then a small render through each. Same run, so the ratio holds
# under load. Usage: bench/cli/startup.sh [BUILD_DIR] [RUNS]
set -euo pipefail
build=${1:-build}
runs=${2:-30}
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "shared libraries: thaw $(ldd "$build/thaw" | wc -l), thaw-full $(ldd "$build/libexec/thaw-full" | wc -l)"
hyperfine --style basic --warmup 3 --runs "$runs" -N \
  "$build/thaw materials water-0c" "$build/libexec/thaw-full materials water-0c"
hyperfine --style basic --warmup 2 --runs "$runs" -N \
  "$build/thaw render $root/data/scenes/s1_ice_shell.toml -o $out/a.png --width 160 --height 160 --quiet" \
  "$build/libexec/thaw-full render $root/data/scenes/s1_ice_shell.toml -o $out/b.png --width 160 --height 160 --quiet"
