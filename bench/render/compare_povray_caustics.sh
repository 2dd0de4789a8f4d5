#!/usr/bin/env bash
# thaw vs POV-Ray 3.7 with photons, an area light and anti-aliasing (issue 10's caustics target:
# at equal or lower error against a converged reference, thaw at least 10x faster, wall, one run).
# Scene: data/scenes/s1_caustics_area.toml and its POV-Ray twin bench/render/pov/s1_caustics_area.pov
# (S1's ice shell, a sphere light of radius 0.3 behind it: a soft shadow and a ball-lens caustic).
#  1. Each renderer's converged reference (cached in $OUT; REFRESH=1 redoes them): POV-Ray with 2M
#     photons, a 17x17 area light and +AM2 +A0 +R3 (81 samples in every pixel); thaw with 256
#     samples in every pixel (adaptive off), 2M photons and 16 light samples.
#  2. POV-Ray on a ladder of settings (photons, area light N x N, AA threshold and depth) and thaw
#     as shipped; each image's error against its OWN reference (image_error.py: 8-bit sRGB RMS),
#     so that what is compared is convergence, not the two renderers' models.
#  3. Whole-process wall time of every setting in one hyperfine run, 2 threads; the speed-up is
#     taken against the fastest POV-Ray setting whose error is at most thaw's.
# usage: bench/render/compare_povray_caustics.sh [THAW_EXECUTABLE] [RUNS]     (SIZE=WxH, OUT=dir)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
thaw=$(realpath "${1:-$root/build/thaw}")
runs=${2:-3}
size=${SIZE:-640x640}
out=${OUT:-/tmp/thaw-bench-caustics}
py=/usr/bin/python3  # Debian's, with python3-numpy (scripts/setup-bench)
for tool in povray hyperfine; do
  command -v "$tool" >/dev/null || { echo "$tool not installed: run scripts/setup-bench" >&2; exit 1; }
done
mkdir -p "$out"
cp "$root/bench/render/pov/s1_caustics_area.pov" "$out/"
scene="$root/data/scenes/s1_caustics_area.toml"
w=${size%x*}; h=${size#*x}

# pov_cmd NAME PHOTONS AREA_N AA_THRESHOLD AA_DEPTH: POV-Ray's command line (in $out: Debian's
# POV-Ray reads and writes only below the current folder).
pov_cmd() {
  echo "cd $out && povray +Is1_caustics_area.pov +O$1.png +FN +W$w +H$h +WT2 -D -V File_Gamma=sRGB" \
       "Declare=PHOTONS=$2 Declare=AREA_N=$3 +A$4 +AM2 +R$5 2>/dev/null"
}
thaw_cmd() {  # NAME SCENE
  echo "$thaw render $2 -o $out/$1.png --width $w --height $h --threads 2 --quiet"
}

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "size $size, thaw $("$thaw" --version | cut -d' ' -f2), $(povray --version 2>&1 | grep -m1 -o 'POV-Ray [0-9.]*' || echo POV-Ray 3.7)"

# 1. references
if [ ! -f "$out/pov_ref.png" ] || [ "${REFRESH:-0}" = 1 ]; then
  eval "$(pov_cmd pov_ref 2000000 17 0.0 3)"
fi
if [ ! -f "$out/thaw_ref.png" ] || [ "${REFRESH:-0}" = 1 ]; then
  sed -e 's/^samples_per_pixel = .*/samples_per_pixel = 256\nadaptive = false/' \
      -e 's/^enabled = true .*/enabled = true\nphotons = 2000000/' \
      -e 's/^radius = 0.3/radius = 0.3\nsamples = 16/' "$scene" > "$out/thaw_ref.toml"
  eval "$(thaw_cmd thaw_ref "$out/thaw_ref.toml")"
fi

# 2. + 3. the settings, timed in one hyperfine run, then their errors
ladder=("pov_a:50000:3:0.3:2" "pov_b:200000:5:0.1:2" "pov_c:1000000:9:0.05:3" "pov_d:2000000:13:0.02:3")
cmds=("$(thaw_cmd thaw "$scene")")
for spec in "${ladder[@]}"; do
  IFS=: read -r name photons area aa depth <<<"$spec"
  cmds+=("$(pov_cmd "$name" "$photons" "$area" "$aa" "$depth")")
done
hyperfine --style none --warmup 1 --runs "$runs" --export-json "$out/times.json" "${cmds[@]}" >/dev/null
IMAGE_ERROR="$root/bench/render/image_error.py" "$py" - "$out" "${ladder[@]}" <<'PY'
import json, os, subprocess, sys
out, ladder = sys.argv[1], sys.argv[2:]
times = [r["mean"] for r in json.load(open(f"{out}/times.json"))["results"]]
def rms(ref, img):
    row = subprocess.run([sys.executable, os.environ.get("IMAGE_ERROR"), f"{out}/{ref}.png", f"{out}/{img}.png"],
                         check=True, capture_output=True, text=True).stdout.split("|")
    return float(row[2]), row
rows = [("thaw (as shipped)", "thaw", "thaw_ref", times[0])]
for spec, t in zip(ladder, times[1:]):
    name, photons, area, aa, depth = spec.split(":")
    rows.append((f"POV-Ray {int(photons)//1000}k photons, {area}x{area} light, +A{aa} +R{depth}", name, "pov_ref", t))
print("\n| renderer, settings | wall [s] | RMS error vs own reference (8-bit) | p99 | high-pass RMS |")
print("|---|---:|---:|---:|---:|")
errors = {}
for label, img, ref, t in rows:
    e, row = rms(ref, img)
    errors[img] = (e, t)
    print(f"| {label} | {t:.2f} | {e:.2f} | {row[3].strip()} | {row[4].strip()} |")
thaw_error, thaw_time = errors["thaw"]
matching = [t for img, (e, t) in errors.items() if img != "thaw" and e <= thaw_error]
if matching:
    print(f"\nspeed-up at equal or lower error: {min(matching) / thaw_time:.1f}x (POV-Ray {min(matching):.2f} s / thaw {thaw_time:.2f} s)")
else:
    print(f"\nno POV-Ray setting reached thaw's error ({thaw_error:.2f}); against the best: "
          f"{max(t for img, (e, t) in errors.items() if img != 'thaw') / thaw_time:.1f}x")
PY
