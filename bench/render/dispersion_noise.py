#!/usr/bin/env python3
"""Colour noise of S3 renders (the glass sphere's disk), for bench/render/compare_povray.sh.

usage: dispersion_noise.py REFERENCE.png IMAGE.png [IMAGE.png ...]

For each IMAGE, over the disk of the glass sphere (centre (500, 500), radius 340 px of a
1000x1000 S3 render, where the dispersed checker is seen):
  rms_ref    RMS difference to REFERENCE (a high-spp thaw render) per channel, 8-bit sRGB units:
             noise plus any difference of model (for POV-Ray: its own dispersion model, 25
             fixed wavelengths and no anti-aliasing, so this is an upper bound of its noise);
  chroma_hp  RMS of the high-passed chroma (R-G, B-G minus their 3x3 box mean), 8-bit units:
             pixel-to-pixel colour speckle, whatever the reference (fringes add a little).
Decodes PNGs with ffmpeg (rawvideo rgb24); plain Python, no numpy.
"""
import subprocess
import sys


def load(path):
    out = subprocess.run(["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                         check=True, capture_output=True).stdout
    probe = subprocess.run(["ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries",
                            "stream=width,height", "-of", "csv=p=0", path],
                           check=True, capture_output=True, text=True).stdout.strip().split(",")
    return int(probe[0]), int(probe[1]), out


def disk(w, h):
    cx, cy, r = w * 0.5, h * 0.5, 0.34 * w
    return [(x, y) for y in range(1, h - 1) for x in range(1, w - 1) if (x - cx) ** 2 + (y - cy) ** 2 < r * r]


def main():
    ref_path, images = sys.argv[1], sys.argv[2:]
    w, h, ref = load(ref_path)
    pts = disk(w, h)
    for path in images:
        iw, ih, img = load(path)
        if (iw, ih) != (w, h):
            sys.exit(f"{path}: size {iw}x{ih} differs from the reference {w}x{h}")
        se = 0.0
        for x, y in pts:
            i = 3 * (y * w + x)
            for k in range(3):
                d = img[i + k] - ref[i + k]
                se += d * d
        rms_ref = (se / (3 * len(pts))) ** 0.5

        def chroma(x, y):
            i = 3 * (y * w + x)
            return img[i] - img[i + 1], img[i + 2] - img[i + 1]

        hp = 0.0
        for x, y in pts:
            c = chroma(x, y)
            m0 = m1 = 0.0
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    a, b = chroma(x + dx, y + dy)
                    m0 += a
                    m1 += b
            hp += (c[0] - m0 / 9) ** 2 + (c[1] - m1 / 9) ** 2
        chroma_hp = (hp / (2 * len(pts))) ** 0.5
        print(f"{path}: rms_ref {rms_ref:.2f} chroma_hp {chroma_hp:.2f}")


if __name__ == "__main__":
    main()
