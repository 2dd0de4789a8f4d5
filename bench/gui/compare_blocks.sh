#!/usr/bin/env bash
# compare_blocks.sh BEFORE AFTER [RUNS=3] [EDITS=10]: bench_gui of two builds (paths to their
# bench_gui executables), alternated in one script so that both see the same machine load, each
# run first with an empty Mesa shader cache (a machine's first run: a new MESA_SHADER_CACHE_DIR)
# and then again with the cache that run filled (warm). Prints `uptime` and, per run, the
# figures of issue 14's targets: the longest GUI-thread block per phase, the scrub and preview
# latencies, and the blocks over 50 ms. Figures: docs/benchmarks.md, "thaw gui".
set -euo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: $0 BEFORE_BENCH_GUI AFTER_BENCH_GUI [RUNS=3] [EDITS=10]" >&2
  exit 2
fi
declare -A bench=([before]=$1 [after]=$2)
runs=${3:-3}
edits=${4:-10}
work=$(mktemp -d /tmp/thaw_compare_blocks.XXXXXX)
trap 'rm -rf "$work"' EXIT
uptime
for run in $(seq 1 "$runs"); do
  for which in before after; do
    cache="$work/$which-$run"
    mkdir -p "$cache"
    for state in empty warm; do
      echo "== run $run, $which, $state shader cache ($(date -u +%T), load $(cut -d' ' -f1 /proc/loadavg))"
      MESA_SHADER_CACHE_DIR="$cache" "${bench[$which]}" "$edits" 2>/dev/null |
        grep -E "longest GUI-thread block|less its waits|most GUI-thread CPU|frame shown|320x240 image shown|blocked|view complete|late" ||
        echo "   (bench_gui failed)"
    done
  done
done
uptime
