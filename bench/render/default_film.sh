#!/usr/bin/env bash
# Speed of the default film (issue 10 "Performance"): one default film frame (640x480, adaptive
# anti-aliasing, caustics, the sphere light's soft shadow) and the whole default film
# (`thaw run --out DIR`, built-in default scenario, every stage) end to end, with the per-stage
# seconds thaw reports. Targets: a frame <= 1 s wall, the film <= 30 s wall, on 2 cores.
# With BEFORE=path/to/other/thaw the same is timed for that binary too, alternating runs (before,
# after, before, after ...) so that both see the same machine load, and the ratios are printed.
# The machine is shared: the load is printed at the start and the end of every measurement; CPU
# seconds (user + sys) are less sensitive to it than wall seconds.
# SCENARIO=file runs that scenario instead of the built-in default (e.g. an older binary's
# `thaw run --print-default`, so that two binaries render the same film). With BEFORE and FILM=1
# the two films' frames are compared byte by byte (a speed-up that must not change the picture).
# usage: bench/render/default_film.sh [OUT_DIR]   (THAW=path/to/thaw, BEFORE=path/to/thaw,
#        FRAME=25 the frame timed alone, RUNS=3 runs of the frame per binary, FILM=1: also the
#        film, SCENARIO=file)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
thaw="${THAW:-$here/../../build/thaw}"
before="${BEFORE:-}"
out="${1:-/tmp/thaw-default-film}"
frame="${FRAME:-25}"
runs="${RUNS:-3}"
film="${FILM:-1}"
scenario=()
[ -n "${SCENARIO:-}" ] && scenario=("$(realpath "$SCENARIO")")
mkdir -p "$out"
load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "scenario: ${scenario[*]:-built-in default}"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), load $(load)"

names=(after)
bins=("$thaw")
if [ -n "$before" ]; then
  names=(before after)
  bins=("$before" "$thaw")
fi

# The simulation and meshes once per binary, so that a frame can be rendered alone.
for i in "${!bins[@]}"; do
  "${bins[$i]}" run "${scenario[@]}" --out "$out/${names[$i]}" --stage simulate -q
  "${bins[$i]}" run "${scenario[@]}" --out "$out/${names[$i]}" --stage mesh -q
done

# One frame: its earlier image removed, so the render stage redoes it (photon pass included).
frame_file=$(printf 'frame_%06d' "$frame")
declare -A wall cpu
for r in $(seq 1 "$runs"); do
  for i in "${!bins[@]}"; do
    dir="$out/${names[$i]}"
    rm -rf "$dir/frames/$frame_file.png" "$dir/run_items/render/$frame_file"
    /usr/bin/time -o "$out/time.txt" -f "%e %U %S" "${bins[$i]}" run "${scenario[@]}" --out "$dir" \
      --frames "$frame" --stage render -q
    read -r w u s <"$out/time.txt"
    wall[${names[$i]}]+="$w "
    cpu[${names[$i]}]+="$(echo "$u + $s" | bc) "
  done
done
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
echo "frame $frame alone (render stage: photon pass + tracing + PNG), $runs runs each, median; load $(load):"
for n in "${names[@]}"; do
  echo "  $n: $(echo "${wall[$n]}" | median) s wall, $(echo "${cpu[$n]}" | median) s CPU   (wall: ${wall[$n]}; CPU: ${cpu[$n]})"
done
if [ -n "$before" ]; then
  echo "  after/before: wall $(echo "scale=3; $(echo "${wall[after]}" | median) / $(echo "${wall[before]}" | median)" | bc), CPU $(echo "scale=3; $(echo "${cpu[after]}" | median) / $(echo "${cpu[before]}" | median)" | bc)"
fi
if [ "$film" = 1 ]; then
  # The whole film from nothing: every stage, as a new user runs it.
  for i in "${!bins[@]}"; do
    dir="$out/film_${names[$i]}"
    rm -rf "$dir"
    echo "whole default film, ${names[$i]} (load $(load) at start):"
    /usr/bin/time -f "  total: %e s wall, %U s user + %S s sys CPU" "${bins[$i]}" run "${scenario[@]}" \
      --out "$dir" 2>&1 |
      grep -E '^  (simulate|mesh|render|film|inspect) |total:|frames,' | sed 's/^thaw run: /  /'
  done
  echo "load at end: $(load)"
  if [ -n "$before" ]; then
    # An optimisation that should not change the picture: compare every frame of the two films.
    same=0 total=0
    for f in "$out/film_before/frames/"*.png; do
      total=$((total + 1))
      cmp -s "$f" "$out/film_after/frames/$(basename "$f")" && same=$((same + 1))
    done
    echo "frames byte-identical before/after: $same of $total"
  fi
fi
