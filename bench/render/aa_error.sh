#!/usr/bin/env bash
# Anti-aliasing error of the default film frame (issue 10 item 5): frame 0 of the built-in default
# scenario rendered as `thaw run` does (its [render.image] settings: adaptive, cap 8, Gaussian
# filter, textures averaged over ray cones), at one sample per pixel through the pixel centre
# (--spp 1: no anti-aliasing, everything point-sampled, the look before the film was wired), and a
# 256-spp reference (not adaptive, same filter). Reports, against the reference, the RMS error and
# the high-frequency energy at the horizon and at the ball's rim (bench/render/aa_quality.py), and
# the wall and CPU time of each frame's render stage.
# usage: bench/render/aa_error.sh [OUT_DIR]   (THAW=path/to/thaw, HORIZON/RIM="x0,y0,x1,y1")
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
thaw="${THAW:-$here/../../build/thaw}"
out="${1:-/tmp/thaw-aa-error}"
# Windows of the 640x480 default frame 0: the far floor up to the horizon (right of the caption),
# and the band across the ball's lower rim where the refracted floor converges.
horizon="${HORIZON:-100,36,640,130}"
rim="${RIM:-225,250,410,335}"
mkdir -p "$out"
"$thaw" run --print-default > "$out/default.toml"
# The reference: the same scenario with 256 samples in every pixel.
sed -e 's/^samples_per_pixel = 8 .*/samples_per_pixel = 256/' -e 's/^adaptive_threshold = .*/adaptive = false/' \
  "$out/default.toml" > "$out/reference.toml"
grep -q '^samples_per_pixel = 256' "$out/reference.toml" || { echo "aa_error.sh: could not set the reference's spp" >&2; exit 1; }
timed() {  # label, then the command: prints "label: wall s, CPU s"
  local label="$1"; shift
  /usr/bin/time -f "$label: %e s wall, %U s user + %S s sys CPU" "$@" 2>&1 >/dev/null | tail -1
}
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at start"
"$thaw" run "$out/default.toml" --out "$out/default" --stage simulate -q
"$thaw" run "$out/default.toml" --out "$out/default" --stage mesh -q
timed "default frame 0 (cap 8, adaptive)" "$thaw" run "$out/default.toml" --out "$out/default" --stage render --frames 0 -q
rm -rf "$out/spp1" "$out/reference"
cp -r "$out/default" "$out/spp1"
timed "frame 0 at --spp 1" "$thaw" run "$out/default.toml" --out "$out/spp1" --stage render --frames 0 --spp 1 -q
cp -r "$out/default" "$out/reference"
timed "reference (256 spp, not adaptive)" "$thaw" run "$out/reference.toml" --out "$out/reference" --stage render --frames 0 -q
cp "$out/default/frames/frame_000000.png" "$out/default_frame.png"
cp "$out/spp1/frames/frame_000000.png" "$out/spp1_frame.png"
cp "$out/reference/frames/frame_000000.png" "$out/reference_frame.png"
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 "$here/aa_quality.py" --header
/usr/bin/python3 "$here/aa_quality.py" "$out/reference_frame.png" "$horizon" "$rim" \
  "$out/default_frame.png" "$out/spp1_frame.png"
