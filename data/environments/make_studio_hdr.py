#!/usr/bin/env python3
"""Writes data/environments/studio.hdr: a small photographic studio as a lat-long HDR map.

A grey cyclorama (no horizon line: the wall curves into the floor), darker overhead, lit by
three soft boxes -- a large key box up front-left, a tall strip light on the right and a
smaller overhead box behind -- whose light ice and water reflect and refract as the bright
rectangles a photographer uses to show transparent things. Made here, deterministically, with
the Python standard library only (no download, no numpy): run it again and the bytes are
identical.

Conventions are thaw's (render/light/latlong_map.h): 512 x 256 texels, column u = 0.5 +
atan2(x, -z) / (2 pi) (the image's centre faces -z), row v = acos(y) / pi (top row = zenith).
Values are linear radiance in the renderer's units: the soft boxes at 6-12 (a sphere light of
intensity 0.7 at 0.82 m, the default film's, is 0.7 / (pi 0.06^2) = 62), the walls 0.12-0.35.
The file is Radiance RGBE with run-length encoded scanlines (Ward, Graphics Gems II, 1991).

Usage: python3 data/environments/make_studio_hdr.py [OUT.hdr]
"""
import math
import struct
import sys

WIDTH, HEIGHT = 512, 256


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3 - 2 * t)


def direction(u, v):
    phi = (u - 0.5) * 2 * math.pi
    theta = v * math.pi
    s = math.sin(theta)
    return (s * math.sin(phi), math.cos(theta), -s * math.cos(phi))


# Soft boxes: (centre azimuth [deg, 0 = -z, +90 = +x], centre elevation [deg], half-width
# [deg], half-height [deg], radiance RGB). Edges fall off over 1.5 degrees (a diffuser's rim),
# so the map has no hard step to alias.
BOXES = [
    (-40.0, 30.0, 16.0, 11.0, (11.0, 10.6, 10.0)),   # key: large, front-left, slightly warm
    (75.0, 15.0, 4.0, 22.0, (6.5, 6.7, 7.2)),        # strip: tall, right, slightly cool
    (170.0, 60.0, 12.0, 8.0, (7.0, 7.0, 7.0)),       # overhead box behind the set
]
EDGE_DEG = 1.5


def radiance(d):
    x, y, z = d
    elevation = math.degrees(math.asin(max(-1.0, min(1.0, y))))
    azimuth = math.degrees(math.atan2(x, -z))
    # Cyclorama: floor 0.30 (warm grey), wall 0.35 at eye height, darker towards the ceiling.
    wall = 0.35 - 0.23 * smoothstep(5.0, 80.0, elevation)
    floor = 0.30
    t = smoothstep(-12.0, 6.0, elevation)  # the curved join between floor and wall
    base = floor * (1 - t) + wall * t
    r, g, b = base * 1.02, base * 1.0, base * 0.97
    for az, el, hw, hh, rgb in BOXES:
        daz = (azimuth - az + 180.0) % 360.0 - 180.0
        # Angular distance along the azimuth shrinks with cos(elevation).
        dx = abs(daz) * math.cos(math.radians(el))
        dy = abs(elevation - el)
        w = (1 - smoothstep(hw - EDGE_DEG, hw + EDGE_DEG, dx)) * \
            (1 - smoothstep(hh - EDGE_DEG, hh + EDGE_DEG, dy))
        if w > 0:
            r, g, b = r + w * rgb[0], g + w * rgb[1], b + w * rgb[2]
    return r, g, b


def rgbe(r, g, b):
    v = max(r, g, b)
    if v < 1e-32:
        return bytes((0, 0, 0, 0))
    m, e = math.frexp(v)
    scale = m * 256.0 / v
    return bytes((int(r * scale), int(g * scale), int(b * scale), e + 128))


def rle_channel(values):
    """One channel of a new-style RLE scanline: runs (128 + n, value) and dumps (n, values)."""
    out = bytearray()
    i, n = 0, len(values)
    while i < n:
        run = 1
        while i + run < n and run < 127 and values[i + run] == values[i]:
            run += 1
        if run >= 4:
            out += bytes((128 + run, values[i]))
            i += run
            continue
        # A dump up to the next run of 4 or more (or 128 values).
        j = i
        while j < n and j - i < 128:
            k = 1
            while j + k < n and k < 4 and values[j + k] == values[j]:
                k += 1
            if k >= 4:
                break
            j += 1
        out += bytes((j - i,)) + bytes(values[i:j])
        i = j
    return out


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "data/environments/studio.hdr"
    data = bytearray(b"#?RADIANCE\n# thaw studio environment (data/environments/make_studio_hdr.py)\n"
                     b"FORMAT=32-bit_rle_rgbe\n\n")
    data += ("-Y %d +X %d\n" % (HEIGHT, WIDTH)).encode()
    for j in range(HEIGHT):
        pixels = [rgbe(*radiance(direction((i + 0.5) / WIDTH, (j + 0.5) / HEIGHT)))
                  for i in range(WIDTH)]
        data += struct.pack(">BBH", 2, 2, WIDTH)
        for c in range(4):
            data += rle_channel([p[c] for p in pixels])
    with open(out, "wb") as f:
        f.write(data)


if __name__ == "__main__":
    main()
