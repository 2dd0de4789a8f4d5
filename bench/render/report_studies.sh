#!/usr/bin/env bash
# The second report's studies reproduced with thaw (issue 30, item 4): render time of S4 (spheres on
# a checker floor, data/scenes/s4_spheres16.toml) against image size (100, 200, 500, 1000, 2000 px
# square, all 16 spheres) and against object count (the first 2, 4, 8, 16 spheres, SIZE px square),
# 1 thread against 2. Whole `thaw render` processes, wall and CPU time (user + system of the child,
# the fairer figure on a shared machine), the best of RUNS each. Writes markdown tables to stdout
# and $OUT/report_studies.png (time against pixels and against objects, log-log), with the
# second report's own figure beside thaw's (16 objects at 2000 px: 102 s serial, 31 s parallel on
# a 4-core laptop). Needs python3-matplotlib (scripts/setup-bench).
# usage: bench/render/report_studies.sh [THAW_EXECUTABLE] [RUNS]   (env: OUT, SIZE)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
thaw=$(realpath "${1:-$root/build/thaw}")
runs=${2:-1}
out=${OUT:-/tmp/thaw-report-studies}
size=${SIZE:-500}
mkdir -p "$out"
ln -sfn "$root/data/scenes/meshes" "$out/meshes"  # mesh files resolve next to the scene file
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg) at start"
/usr/bin/python3 - "$thaw" "$runs" "$out" "$size" "$root/data/scenes/s4_spheres16.toml" <<'PY'
import os, re, resource, subprocess, sys, time
thaw, runs, out, size, s4 = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), sys.argv[5]

def scene_with(n):
    """S4 with its first n spheres (each sphere is one [[objects]] block named sphereNN)."""
    blocks = open(s4).read().split('[[objects]]')
    def keep(b):
        m = re.search(r'name = "sphere(\d+)"', b)
        return m is None or int(m.group(1)) < n
    path = f'{out}/s4_n{n}.toml'
    open(path, 'w').write(blocks[0] + ''.join('[[objects]]' + b for b in blocks[1:] if keep(b)))
    return path

def render(scene, px, threads):
    """Best of `runs` (wall [s], CPU [s]) of one whole thaw render process."""
    best = None
    for _ in range(runs):
        c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        w0 = time.perf_counter()
        subprocess.run([thaw, 'render', scene, '-o', f'{out}/frame.png', '--width', str(px),
                        '--height', str(px), '--threads', str(threads), '--quiet'], check=True)
        wall = time.perf_counter() - w0
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
        best = (wall, cpu) if best is None else (min(best[0], wall), min(best[1], cpu))
    return best

sizes, counts = [100, 200, 500, 1000, 2000], [2, 4, 8, 16]
by_size = {t: [render(scene_with(16), px, t) for px in sizes] for t in (1, 2)}
by_count = {t: [render(scene_with(n), size, t) for n in counts] for t in (1, 2)}
load = open('/proc/loadavg').read().split()[:3]

print(f'\nStudy 1: S4 (16 spheres), 1 ray per pixel, best of {runs}; wall [s] / CPU [s]\n')
print('| size [px] | 1 thread | 2 threads | speed-up 2 vs 1 (wall) | CPU per megapixel, 2 threads [s] |')
print('|---:|---:|---:|---:|---:|')
for i, px in enumerate(sizes):
    (w1, c1), (w2, c2) = by_size[1][i], by_size[2][i]
    print(f'| {px} | {w1:.3f} / {c1:.3f} | {w2:.3f} / {c2:.3f} | {w1 / w2:.2f}x | {c2 / (px * px / 1e6):.3f} |')
print(f'\nStudy 2: S4 with the first N spheres, {size}x{size}; wall [s] / CPU [s]\n')
print('| spheres | 1 thread | 2 threads | speed-up 2 vs 1 (wall) |')
print('|---:|---:|---:|---:|')
for i, n in enumerate(counts):
    (w1, c1), (w2, c2) = by_count[1][i], by_count[2][i]
    print(f'| {n} | {w1:.3f} / {c1:.3f} | {w2:.3f} / {c2:.3f} | {w1 / w2:.2f}x |')
w1, w2 = by_size[1][-1][0], by_size[2][-1][0]
print(f'\nThe second report, 16 objects at 2000 px on a 4-core laptop: 102 s serial, 31 s parallel; '
      f'thaw here: {w1:.2f} s on 1 thread, {w2:.2f} s on 2 ({102 / w1:.0f}x and {31 / w2:.0f}x '
      f'faster, different machines).')
print(f'load at end: {" ".join(load)}')

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
mp = [px * px / 1e6 for px in sizes]
for t, style in ((1, 'o-'), (2, 's-')):
    a.loglog(mp, [x[1] for x in by_size[t]], style, label=f'thaw CPU time, {t} thread(s)')
    a.loglog(mp, [x[0] for x in by_size[t]], style, alpha=0.4, label=f'thaw wall time, {t} thread(s)')
    b.plot(counts, [x[1] for x in by_count[t]], style, label=f'thaw CPU time, {t} thread(s)')
a.loglog([4.0], [102], 'kx', markersize=9, label='second report, serial (4-core laptop)')
a.loglog([4.0], [31], 'k+', markersize=11, label='second report, parallel')
ref = by_size[1][-1][1]
a.loglog(mp, [ref * m / mp[-1] for m in mp], 'k:', label='O(pixels) through the 2000 px point')
a.set_xlabel('image size [megapixels]')
a.set_ylabel('time per frame [s]')
a.set_title('S4, 16 spheres: time against pixels')
a.legend(fontsize=7)
b.set_xlabel('spheres on the floor')
b.set_ylabel('CPU time per frame [s]')
b.set_title(f'S4, first N spheres, {size}x{size}')
b.set_ylim(bottom=0)
b.legend(fontsize=7)
fig.suptitle(f'thaw render, best of {runs}; shared 2-core machine, load {" ".join(load)}', fontsize=9)
fig.tight_layout()
fig.savefig(f'{out}/report_studies.png', dpi=110)
print(f'plot: {out}/report_studies.png')
PY
