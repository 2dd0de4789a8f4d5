#!/usr/bin/python3
"""The Python module's costs (issue 28), for docs/benchmarks.md.

  /usr/bin/python3 bench/python/bench_python.py BUILD_DIR [--calls N]

1. Call overhead: a tiny scenario (the default cut to 2 minutes: 3 output times) simulated N
   times from C++ (BUILD_DIR/bench/python/bench_simulate_calls, the library call thaw.simulate
   makes) and N times from Python (thaw.simulate, plus reading interfaces as a caller would), in
   rounds that alternate the two so the machine's load falls on both alike. Reports the median
   wall and CPU time per call and the difference (target: <= 1 ms).
2. fields(step) of 3D runs of growing cell counts: time per call and bytes allocated (the arrays
   view the Result's memory, so both should not grow with the grid).
"""
import argparse
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc

ap = argparse.ArgumentParser()
ap.add_argument("build_dir")
ap.add_argument("--calls", type=int, default=200)
ap.add_argument("--rounds", type=int, default=5)
args = ap.parse_args()
build = pathlib.Path(args.build_dir).resolve()
sys.path.insert(0, str(build / "python"))
import thaw  # noqa: E402

tiny = thaw.Scenario.default().with_(**{"simulation.duration_s": 120.0})
tmp = pathlib.Path(tempfile.mkdtemp())
(tmp / "tiny.toml").write_text(tiny.text)

print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()}")
cpp_wall, cpp_cpu, py_wall, py_cpu = [], [], [], []
for _ in range(args.rounds):
    out = subprocess.run([build / "bench" / "python" / "bench_simulate_calls", tmp / "tiny.toml",
                          str(args.calls)], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines()[5:]:  # the first calls warm caches up
        w, c, _ = line.split()
        cpp_wall.append(float(w))
        cpp_cpu.append(float(c))
    for k in range(args.calls):
        t0, c0 = time.perf_counter(), time.process_time()
        r = thaw.simulate(tiny)
        r.interfaces
        t1, c1 = time.perf_counter(), time.process_time()
        if k >= 5:
            py_wall.append(t1 - t0)
            py_cpu.append(c1 - c0)
med = statistics.median
print(f"simulate, tiny scenario ({r.steps} output times), {len(cpp_wall)} calls each:")
print(f"  C++    wall {med(cpp_wall) * 1e3:.3f} ms, CPU {med(cpp_cpu) * 1e3:.3f} ms per call")
print(f"  Python wall {med(py_wall) * 1e3:.3f} ms, CPU {med(py_cpu) * 1e3:.3f} ms per call")
print(f"  overhead: wall {(med(py_wall) - med(cpp_wall)) * 1e3:+.3f} ms, "
      f"CPU {(med(py_cpu) - med(cpp_cpu)) * 1e3:+.3f} ms per call")

print("fields(step) of 3D runs (hollow cube, one output step after t = 0):")
cube = (pathlib.Path(__file__).parents[2] / "data" / "scenarios" / "hollow_cube.toml").read_text()
for cell in (0.0025, 0.00125, 0.000625):
    sc = thaw.Scenario.from_toml(cube, "hollow_cube.toml").with_(**{
        "simulation.duration_s": 1.0, "simulation.output_interval_s": 1.0,
        "simulation.cell_size_m": cell, "simulation.flow": "none"})
    r = thaw.simulate(sc)
    cells = 1
    for n in r.grid["cells"]:
        cells *= n
    r.fields(1)
    n = 20000
    t0 = time.perf_counter()
    for _ in range(n):
        r.fields(1)
    per_call = (time.perf_counter() - t0) / n
    tracemalloc.start()
    f = r.fields(1)
    size, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    print(f"  cell {cell * 1e3:.3g} mm: {cells:>9d} cells ({3 * 4 * cells / 2**20:7.1f} MiB of "
          f"fields): {per_call * 1e6:.2f} us per call, {peak} bytes allocated by one call")
