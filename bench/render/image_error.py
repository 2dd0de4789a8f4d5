#!/usr/bin/python3
"""Error of renders against a converged reference of the same scene, in 8-bit sRGB units.

usage: image_error.py REFERENCE.png IMAGE.png [IMAGE.png ...]
       image_error.py --header

For each IMAGE: rgb_rms (RMS difference over all pixels and channels), p99 (99th percentile of
the per-pixel largest channel difference: speckle and fireflies), hf_rms (RMS of the difference
high-passed by its 3x3 box mean: noise and aliasing as opposed to a smooth bias) and mean_bias
(mean signed difference: a brightness offset). Used by compare_povray_caustics.sh (each renderer
against its own converged image) and the anti-aliasing study. Needs numpy (python3-numpy,
scripts/setup-bench); decodes PNG with ffmpeg (dispersion_noise.load).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dispersion_noise import box3, load  # noqa: E402


def errors(reference, image):
    diff = image - reference
    high_pass = diff - box3(diff)
    return {
        "rgb_rms": float(np.sqrt(np.mean(diff**2))),
        "p99": float(np.percentile(np.abs(diff).max(-1), 99)),
        "hf_rms": float(np.sqrt(np.mean(high_pass**2))),
        "mean_bias": float(np.mean(diff)),
    }


def main(argv):
    if argv[1:] == ["--header"]:
        print("| image | rgb_rms | p99 | hf_rms | mean_bias |\n|---|---|---|---|---|")
        return 0
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    reference = load(argv[1])
    for path in argv[2:]:
        e = errors(reference, load(path))
        print(f"| {os.path.basename(path)} | {e['rgb_rms']:.2f} | {e['p99']:.1f} | {e['hf_rms']:.2f} | {e['mean_bias']:+.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
