#!/usr/bin/env bash
# thaw render vs POV-Ray 3.7 (Debian `povray`, scripts/setup-bench) on the reference scenes of
# ../shared/scenes, side by side in one run with hyperfine: whole process, same size, depth 10,
# 1 ray per pixel, 2 threads. Then the reports' studies: time vs image size (128..2000) at 1 and
# 2 threads, and time vs object count (2, 4, 8, 16 spheres of S4) at 1000x1000.
# usage: bench/render/compare_povray.sh [THAW_EXECUTABLE] [SHARED_SCENES_DIR] [RUNS]
# Writes markdown tables to stdout and hyperfine JSON to $OUT (default /tmp/thaw-bench-render).
# BEFORE=path/to/other/thaw also times that binary (e.g. main before a change) in the same
# hyperfine runs of the reference-scene table, so that both ratios see the same machine load, and
# says whether the two wrote the same PNG bytes.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
thaw=$(realpath "${1:-$root/build/thaw}")
before=${BEFORE:+$(realpath "$BEFORE")}
shared=$(realpath "${2:-$root/../shared/scenes}")
runs=${3:-5}
out=${OUT:-/tmp/thaw-bench-render}
for tool in povray hyperfine; do
  command -v "$tool" >/dev/null || { echo "$tool not installed: run scripts/setup-bench" >&2; exit 1; }
done
mkdir -p "$out"
pov="$out/pov"
rm -rf "$pov" && cp -r "$shared/pov" "$pov" && chmod -R u+w "$pov"
scenes="$root/data/scenes"

# povray_cmd NAME WxH THREADS: the command line of ../shared/scenes/run_povray.sh (no anti-aliasing,
# adaptive depth control 1/255, max_trace_level 10, sRGB), run in the folder holding the .pov.
povray_cmd() {
  echo "cd $pov && povray +I$1.pov +O$out/$1_pov.png +FN +W${2%x*} +H${2#*x} -A +WT$3 -D -V File_Gamma=sRGB 2>/dev/null"
}
thaw_cmd() {  # SCENE WxH THREADS [BINARY: the BEFORE one]
  echo "${4:-$thaw} render $1 -o $out/$(basename "$1" .toml)_thaw${4:+_before}.png --width ${2%x*} --height ${2#*x} --threads $3 --quiet"
}
# wall-time means [s] of command 0 (POV-Ray) and command I (default 1: thaw) in a hyperfine JSON
# file, their ratio, and the ratio of CPU time (user + system): the fairer figure when the machine
# is shared. With ONLY=1 just the last two (for the BEFORE binary's columns).
ratio() {
  python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['results']; i=int(sys.argv[2]); a,b=r[0]['mean'],r[i]['mean']; ca,cb=r[0]['user']+r[0]['system'],r[i]['user']+r[i]['system']; c=[f'{a:.3f}',f'{b:.3f}',f'{a/b:.2f}x',f'{ca/cb:.2f}x']; print(' | '.join(c[1:] if sys.argv[3]=='1' else c))" "$1" "${2:-1}" "${ONLY:-0}"
}

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "thaw $("$thaw" --version | cut -d' ' -f2), $(povray --version 2>&1 | grep -m1 -o 'POV-Ray [0-9.]*' || echo POV-Ray 3.7)"
echo
if [ "${MAIN:-1}" = 1 ]; then  # MAIN=0 skips the reference-scene table
if [ -n "$before" ]; then
  echo "| scene | size | POV-Ray [s] | thaw [s] | speed-up (wall) | speed-up (CPU) | before [s] | before speed-up (wall) | before speed-up (CPU) | same PNG |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
else
  echo "| scene | size | POV-Ray [s] | thaw [s] | speed-up (wall) | speed-up (CPU) |"
  echo "|---|---|---|---|---|---|"
fi
for spec in "s1_ice_shell_mesh:s1_ice_shell_mesh:640x640" "s1_ice_shell:s1_ice_shell:640x640" \
            "s4_spheres16:s4_spheres16:2000x2000" "s3_dispersion_nodisp:s3_dispersion_nodisp:1000x1000"; do
  IFS=: read -r povname toml size <<<"$spec"
  cmds=("$(povray_cmd "$povname" "$size" 2)" "$(thaw_cmd "$scenes/$toml.toml" "$size" 2)")
  [ -n "$before" ] && cmds+=("$(thaw_cmd "$scenes/$toml.toml" "$size" 2 "$before")")
  hyperfine --style none --warmup 1 --runs "$runs" --export-json "$out/$povname.json" "${cmds[@]}" >/dev/null
  if [ -n "$before" ]; then
    same=no
    cmp -s "$out/${toml}_thaw.png" "$out/${toml}_thaw_before.png" && same=yes
    echo "| $povname | $size | $(ratio "$out/$povname.json") | $(ONLY=1 ratio "$out/$povname.json" 2) | $same |"
  else
    echo "| $povname | $size | $(ratio "$out/$povname.json") |"
  fi
done
fi

# Dispersion (issue 5): S3 with the N-SF10 Sellmeier glass, 1000x1000, 2 threads, whole process,
# one hyperfine run: POV-Ray 3.7 through ../shared/scenes/run_povray.sh (dispersion_samples 25,
# 1 ray per pixel) against thaw spectral at 1 sample per pixel (pixel centres, as POV-Ray):
# adaptive dispersion (the default) and, for comparison, the plain split into 4 wavelengths.
# Colour error of each renderer against its OWN converged image at the same pixel centres
# (bench/render/dispersion_noise.py): POV-Ray with dispersion_samples 250, thaw with 256
# wavelengths through the split and, as a second reference, adaptive with 128 probes at 0.25 nm. That isolates the error of the wavelength sampling from the
# two renderers' different models (POV-Ray's dispersion law and colour mapping, its shadowless
# glass), and the relative error divides by each reference's own fringe colour.
if [ "${DISPERSION:-1}" = 1 ]; then
  echo
  echo "Dispersion: S3 (N-SF10 Sellmeier sphere), 1000x1000, 2 threads, 1 ray per pixel."
  echo
  f="$out/s3_dispersion.json"
  s3="$scenes/s3_dispersion.toml"
  hyperfine --style none --warmup 1 --runs "$runs" --export-json "$f" \
    "$shared/run_povray.sh s3_dispersion 1000x1000 2 $out/s3_pov.png >/dev/null 2>&1" \
    "$thaw render $s3 -o $out/s3_thaw_adaptive.png --spp 1 --threads 2 --quiet" \
    "$thaw render $s3 -o $out/s3_thaw_split4.png --spp 1 --threads 2 --quiet --dispersion split --dispersion-wavelengths 4" >/dev/null
  sed 's/dispersion_samples 25/dispersion_samples 250/' "$pov/s3_dispersion.pov" > "$pov/s3_dispersion_ref.pov"
  (cd "$pov" && povray +Is3_dispersion_ref.pov +O"$out/s3_pov_reference.png" +FN +W1000 +H1000 -A +WT2 -D -V \
    File_Gamma=sRGB 2>/dev/null)
  "$thaw" render "$s3" -o "$out/s3_thaw_reference.png" --spp 1 --threads 2 --quiet --dispersion split \
    --dispersion-wavelengths 256
  "$thaw" render "$s3" -o "$out/s3_thaw_reference_adaptive.png" --spp 1 --threads 2 --quiet \
    --dispersion-wavelengths 128 --dispersion-resolution-nm 0.25
  python3 - "$f" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))['results']
names = ['POV-Ray 3.7, dispersion_samples 25', 'thaw, adaptive dispersion (default)', 'thaw, split into 4 wavelengths']
cpu = [x['user'] + x['system'] for x in r]
print('| renderer | wall [s] | CPU [s] | POV-Ray / this (wall) | POV-Ray / this (CPU) |')
print('|---|---|---|---|---|')
for n, x, c in zip(names, r, cpu):
    print(f"| {n} | {x['mean']:.2f} | {c:.2f} | {r[0]['mean'] / x['mean']:.2f}x | {cpu[0] / c:.2f}x |")
PY
  echo
  echo "Colour error over the glass sphere's disk against each renderer's own converged image:"
  echo
  noise=(/usr/bin/python3 "$root/bench/render/dispersion_noise.py")
  "${noise[@]}" --header
  "${noise[@]}" "$out/s3_pov_reference.png" "$out/s3_pov.png"
  echo "thaw against its split reference (256 wavelengths):"
  "${noise[@]}" "$out/s3_thaw_reference.png" "$out/s3_thaw_adaptive.png" "$out/s3_thaw_split4.png" \
    "$out/s3_thaw_reference_adaptive.png"
  echo "thaw against its adaptive reference (128 probe wavelengths, 0.25 nm):"
  "${noise[@]}" "$out/s3_thaw_reference_adaptive.png" "$out/s3_thaw_adaptive.png" "$out/s3_thaw_split4.png"
fi

[ "${STUDIES:-1}" = 1 ] || exit 0
echo
echo "Study 1: S4, time vs image size (whole process)."
echo
echo "| size | threads | POV-Ray [s] | thaw [s] | speed-up (wall) | speed-up (CPU) |"
echo "|---|---|---|---|---|---|"
for n in 128 256 512 1000 2000; do
  for t in 1 2; do
    f="$out/size_${n}_$t.json"
    hyperfine --style none --warmup 1 --runs "$runs" --export-json "$f" \
      "$(povray_cmd s4_spheres16 "${n}x$n" "$t")" "$(thaw_cmd "$scenes/s4_spheres16.toml" "${n}x$n" "$t")" >/dev/null
    echo "| ${n}x$n | $t | $(ratio "$f") |"
  done
done

echo
echo "Study 2: S4 with the first N spheres, 1000x1000, 2 threads."
echo
echo "| spheres | POV-Ray [s] | thaw [s] | speed-up (wall) | speed-up (CPU) |"
echo "|---|---|---|---|---|"
for n in 2 4 8 16; do
  # Keep the first n sphere objects of both scene files (each sphere is one '// sphereNN' block).
  python3 - "$pov/s4_spheres16.pov" "$pov/s4_n$n.pov" "$scenes/s4_spheres16.toml" "$out/s4_n$n.toml" "$n" <<'PY'
import re, sys
pov_in, pov_out, toml_in, toml_out, n = sys.argv[1:6]; n = int(n)
lines = open(pov_in).read().split('\n'); keep = []; skip = False
for i, l in enumerate(lines):
    m = re.match(r'// sphere(\d+):', l)
    if m: skip = int(m.group(1)) >= n
    elif l.startswith('// floor'): skip = False
    if not skip: keep.append(l)
open(pov_out, 'w').write('\n'.join(keep))
blocks = open(toml_in).read().split('[[objects]]')
kept = [b for b in blocks[1:] if not re.search(r'name = "sphere(\d+)"', b) or int(re.search(r'name = "sphere(\d+)"', b).group(1)) < n]
open(toml_out, 'w').write(blocks[0] + ''.join('[[objects]]' + b for b in kept))
PY
  # (unused materials are fine in thaw; mesh files resolve next to the scene file)
  ln -sfn "$scenes/meshes" "$out/meshes"
  f="$out/objects_$n.json"
  hyperfine --style none --warmup 1 --runs "$runs" --export-json "$f" \
    "$(povray_cmd "s4_n$n" 1000x1000 2)" "$(thaw_cmd "$out/s4_n$n.toml" 1000x1000 2)" >/dev/null
  echo "| $n | $(ratio "$f") |"
done
