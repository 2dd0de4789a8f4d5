#!/usr/bin/env bash
# Where a frame's CPU time goes (issue 30, item 1: "where a frame's time goes outside traversal"):
# samples `ray_limit ... frames-only` (the frame rendered and its PNG written RUNS times, photon
# pass included, nothing else) with `perf record` and sums the samples' own time (no children)
# by what the function does: traversal, the shadow cones' culling, the photon pass, the photon
# lookup, texture filtering, shading, sampling and the tile loop, the PNG, the OpenMP runtime
# (threads waiting for work) and the kernel. Functions inlined into another count as that one
# (a camera ray's generation is inlined into the tile loop, a Fresnel term into shading), so the
# split is by the code that ran, to the granularity of the symbols the compiler kept.
# Needs perf (linux-perf) and ray_limit (Embree found at configure time).
# usage: bench/render/frame_profile.sh [scene.toml | RUN_DIR] [threads] [runs] [frame]
#   (RAY_LIMIT=path/to/ray_limit, FREQ=1999 samples per second)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
ray_limit="${RAY_LIMIT:-$here/../../build/bench/render/ray_limit}"
scene="${1:-$here/../../data/scenes/s1_ice_shell_mesh.toml}"
threads="${2:-2}"
runs="${3:-3}"
frame="${4:-30}"
data="$(mktemp -d)/perf.data"
trap 'rm -rf "$(dirname "$data")"' EXIT
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), load $(cut -d' ' -f1-3 /proc/loadavg)"
perf record -q -o "$data" -F "${FREQ:-1999}" -- "$ray_limit" "$scene" "$threads" "$runs" "$frame" frames-only
echo "load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
# Own time per symbol, summed by category; the categories' shares of all samples, largest first.
perf report -i "$data" --no-children --sort dso,sym --stdio -g none -t ';' 2>/dev/null |
  grep -v '^#' | grep -v '^$' |
  awk -F';' '
  function category(dso, s) {
    if (dso ~ /kernel/) return "kernel"
    if (dso ~ /libgomp/) return "OpenMP runtime (threads waiting for work)"
    if (dso ~ /libz/ || s ~ /encode_png|compress_band|write_png|agx_view|curve|srgb/) return "PNG (view transform, deflate)"
    if (s ~ /light_unoccluded|any_leaf|EnvironmentOccluders|ConeBoxes/) return "shadow-cone culling (light_unoccluded)"
    if (s ~ /PhotonMap::lookup|PhotonMap::irradiance_at/) return "photon lookup (caustic gather)"
    if (s ~ /photon::/) return "photon pass (tracing, Halton, kd-tree build)"
    if (s ~ /Bvh::|intersect_triangle|intersect_sphere|intersect_box|intersect_plane|Scene::intersect|Scene::occluded/) return "traversal (BVH, primitive tests)"
    if (s ~ /Texture::/) return "texture filtering (checker footprints)"
    if (s ~ /render_image_tiles|PixelSampler|sampling::|Camera|Filter::/) return "tile loop, camera rays, pixel filter, sampling"
    if (s ~ /WhittedShading|interaction|irradiance|IrradianceSH|sphere_light|fresnel|microfacet|media::/ || dso ~ /libm/) return "shading (lights, environment, Fresnel, libm)"
    return "other"
  }
  { p = $1; sub(/%/, "", p); gsub(/ /, "", $2); sum[category($2, $3)] += p }
  END { for (c in sum) printf "%6.1f %%  %s\n", sum[c], c }' | sort -rn
