#!/usr/bin/env bash
# CLI smoke test of `thaw render` on bad input (issue 3): every case must exit with code 2, print
# exactly one line on stderr naming the problem, and leave no output file (not even a temporary).
# usage: check_render_bad_input.sh THAW_EXECUTABLE SOURCE_DIR
set -u
thaw=$1; src=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
good="$src/data/scenes/s1_ice_shell.toml"
cp -r "$src/data/scenes/meshes" "$work/meshes"
failures=0

# expect_bad NAME EXPECTED_FRAGMENT ARGS...: runs thaw render ARGS (-o $work/out.png unless
# OUT is set to another path)
expect_bad() {
  local name=$1 fragment=$2; shift 2
  rm -rf "$work"/out.* "$work/err"
  "$thaw" render "$@" -o "${OUT:-$work/out.png}" --quiet 2>"$work/err" >/dev/null
  local code=$? lines
  lines=$(wc -l <"$work/err")
  if [ "$code" -ne 2 ]; then echo "FAIL $name: exit code $code, expected 2"; failures=$((failures + 1)); fi
  if [ "$lines" -ne 1 ]; then echo "FAIL $name: $lines lines on stderr, expected 1"; cat "$work/err"; failures=$((failures + 1)); fi
  if ! grep -q -- "$fragment" "$work/err"; then echo "FAIL $name: stderr lacks '$fragment':"; cat "$work/err"; failures=$((failures + 1)); fi
  if compgen -G "$work/out.*" >/dev/null; then echo "FAIL $name: output file left behind"; failures=$((failures + 1)); fi
  [ "$code" -eq 2 ] && echo "ok   $name: $(cat "$work/err")"
}

# scene NAME SED_EXPRESSION: a copy of the good scene edited by sed, in $work
scene() { sed -e "$2" "$good" >"$work/$1.toml"; echo "$work/$1.toml"; }

expect_bad missing_scene "nope.toml: no such file" "$work/nope.toml"
printf 'this is = = not toml\n' >"$work/malformed.toml"
expect_bad malformed_toml "line 1" "$work/malformed.toml"
expect_bad unknown_key "unknown key" "$(scene unknown_key 's/^max_depth = 10/max_dpth = 10/')"
expect_bad unknown_medium "unknown medium 'watr'" "$(scene unknown_medium 's/inside = "water"/inside = "watr"/')"
expect_bad unknown_material "unknown material" "$(scene unknown_material 's/material = "floor"/material = "flor"/')"
expect_bad zero_width "width" "$(scene zero_width 's/^width = 640/width = 0/')"
expect_bad huge_size "height" "$(scene huge 's/^height = 640/height = 1000000/')"
expect_bad zero_up "zero vector" "$(scene zero_up 's/^up = .*/up = [0.0, 0.0, 0.0]/')"
expect_bad non_unit_up "unit vector" "$(scene non_unit_up 's/^up = .*/up = [0.0, 2.0, 0.0]/')"
expect_bad missing_obj "nothing.obj: no such file" "$(scene missing_obj 's#meshes/floor_200.obj#meshes/nothing.obj#')"
# An open dielectric mesh: drop the last face of the icosphere.
head -n -1 "$work/meshes/sphere_r0.7.obj" >"$work/meshes/open.obj"
expect_bad open_mesh "closed" "$(scene open_mesh 's#shape = "sphere"#shape = "mesh"\nfile = "meshes/open.obj"#; /^center = /d; /^radius = /d')"
printf 'v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n' >"$work/meshes/nan.obj"
expect_bad nan_obj "line 2" "$(scene nan_obj 's#meshes/floor_200.obj#meshes/nan.obj#')"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >"$work/meshes/badindex.obj"
expect_bad bad_index "refers to vertex 9 but the file has only 3 vertices" "$(scene bad_index 's#meshes/floor_200.obj#meshes/badindex.obj#')"
: >"$work/meshes/empty.obj"
expect_bad empty_obj "no faces" "$(scene empty_obj 's#meshes/floor_200.obj#meshes/empty.obj#')"
expect_bad nan_rotation "rotate_deg" "$(scene nan_rotation 's#meshes/floor_200.obj"#meshes/floor_200.obj"\nrotate_deg = [0.0, nan, 0.0]#')"
expect_bad bad_noise_pattern "pattern" "$(scene bad_noise 's#^checker = .*#noise = { pattern = "marble", colors = [[0.9, 0.9, 0.9], [0.1, 0.1, 0.1]], scale = 0.5 }#')"
expect_bad zero_light_radius "lights\[0\].radius" "$(scene zero_radius 's/^kind = "point"/kind = "sphere"\nradius = 0.0/')"
expect_bad negative_light_radius "positive radius" "$(scene neg_radius 's/^kind = "point"/kind = "sphere"\nradius = -0.5/')"
expect_bad light_in_opaque_object "inside opaque object 'lamp_shade'" "$(scene light_inside 's/^kind = "point"/kind = "sphere"\nradius = 0.2/; $a [[objects]]\nname = "lamp_shade"\nshape = "sphere"\ncenter = [-4.0, 6.0, 4.0]\nradius = 1.0\nmaterial = "floor"')"
expect_bad unknown_filter '(got "lanczos")' "$(scene unknown_filter 's/^max_depth = 10/max_depth = 10\nfilter = "lanczos"/')"
expect_bad bad_filter_radius "filter_radius" "$(scene bad_filter_radius 's/^max_depth = 10/max_depth = 10\nfilter_radius = 9.0/')"
expect_bad bad_min_samples "min_samples" "$(scene bad_min_samples 's/^max_depth = 10/max_depth = 10\nmin_samples = 0/')"
# [caustics] (issue 10): absurd photon counts and a negative radius (s1 has caustics.enabled = false).
expect_bad zero_photons "caustics.photons" "$(scene zero_photons 's/^enabled = false/enabled = true\nphotons = 0/')"
expect_bad negative_photons "caustics.photons" "$(scene negative_photons 's/^enabled = false/photons = -100/')"
expect_bad huge_photons "between 1 and 1e7" "$(scene huge_photons 's/^enabled = false/photons = 5000000000/')"
expect_bad negative_radius "caustics.radius" "$(scene negative_radius 's/^enabled = false/radius = -0.01/')"
expect_bad bad_enabled "caustics.enabled" "$(scene bad_enabled 's/^enabled = false/enabled = "no"/')"
expect_bad bad_cli_width "--width" "$good" --width 0
expect_bad bad_png_bits "--png-bits" "$good" --png-bits 12
# [environment] kind = "latlong": the file's problems and the keys (issue 10)
env() { scene "$1" "s#^\[camera\]#[environment]\nkind = \"latlong\"\n$2\n\n[camera]#"; }
expect_bad env_missing "environment.file.*no_sky.hdr' no such file" "$(env env_missing 'file = "no_sky.hdr"')"
expect_bad env_not_hdr "environment.file.*is not a Radiance HDR image" "$(env env_not_hdr "file = \"$good\"")"
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n%s' "$(head -c 16 /dev/zero | tr '\0' 'A')" >"$work/square.hdr"
expect_bad env_square "twice as wide as high" "$(env env_square "file = \"$work/square.hdr\"")"
expect_bad env_intensity "environment.intensity" "$(env env_intensity "file = \"$src/data/environments/studio.hdr\"\nintensity = -1.0")"
expect_bad env_rotation "environment.rotation_deg" "$(env env_rotation "file = \"$src/data/environments/studio.hdr\"\nrotation_deg = 1000.0")"
head -c 9000 "$src/data/environments/studio.hdr" >"$work/cut.hdr"
expect_bad env_truncated "environment.file.*cut.hdr' is truncated" "$(env env_truncated "file = \"$work/cut.hdr\"")"
"$thaw" render "$good" --width 64 --height 32 -o "$work/map.exr" --quiet >/dev/null 2>&1
head -c 2000 "$work/map.exr" >"$work/cut.exr"
expect_bad env_truncated_exr "environment.file.*cut.exr' is not a readable OpenEXR image" "$(env env_truncated_exr "file = \"$work/cut.exr\"")"
# Rough surfaces (issue 26): roughness outside [0, 1] on a dielectric object or a material; a
# roughness on a matte material is an unknown key.
expect_bad rough_object "roughness.*must be between 0 and 1" "$(scene rough_object 's/^inside = "water"/inside = "water"\nroughness = 1.5/')"
expect_bad rough_negative "roughness.*must be between 0 and 1" "$(scene rough_negative 's/^inside = "water"/inside = "water"\nroughness = -0.1/')"
expect_bad rough_matte "unknown key" "$(scene rough_matte 's/^kind = "matte"/kind = "matte"\nroughness = 0.3/')"
# Scattering media (issue 26): a negative coefficient, |asymmetry| >= 1, a bubble fraction of 1.
expect_bad negative_scattering "media.ice.scattering_per_m.*must be between 0" "$(scene neg_scatter 's/^\[media.ice\]/[media.ice]\nscattering_per_m = -3.0/')"
expect_bad asymmetry_one "asymmetry.*(-1, 1)" "$(scene asym_one 's/^\[media.ice\]/[media.ice]\nscattering_per_m = 3.0\nasymmetry = 1.0/')"
expect_bad bubble_fraction "air_fraction.*\[0, 1)" "$(scene bubbles 's/^\[media.ice\]/[media.ice]\nbubbles = { air_fraction = 1.0, radius_m = 5e-5 }/')"
OUT="$work/out.jpg" expect_bad bad_extension "unsupported output format" "$good"
OUT="$work/no/such/dir/out.png" expect_bad missing_out_dir "does not exist" "$good"

# A flag that overrides an [image] key is checked by that key's rule (render/scene/scene_rules.h):
# the same bad value gives the same problem from the command line and from the file.
# problem_of ARGS...: the problem thaw render reports (without file, line and key or flag), or
# "exit N" unless it exits with code 2
problem_of() {
  local err code
  err=$("$thaw" render "$@" -o "$work/out.png" --quiet 2>&1 >/dev/null)
  code=$?
  if [ "$code" -ne 2 ]; then echo "exit $code"; return; fi
  printf '%s\n' "$err" | sed -e "s/^.*\(--[a-z-]*\|key '[a-z_.]*'\): //"
}
# same_problem NAME SED_EXPRESSION FLAG VALUE
same_problem() {
  local name=$1 edit=$2; shift 2
  local from_file from_flag
  from_file=$(problem_of "$(scene "$name" "$edit")")
  from_flag=$(problem_of "$good" "$@")
  if [ -n "$from_file" ] && [ "${from_file#exit }" = "$from_file" ] && [ "$from_file" = "$from_flag" ]; then
    echo "ok   $name: file and $1 both say: $from_flag"
  else
    echo "FAIL $name: file says '$from_file', $1 says '$from_flag'"; failures=$((failures + 1))
  fi
}
same_problem same_width 's/^width = 640/width = 0/' --width 0
same_problem same_height 's/^height = 640/height = 20000/' --height 20000
same_problem same_spp 's/^samples_per_pixel = 1/samples_per_pixel = 70000/' --spp 70000
same_problem same_depth 's/^max_depth = 10/max_depth = 257/' --max-depth 257
same_problem same_wavelengths 's/^max_depth = 10/max_depth = 10\ndispersion_wavelengths = 2/' --dispersion-wavelengths 2
same_problem same_resolution 's/^max_depth = 10/max_depth = 10\ndispersion_resolution_nm = 0.01/' --dispersion-resolution-nm 0.01
same_problem same_dispersion 's/^max_depth = 10/max_depth = 10\ndispersion = "rainbow"/' --dispersion rainbow
same_problem same_pattern 's/^max_depth = 10/max_depth = 10\nwavelength_pattern = "random"/' --wavelength-pattern random

# And the good scene renders (tiny) and leaves exactly the PNG.
if "$thaw" render "$good" -o "$work/out.png" --width 24 --height 24 --quiet && [ -s "$work/out.png" ]; then
  echo "ok   good scene renders"
else
  echo "FAIL good scene"; failures=$((failures + 1))
fi
[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
