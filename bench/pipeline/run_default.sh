#!/usr/bin/env bash
# End-to-end timing of `thaw run` on the built-in default scenario (>= 48 frames at 640x480,
# the shell melting through), with the per-stage breakdown thaw prints, at --jobs 2 and
# --jobs 1 in the same run so the ratio is measured under the same conditions.
#   bench/pipeline/run_default.sh [BUILD_DIR] [REPEATS]
set -euo pipefail
build=${1:-build}
repeats=${2:-1}
thaw="$build/thaw"
[ -x "$thaw" ] || { echo "no $thaw: build first (scripts/build)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg)"
for jobs in 2 1; do
  for r in $(seq "$repeats"); do
    start=$(date +%s.%N)
    "$thaw" run --out "$out/run" --force --jobs "$jobs" 2>/dev/null > "$out/summary.txt"
    end=$(date +%s.%N)
    awk -v j="$jobs" -v r="$r" -v s="$start" -v e="$end" 'BEGIN { printf "jobs=%s run %s: %.2f s wall\n", j, r, e - s }'
    sed -n '1,7p' "$out/summary.txt" | sed 's/^/    /'
  done
done
