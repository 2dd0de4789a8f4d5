#!/usr/bin/python3
"""Colour error of S3 renders over the glass sphere's disk, for bench/render/compare_povray.sh.

usage: dispersion_noise.py REFERENCE.png IMAGE.png [IMAGE.png ...]
       dispersion_noise.py --header

REFERENCE is the same renderer's converged image at the same pixel centres (POV-Ray with
dispersion_samples 250; thaw with 256 wavelengths), so what is measured is the error of the
wavelength sampling alone, not the difference between the two renderers' models. Over the disk
where the dispersed checker is seen (centre of the image, radius 0.34 of its width; RADIUS
overrides), in 8-bit sRGB units:
  rgb_rms     RMS difference per channel;
  chroma_rms  RMS difference of the chroma (R-G, B-G): the colour error;
  chroma_hp   RMS of that chroma difference high-passed (minus its 3x3 box mean): speckle;
  fringe      RMS chroma of the reference itself: how colourful the fringes are;
  relative    chroma_rms / fringe: colour error relative to the colour there is to get right.
Needs numpy (Debian python3-numpy, installed by scripts/setup-bench); decodes PNG with ffmpeg.
"""
import os
import subprocess
import sys

import numpy as np


def load(path):
    out = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                         check=True, capture_output=True).stdout
    size = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries",
                           "stream=width,height", "-of", "csv=p=0", path],
                          check=True, capture_output=True, text=True).stdout.strip().split(",")
    w, h = int(size[0]), int(size[1])
    return np.frombuffer(out, np.uint8).astype(np.float64).reshape(h, w, 3)


def chroma(img):
    return np.stack([img[..., 0] - img[..., 1], img[..., 2] - img[..., 1]], -1)


def box3(x):
    p = np.pad(x, ((1, 1), (1, 1), (0, 0)), mode="edge")
    return sum(p[dy:dy + x.shape[0], dx:dx + x.shape[1]] for dy in range(3) for dx in range(3)) / 9


def main():
    if sys.argv[1:] == ["--header"]:
        print("| image | rgb_rms | chroma_rms | chroma_hp | fringe | relative |")
        print("|---|---:|---:|---:|---:|---:|")
        return
    ref = load(sys.argv[1])
    h, w, _ = ref.shape
    yy, xx = np.mgrid[0:h, 0:w]
    radius = float(os.environ.get("RADIUS", "0.34")) * w
    disk = (xx + 0.5 - w / 2) ** 2 + (yy + 0.5 - h / 2) ** 2 < radius ** 2
    fringe = np.sqrt((chroma(ref)[disk] ** 2).mean())
    for path in sys.argv[2:]:
        img = load(path)
        if img.shape != ref.shape:
            sys.exit(f"{path}: size differs from the reference")
        e = img - ref
        ce = chroma(img) - chroma(ref)
        rgb_rms = np.sqrt((e[disk] ** 2).mean())
        chroma_rms = np.sqrt((ce[disk] ** 2).mean())
        chroma_hp = np.sqrt(((ce - box3(ce))[disk] ** 2).mean())
        print(f"| {os.path.basename(path)} | {rgb_rms:.2f} | {chroma_rms:.2f} | {chroma_hp:.2f} | {fringe:.2f} | "
              f"{chroma_rms / fringe:.3f} |")


if __name__ == "__main__":
    main()
