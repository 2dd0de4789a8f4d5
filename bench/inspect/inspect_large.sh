#!/usr/bin/env bash
# `thaw inspect` on large and pathological meshes (issue 12): a closed torus of N x N vertices
# (N = 1000: one million vertices, two million triangles) and the 3-vertex file with 4,000 copies
# of `f 1 2 3` that made vtkFeatureEdges take minutes. Prints wall time and peak memory of each.
#   bench/inspect/inspect_large.sh [THAW_BINARY] [N]      (defaults: build/thaw, 1000)
# Figures: docs/benchmarks.md, "Mesh inspection at scale".
set -euo pipefail
thaw=${1:-build/thaw}
n=${2:-1000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Torus: major radius 1, minor radius 0.3; vertex (i, j) at angles 2 pi i / n, 2 pi j / n; each
# grid quad split into two triangles ordered so the normals point outward.
awk -v n="$n" 'BEGIN {
  pi = atan2(0, -1); R = 1.0; r = 0.3;
  for (i = 0; i < n; i++) for (j = 0; j < n; j++) {
    u = 2 * pi * i / n; v = 2 * pi * j / n;
    printf "v %.17g %.17g %.17g\n", (R + r * cos(v)) * cos(u), (R + r * cos(v)) * sin(u), r * sin(v);
  }
  for (i = 0; i < n; i++) for (j = 0; j < n; j++) {
    a = i * n + j + 1; b = ((i + 1) % n) * n + j + 1;
    c = ((i + 1) % n) * n + (j + 1) % n + 1; d = i * n + (j + 1) % n + 1;
    printf "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d;
  }
}' > "$work/torus.obj"
{ printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n'; for _ in $(seq 4000); do echo 'f 1 2 3'; done; } > "$work/copies.obj"

run() {  # $1 label, $2 file
  local t0 t1 status
  t0=$(date +%s.%N)
  set +e
  timeout "${THAW_BENCH_TIMEOUT:-600}" /usr/bin/time -f "%U %S %M" -o "$work/mem" "$thaw" inspect "$2" --json > "$work/out.json" 2> "$work/err"
  status=$?
  set -e
  t1=$(date +%s.%N)
  local kib
  local cpu
  kib=$(tail -1 "$work/mem" 2>/dev/null | awk '{print $3}')
  cpu=$(tail -1 "$work/mem" 2>/dev/null | awk 'NF == 3 {printf "%.2f s CPU", $1 + $2}')
  [[ "$kib" =~ ^[0-9]+$ ]] && kib="$(( kib / 1024 )) MiB" || kib="? (killed after the timeout)"
  printf '%-36s exit %3d  %7.2f s wall  %s  peak %s  %s\n' "$1" "$status" \
    "$(echo "$t1 - $t0" | bc)" "${cpu:-?}" "$kib" "$(grep -o '"closed": [a-z]*' "$work/out.json" | head -1)"
  [ "$status" -eq 0 ] || head -c 300 "$work/err"
}
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); $thaw"
run "torus ${n}x${n} ($(( n * n )) vertices)" "$work/torus.obj"
run "3 vertices, 4000 x f 1 2 3" "$work/copies.obj"
