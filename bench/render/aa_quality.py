#!/usr/bin/python3
"""Anti-aliasing quality of a film frame against a converged reference (bench/render/aa_error.sh).

usage: aa_quality.py REFERENCE.png HORIZON RIM IMAGE.png [IMAGE.png ...]
       aa_quality.py --header

HORIZON and RIM are pixel windows "x0,y0,x1,y1" (x1, y1 exclusive): where the checker floor
recedes to the horizon (moire) and across the ball's rim (edge aliasing, the speckle band of the
refracted floor). REFERENCE is the same renderer at 256 samples per pixel, not adaptive, so what
is measured is the sampling error alone. Units: 8-bit sRGB codes (0..255); Y = 0.2126 R +
0.7152 G + 0.0722 B of the encoded values.
  rms            RMS difference to the reference over the whole image (all channels)
  hf_horizon     high-frequency energy in the horizon window: mean squared discrete Laplacian of
                 Y (4-neighbour stencil), the highest spatial frequencies, where aliasing and
                 speckle live; the reference's own value is its real detail
  hf_err_horizon the same of Y(image) - Y(reference): energy the reference does not have
  hf_rim, hf_err_rim  the same in the rim window
Needs numpy (python3-numpy, scripts/setup-bench); decodes PNG with ffmpeg.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dispersion_noise import load  # noqa: E402


def luminance(img):
    return img @ np.array([0.2126, 0.7152, 0.0722])


def laplacian(y):
    return 4 * y[1:-1, 1:-1] - y[:-2, 1:-1] - y[2:, 1:-1] - y[1:-1, :-2] - y[1:-1, 2:]


def window(spec):
    x0, y0, x1, y1 = (int(v) for v in spec.split(","))
    return slice(y0, y1), slice(x0, x1)


def hf(y, win):
    return float((laplacian(y[win]) ** 2).mean())


def main(argv):
    if argv[1:] == ["--header"]:
        print("| image | rms | hf_horizon | hf_err_horizon | hf_rim | hf_err_rim |")
        print("|---|---:|---:|---:|---:|---:|")
        return 0
    if len(argv) < 5:
        print(__doc__, file=sys.stderr)
        return 2
    ref = load(argv[1])
    horizon, rim = window(argv[2]), window(argv[3])
    yr = luminance(ref)
    for path in [argv[1]] + argv[4:]:
        img = load(path)
        if img.shape != ref.shape:
            print(f"{path}: size differs from the reference", file=sys.stderr)
            return 2
        y = luminance(img)
        rms = float(np.sqrt(((img - ref) ** 2).mean()))
        print(f"| {os.path.basename(path)} | {rms:.2f} | {hf(y, horizon):.1f} | "
              f"{hf(y - yr, horizon):.1f} | {hf(y, rim):.1f} | {hf(y - yr, rim):.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
