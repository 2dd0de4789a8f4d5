#!/usr/bin/env python3
"""Mean Nusselt numbers of the hot (x = 0) and cold (x = 1) walls of the OpenFOAM cube case.

Usage: nusselt.py CASE_DIR LOG
For every written iteration (SIMPLE) or time (PIMPLE) directory of CASE_DIR, reads the cell temperatures T (blockMesh's
order: x fastest, then y, then z, CELLS^3 uniform cells of edge h = 1/CELLS) and takes the wall
gradient as OpenFOAM's own snGrad of a fixedValue patch does on this mesh, (T_wall - T_P) / (h/2);
Nu = L / dT * mean over the wall of |dT/dn|, with L = 1 and dT = 1 (free-fall units). LOG is
the solver's log: the process CPU time (ExecutionTime) and the wall time (ClockTime, whole
seconds) at each written iteration. Prints one line per written iteration or time: iteration or
time, CPU s, Nu hot, Nu cold, wall s.
"""
import os
import re
import sys


def read_cells(path):
    text = open(path).read()
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\(", text)
    if not m:
        return None
    n = int(m.group(1))
    body = text[m.end():text.index(")", m.end())]
    values = [float(v) for v in body.split()]
    if len(values) != n:
        raise SystemExit(f"{path}: {len(values)} values, header says {n}")
    return values


def cpu_by_iteration(log):
    cpu, wall, it = {}, {}, None
    for line in open(log):
        m = re.match(r"^Time = ([0-9.eE+-]+)\s*$", line)
        if m:
            it = float(m.group(1))
        m = re.match(r"^ExecutionTime = ([0-9.eE+-]+) s\s+ClockTime = ([0-9.eE+-]+) s", line)
        if m and it is not None:
            cpu[it] = float(m.group(1))
            wall[it] = float(m.group(2))
    return cpu, wall


def main():
    case, log = sys.argv[1], sys.argv[2]
    cpu, wall = cpu_by_iteration(log)
    def number(d):
        try:
            return float(d)
        except ValueError:
            return None

    written = sorted((number(d), d) for d in os.listdir(case) if number(d))
    for it, name in written:
        t = read_cells(os.path.join(case, name, "T"))
        if t is None:
            continue
        n = round(len(t) ** (1 / 3))
        if n ** 3 != len(t):
            raise SystemExit(f"{case}/{it}/T: {len(t)} cells is not a cube")
        half = 0.5 / n
        hot = cold = 0.0
        for k in range(n):
            for j in range(n):
                row = n * (j + n * k)
                hot += (0.5 - t[row]) / half
                cold += (t[row + n - 1] + 0.5) / half
        print(f"{name} {cpu.get(it, float('nan')):.3f} {hot / n**2:.6f} {cold / n**2:.6f} "
              f"{wall.get(it, float('nan')):.0f}")


if __name__ == "__main__":
    main()
