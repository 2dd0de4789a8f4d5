#!/usr/bin/env bash
# RGB-path cost before/after a change (issue 5: spectral rendering must leave non-dispersive
# scenes no more than 10 % slower): renders S1 analytic and mesh (1280x1280), S4 (2000x2000) and S3
# without dispersion (1000x1000, 1 spp, as compare_povray.sh; issue 10's Whitted table) with two thaw
# binaries, interleaved run by run so that machine load affects both alike; reports the median
# wall and CPU (user + sys) time of each and their ratios, and checks the images are identical.
# usage: bench/render/compare_before_after.sh BEFORE_THAW AFTER_THAW [RUNS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
before=$(realpath "$1"); after=$(realpath "$2"); runs=${3:-5}
out=${OUT:-/tmp/thaw-bench-before-after}
mkdir -p "$out"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| scene | size | before wall [s] | after wall [s] | after/before (wall) | before CPU [s] | after CPU [s] | after/before (CPU) | identical |"
echo "|---|---|---|---|---|---|---|---|---|"
for spec in s1_ice_shell:1280x1280 s1_ice_shell_mesh:1280x1280 s4_spheres16:2000x2000 \
            s3_dispersion_nodisp:1000x1000; do
  scene=${spec%%:*}; size=${spec#*:}
  : > "$out/$scene.times"
  for ((i = 0; i < runs; ++i)); do
    for which in before after; do
      bin=$before; [ "$which" = after ] && bin=$after
      /usr/bin/time -f "$which %e %U %S" -a -o "$out/$scene.times" "$bin" render "$root/data/scenes/$scene.toml" \
        -o "$out/${scene}_$which.pfm" --width "${size%x*}" --height "${size#*x}" --threads 2 --quiet
    done
  done
  same=no; cmp -s "$out/${scene}_before.pfm" "$out/${scene}_after.pfm" && same=yes
  python3 - "$out/$scene.times" "$scene" "$size" "$same" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
def med(which, k):
    return statistics.median(float(r[1]) if k == 'wall' else float(r[2]) + float(r[3]) for r in rows if r[0] == which)
bw, aw, bc, ac = med('before', 'wall'), med('after', 'wall'), med('before', 'cpu'), med('after', 'cpu')
print(f"| {sys.argv[2]} | {sys.argv[3]} | {bw:.3f} | {aw:.3f} | {aw/bw:.3f} | {bc:.3f} | {ac:.3f} | {ac/bc:.3f} | {sys.argv[4]} |")
PY
done
