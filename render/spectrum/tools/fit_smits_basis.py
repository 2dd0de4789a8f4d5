#!/usr/bin/env python3
"""Fits the seven basis spectra of Smits' RGB -> spectrum conversion for thaw's colour pipeline.

Method: B. Smits, "An RGB-to-spectrum conversion for reflectances", Journal of Graphics Tools
4(4), 1999. Each basis spectrum (white, cyan, magenta, yellow, red, green, blue) is piecewise
constant over bins and chosen as the smoothest one (least sum of squared differences between
neighbouring bins) that lies in [0, 1] and reproduces its target colour exactly. Smits published
tables for his own primaries and white point; we re-run his optimisation for thaw's chain
(CIE 1931 2-degree observer, D65 illuminant with unit luminance, IEC 61966-2-1 sRGB matrix), so
that uplift -> multiply by D65 -> integrate -> sRGB reproduces every colour of [0, 1]^3 exactly:
the conversion is linear within each of Smits' six cases and exact on every basis vector.
White is the constant 1 (a perfect white reflector), not fitted.

Inputs: the CIE arrays in render/spectrum/cie_tables.cpp. Output: render/spectrum/smits_basis.cpp.
Pure Python (no numpy): augmented Lagrangian + projected gradient, polished by an exact KKT solve.
Run from the repository root: python3 render/spectrum/tools/fit_smits_basis.py
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
BIN_NM = 10.0
LAMBDA_MIN, LAMBDA_MAX = 380.0, 780.0
NBINS = int((LAMBDA_MAX - LAMBDA_MIN) / BIN_NM)
SRGB = [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]]
EPS = 1e-6  # tiny ridge term: makes the QP strictly convex (the smoothness term alone is not)


def read_tables():
    text = (ROOT / "render/spectrum/cie_tables.cpp").read_text()
    out = {}
    for name in ("kXBar", "kYBar", "kZBar", "kD65"):
        m = re.search(name + r" = \{(.*?)\};", text, re.S)
        out[name] = [float(v) for v in m.group(1).replace("\n", " ").split(",") if v.strip()]
        assert len(out[name]) == 81, name
    return out


def bin_matrix(t):
    """G[c][k]: linear sRGB channel c of bin k (value 1 in bin k) under unit-luminance D65."""
    step = 5.0
    cmf = (t["kXBar"], t["kYBar"], t["kZBar"])
    d65 = t["kD65"]

    def interval(i, f, g):  # exact integral of the product of two linear pieces (Simpson)
        a, b = f[i] * g[i], f[i + 1] * g[i + 1]
        m = 0.25 * (f[i] + f[i + 1]) * (g[i] + g[i + 1])
        return step / 6.0 * (a + 4 * m + b)

    lum = sum(interval(i, d65, t["kYBar"]) for i in range(80))
    xyz = [[0.0] * NBINS for _ in range(3)]
    for k in range(NBINS):
        for i in (2 * k, 2 * k + 1):
            for c in range(3):
                xyz[c][k] += interval(i, d65, cmf[c]) / lum
    return [[sum(SRGB[r][c] * xyz[c][k] for c in range(3)) for k in range(NBINS)] for r in range(3)]


def solve(a, b):
    """Gaussian elimination with partial pivoting."""
    n = len(a)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for col in range(n):
        p = max(range(col, n), key=lambda r: abs(m[r][col]))
        m[col], m[p] = m[p], m[col]
        if abs(m[col][col]) < 1e-300:
            raise RuntimeError("singular KKT system")
        for r in range(col + 1, n):
            f = m[r][col] / m[col][col]
            if f:
                for c in range(col, n + 1):
                    m[r][c] -= f * m[col][c]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (m[r][n] - sum(m[r][c] * x[c] for c in range(r + 1, n))) / m[r][r]
    return x


def hessian():
    h = [[0.0] * NBINS for _ in range(NBINS)]
    for k in range(NBINS - 1):
        h[k][k] += 2
        h[k + 1][k + 1] += 2
        h[k][k + 1] -= 2
        h[k + 1][k] -= 2
    for k in range(NBINS):
        h[k][k] += 2 * EPS
    return h


def kkt_on(g, target, lower, upper):
    """Equality-constrained QP with the bins in `lower` fixed at 0 and `upper` at 1."""
    h = hessian()
    free = [k for k in range(NBINS) if k not in lower and k not in upper]
    fixed = {k: 0.0 for k in lower}
    fixed.update({k: 1.0 for k in upper})
    nf = len(free)
    kkt = [[0.0] * (nf + 3) for _ in range(nf + 3)]
    rhs = [0.0] * (nf + 3)
    for i, ki in enumerate(free):
        for j, kj in enumerate(free):
            kkt[i][j] = h[ki][kj]
        rhs[i] = -sum(h[ki][k] * v for k, v in fixed.items())
        for c in range(3):
            kkt[i][nf + c] = g[c][ki]
            kkt[nf + c][i] = g[c][ki]
    for c in range(3):
        rhs[nf + c] = target[c] - sum(g[c][k] * v for k, v in fixed.items())
    sol = solve(kkt, rhs)
    b = [0.0] * NBINS
    for i, k in enumerate(free):
        b[k] = sol[i]
    for k, v in fixed.items():
        b[k] = v
    return b


def fit(g, target):
    """min 1/2 b'Hb  s.t.  G b = target, 0 <= b <= 1.

    An augmented-Lagrangian loop with projected-gradient inner iterations finds the active
    bounds; the KKT system on that active set then gives the exact solution (checked)."""
    h = hessian()
    rho = 100.0
    lip = 8.0 + 4 * EPS + rho * sum(g[c][k] ** 2 for c in range(3) for k in range(NBINS))
    b = [0.5] * NBINS
    lam = [0.0, 0.0, 0.0]
    for _ in range(60):
        for _ in range(400):
            res = [sum(g[c][k] * b[k] for k in range(NBINS)) - target[c] for c in range(3)]
            hb = [sum(h[k][j] * b[j] for j in range(max(0, k - 1), min(NBINS, k + 2)))
                  for k in range(NBINS)]
            grad = [hb[k] + sum((rho * res[c] + lam[c]) * g[c][k] for c in range(3))
                    for k in range(NBINS)]
            b = [min(1.0, max(0.0, b[k] - grad[k] / lip)) for k in range(NBINS)]
        res = [sum(g[c][k] * b[k] for k in range(NBINS)) - target[c] for c in range(3)]
        lam = [lam[c] + rho * res[c] for c in range(3)]
    lower = {k for k in range(NBINS) if b[k] < 1e-6}
    upper = {k for k in range(NBINS) if b[k] > 1 - 1e-6}
    exact = kkt_on(g, target, lower, upper)
    worst = max(max(-v, v - 1.0) for v in exact)
    if worst > 1e-9:
        raise RuntimeError("polished solution leaves [0, 1] by %g for %r" % (worst, target))
    return exact


def main():
    g = bin_matrix(read_tables())
    targets = {
        "cyan": (0, 1, 1), "magenta": (1, 0, 1), "yellow": (1, 1, 0),
        "red": (1, 0, 0), "green": (0, 1, 0), "blue": (0, 0, 1),
    }
    spectra = {"white": [1.0] * NBINS}
    for name, t in targets.items():
        b = fit(g, t)
        # Clamp rounding noise at the bounds, then report the colour error the table will have.
        b = [min(1.0, max(0.0, v)) for v in b]
        rgb = [sum(g[c][k] * b[k] for k in range(NBINS)) for c in range(3)]
        err = max(abs(rgb[c] - t[c]) for c in range(3))
        print(f"{name:8s} max |rgb error| = {err:.2e}", file=sys.stderr)
        spectra[name] = b
    white_rgb = [sum(g[c]) for c in range(3)]
    print("white    rgb =", ["%.6f" % v for v in white_rgb], file=sys.stderr)

    lines = [
        "// Generated by render/spectrum/tools/fit_smits_basis.py from render/spectrum/cie_tables.cpp;",
        "// do not edit. Smits (1999) basis spectra re-fitted for CIE 1931 2-degree + D65 + sRGB:",
        f"// piecewise constant over {NBINS} bins of {BIN_NM:g} nm from {LAMBDA_MIN:g} to {LAMBDA_MAX:g} nm,",
        "// each the smoothest [0, 1] spectrum whose colour under unit-luminance D65 is its target.",
        '#include "render/spectrum/rgb_uplift.h"',
        "",
        "namespace thaw::render::smits {",
        "",
        "// clang-format off",
    ]
    for name in ("white", "cyan", "magenta", "yellow", "red", "green", "blue"):
        lines.append(f"const std::array<double, kBins> k{name.capitalize()} = {{")
        vals = spectra[name]
        for i in range(0, NBINS, 4):
            lines.append("    " + ", ".join("%.17g" % v for v in vals[i:i + 4]) + ",")
        lines.append("};")
    lines += ["// clang-format on", "", "}  // namespace thaw::render::smits", ""]
    (ROOT / "render/spectrum/smits_basis.cpp").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
