#!/usr/bin/env bash
# Temporal stability of thaw's film (issue 10 "Performance"): the mean absolute difference between
# consecutive frames, in 8-bit sRGB codes averaged over pixels and channels,
#  - of a static scene: the built-in default scenario with nothing to melt (ice and water at
#    0 C, insulated outer surface, no captions), 6 frames: every sample depends only on its pixel,
#    index and the fixed seed, so this must be exactly 0;
#  - of the default melt, its first 10 frames (the caption box, top-left, masked out): what
#    changes is the shell, its shadow, caustic and the puddle, never noise patterns.
# usage: bench/render/temporal_stability.sh [OUT_DIR]   (THAW=path/to/thaw)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
thaw="${THAW:-$here/../../build/thaw}"
out="${1:-/tmp/thaw-temporal}"
mkdir -p "$out"
"$thaw" run --print-default > "$out/default.toml"
/usr/bin/python3 - "$out/default.toml" "$out/static.toml" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
s = s.replace("initial_temperature_c = 10.0", "initial_temperature_c = 0.0")
s = s.replace("initial_temperature_c = -5.0", "initial_temperature_c = 0.0")
s = re.sub(r'kind = "convective".*\n(temperature_c = .*\n)(heat_transfer_coefficient_w_m2k = .*\n)',
           'kind = "insulated"\n', s)
s = re.sub(r"^frames = \d+", "frames = 6", s, flags=re.M)
s = re.sub(r"^caption = true", "caption = false", s, flags=re.M)
assert 'kind = "insulated"' in s and "frames = 6" in s and "caption = false" in s, "default changed"
open(sys.argv[2], "w").write(s)
PY
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
"$thaw" run "$out/static.toml" --out "$out/static" -q
"$thaw" run "$out/default.toml" --out "$out/melt" --frames 0-9 -q
BENCH_DIR="$here" /usr/bin/python3 - "$out" <<'PY'
import glob, os, sys
import numpy as np
sys.path.insert(0, os.environ.get("BENCH_DIR", "."))
from dispersion_noise import load
out = sys.argv[1]
def report(name, frames, mask_caption):
    imgs = [load(f) for f in frames]
    diffs = []
    for a, b in zip(imgs, imgs[1:]):
        d = np.abs(a - b)
        if mask_caption:
            d = d[:, :, :].copy()
            d[:60, :240] = np.nan
        diffs.append(float(np.nanmean(d)))
    print(f"{name}: {len(imgs)} frames, mean |frame[i+1] - frame[i]| = "
          + ", ".join(f"{x:.3f}" for x in diffs) + f" (mean {np.mean(diffs):.3f}) 8-bit codes")
report("static scene", sorted(glob.glob(f"{out}/static/frames/frame_*.png")), False)
report("default melt, frames 0-9, caption masked", sorted(glob.glob(f"{out}/melt/frames/frame_*.png"))[:10], True)
PY
