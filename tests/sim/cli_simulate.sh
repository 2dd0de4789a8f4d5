#!/usr/bin/env bash
# Smoke and bad-input tests of `thaw simulate` (registered by tests/sim/CMakeLists.txt).
#   cli_simulate.sh THAW SOURCE_DIR WORK_DIR
# Good runs: the result folder holds interfaces.csv, profiles/ and summary.json. Bad input: exit
# code 2, exactly one line on stderr naming the file and the key or problem, and the result
# folder untouched (absent if it was absent, unchanged if it existed).
set -u
thaw=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail=0
note() { echo "FAIL: $*" >&2; fail=1; }

check_good() {  # name, args...
  local name=$1; shift
  local out="$work/$name"
  if ! "$thaw" simulate "$@" --out "$out" -q; then note "$name: exit code $?"; return; fi
  for f in interfaces.csv summary.json profiles/step_000000.csv; do
    [ -s "$out/$f" ] || note "$name: missing $f"
  done
  head -1 "$out/interfaces.csv" | grep -q '^step,time_s,inner_radius_m,outer_radius_m,liquid_volume_m3,ice_volume_m3,energy_balance_error' \
    || note "$name: interfaces.csv header"
  ls -A "$work" | grep -q "^$name\.tmp-" && note "$name: staging folder left behind"
}

check_bad() {  # name, expected substring 1, expected substring 2, scenario text (or @path)
  local name=$1 want1=$2 want2=$3 text=$4
  local scenario="$work/$name.toml" out="$work/$name-out"
  if [ "${text:0:1}" = "@" ]; then scenario=${text:1}; else printf '%s\n' "$text" > "$scenario"; fi
  mkdir -p "$out" && echo keep > "$out/marker"
  "$thaw" simulate "$scenario" --out "$out" -q 2> "$work/$name.err"
  local code=$?
  [ $code -eq 2 ] || note "$name: exit code $code, expected 2"
  [ "$(wc -l < "$work/$name.err")" -eq 1 ] || note "$name: stderr is not one line: $(cat "$work/$name.err")"
  grep -qF -- "$want1" "$work/$name.err" || note "$name: stderr lacks '$want1': $(cat "$work/$name.err")"
  grep -qF -- "$want2" "$work/$name.err" || note "$name: stderr lacks '$want2': $(cat "$work/$name.err")"
  [ "$(ls -A "$out")" = "marker" ] || note "$name: result folder changed: $(ls -A "$out")"
  # and with no result folder at all, none appears
  rm -rf "$out"
  "$thaw" simulate "$scenario" --out "$out" -q 2>/dev/null
  [ -e "$out" ] && note "$name: result folder created on bad input"
  ls -A "$work" | grep -q "^$name-out\.tmp-" && note "$name: temporary folder left behind"
}

check_good default
check_good drop "$src/data/scenarios/water_drop_freezing.toml"
# thaw run's sections are thaw run's to check: mistakes there never stop thaw simulate (issue 12).
sed -e 's/^\[render.image\]/[render.image]\nwidht = 1/' -e 's/^\[film\]/[film]\nbogus = 1/' \
  -e 's/^\[mesh\]/[mesh]\nedge_lenght_m = "x"/' "$src/data/scenarios/default.toml" > "$work/foreign_errors.toml"
grep -q '^widht = 1' "$work/foreign_errors.toml" || note "foreign_errors: fixture not made"
check_good foreign_errors "$work/foreign_errors.toml"
grep -q '"kind": "core_frozen"' "$work/drop/summary.json" || note "drop: no core_frozen event"
grep -q '"kind": "break_through"' "$work/default/summary.json" || note "default: no break_through event"

# The energy balance is reported: the summary line gives the largest per-step error and every
# row of interfaces.csv the cumulative one; both within the issue's 1e-8 of the reference energy
# (measured ~1e-15 per step), for the 1D default and an axisymmetric grid run.
check_energy() {  # name, args...
  local name=$1; shift
  local out="$work/$name"
  "$thaw" simulate "$@" --out "$out" > "$work/$name.stdout" 2>/dev/null || { note "$name: exit code $?"; return; }
  local per_step
  per_step=$(sed -n 's/.*max energy balance error \([0-9.e+-]*\),.*/\1/p' "$work/$name.stdout")
  [ -n "$per_step" ] || { note "$name: no energy balance in the summary line"; return; }
  awk -v e="$per_step" 'BEGIN { exit !(e < 1e-8) }' || note "$name: per-step energy error $per_step"
  awk -F, 'NR > 1 && !($7 < 1e-8) { bad = 1 } END { exit bad }' "$out/interfaces.csv" \
    || note "$name: a cumulative energy_balance_error above 1e-8"
}
check_energy energy_default
check_energy energy_grid "$src/data/scenarios/bored_cylinder.toml"

base=$("$thaw" simulate --print-default)
check_bad missing_file "nonexistent.toml" "no such file" "@$work/nonexistent.toml"
check_bad malformed "malformed TOML" "line" "[simulation"
check_bad unknown_key "shell.inner_radus_m" "unknown key" "${base/inner_radius_m/inner_radus_m}"
check_bad negative "shell.inner_radius_m" "must not be negative" "${base/inner_radius_m = 0.02/inner_radius_m = -0.02}"
check_bad nan "shell.outer_radius_m" "finite" "${base/outer_radius_m = 0.03/outer_radius_m = nan}"
check_bad inf "simulation.duration_s" "finite" "${base/duration_s = 3600.0/duration_s = inf}"
check_bad inner_gt_outer "inner_radius_m" "larger than outer_radius_m" "${base/inner_radius_m = 0.02/inner_radius_m = 0.04}"
check_bad zero_duration "simulation.duration_s" "must be positive" "${base/duration_s = 3600.0/duration_s = 0.0}"
check_bad long_interval "simulation.output_interval_s" "longer than the run" "${base/output_interval_s = 60.0/output_interval_s = 7200.0}"
hot=${base/kind = \"convective\"/kind = \"temperature\"}
hot=${hot/heat_transfer_coefficient_w_m2k = 50.0/}
check_bad hot_surface "outer_boundary.temperature_c" "ill-posed" "$hot"
# [outer_boundary] kind = "air" (issue 25): a good run, and every range it names.
air=${base/kind = \"convective\"/kind = \"air\"}
air=${air/heat_transfer_coefficient_w_m2k = 50.0/relative_humidity = 0.5}
check_good room_air "$src/data/scenarios/ice_sphere_room_air.toml"
grep -q '"kind": "fully_melted"' "$work/room_air/summary.json" || note "room_air: no fully_melted event"
check_good air "$(printf '%s\n' "$air" > "$work/air.toml"; echo "$work/air.toml")"
check_bad air_humidity "outer_boundary.relative_humidity" "outside [0, 1]" "${air/relative_humidity = 0.5/relative_humidity = 1.5}"
check_bad air_emissivity "outer_boundary.emissivity" "outside (0, 1]" "${air/relative_humidity = 0.5/relative_humidity = 0.5
emissivity = 0.0}"
check_bad air_speed "outer_boundary.speed_m_s" "[3.5, 7.6e4]" "${air/relative_humidity = 0.5/relative_humidity = 0.5
speed_m_s = 60.0}"
check_bad air_temperature "outer_boundary.temperature_c" "[-40, 50] C" "${air/temperature_c = 25.0/temperature_c = 80.0}"
# Grid runs ([shape]): a shipped scenario shortened to one minute writes fields/*.grid (the
# hollow cube without its flow: ~45 s of CPU in 3D with it; the bored cylinder flows).
for name in bored_cylinder hollow_cube; do
  flow=''
  [ "$name" = hollow_cube ] && flow='s/^max_step_s = 10.0/max_step_s = 10.0\nflow = "none"/'
  sed -e 's/^duration_s = 3600.0/duration_s = 60.0/' -e 's/^output_interval_s = 60.0/output_interval_s = 30.0/' \
    -e "$flow" "$src/data/scenarios/$name.toml" > "$work/$name.toml"
  out="$work/grid_$name"
  if ! "$thaw" simulate "$work/$name.toml" --out "$out" -q; then note "grid $name: exit code"; continue; fi
  for f in interfaces.csv summary.json fields/step_000000.grid fields/step_000002.grid; do
    [ -s "$out/$f" ] || note "grid $name: missing $f"
  done
done
grid='[simulation]
geometry = "3d"
duration_s = 60.0
output_interval_s = 30.0
[shape]
outer = { kind = "box", size_m = [0.04, 0.04, 0.04] }
cavity = { kind = "box", size_m = [0.024, 0.024, 0.024] }
[water]
initial_temperature_c = 10.0
[ice]
initial_temperature_c = -5.0
[outer_boundary]
kind = "convective"
temperature_c = 25.0
heat_transfer_coefficient_w_m2k = 50.0'
check_bad grid_cube_axisymmetric "shape.outer.kind" "only spheres and vertical cylinders" "${grid/\"3d\"/\"axisymmetric\"}"
check_bad grid_cavity_touching "shape.cavity" "strictly inside" "${grid/\[0.024, 0.024, 0.024\]/[0.04, 0.024, 0.024]}"
check_bad grid_too_coarse "cell_size_m" "at least 3 are needed" "${grid/output_interval_s = 30.0/output_interval_s = 30.0
cell_size_m = 0.004}"
check_bad grid_unknown_kind "shape.outer" "unknown kind 'cube'" "${grid/kind = \"box\", size_m = \[0.04, 0.04, 0.04\]/kind = \"cube\"}"
check_bad grid_negative_size "shape.outer.size_m" "positive" "${grid/\[0.04, 0.04, 0.04\]/[0.04, -0.04, 0.04]}"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n' > "$work/open.obj"
check_bad grid_open_obj "open.obj" "at least 4 triangles" "${grid/kind = \"box\", size_m = \[0.04, 0.04, 0.04\]/kind = \"obj\", file = \"$work/open.obj\", scale = 0.05}"
check_bad grid_cavity_outside "shape.cavity" "strictly inside" "${grid/cavity = \{ kind = \"box\", size_m = \[0.024, 0.024, 0.024\] \}/cavity = { kind = \"sphere\", radius_m = 0.005, center_m = [0.1, 0.0, 0.0] \}}"
check_bad grid_zero_size "shape.cavity.radius_m" "must be positive (got 0)" "${grid/cavity = \{ kind = \"box\", size_m = \[0.024, 0.024, 0.024\] \}/cavity = { kind = \"sphere\", radius_m = 0.0 \}}"
# a cube with one face missing (open) and two tetrahedra sharing an edge (non-manifold)
printf 'v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nf 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n' > "$work/open_cube.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nv 0 0 -1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 2 5\nf 1 6 2\nf 1 5 6\nf 2 6 5\n' > "$work/two_tets.obj"
solid=${grid/cavity = \{ kind = \"box\", size_m = \[0.024, 0.024, 0.024\] \}/}
check_bad grid_open_cube_obj "open_cube.obj" "not closed" "${solid/kind = \"box\", size_m = \[0.04, 0.04, 0.04\]/kind = \"obj\", file = \"$work/open_cube.obj\", scale = 0.02}"
check_bad grid_non_manifold_obj "two_tets.obj" "not manifold" "${solid/kind = \"box\", size_m = \[0.04, 0.04, 0.04\]/kind = \"obj\", file = \"$work/two_tets.obj\", scale = 0.02}"
# A step cap below the grid's physical floor is refused before any work (it once ran for ever).
for tiny in 1e-9 1e-320; do
  check_bad "grid_step_$tiny" "simulation.max_step_s" "below the smallest useful step" "${grid/output_interval_s = 30.0/output_interval_s = 30.0
max_step_s = $tiny}"
done
# A grid run ends promptly on SIGTERM or SIGINT, mid-interval (steps of 0.01 s, outputs 30 s
# apart; it used to run on until the next output): exit 130, no result folder. The solver stops
# within a second of the flag (tests/sim/grid/test_grid_time_stepper.cpp); here the bound also
# covers signal delivery and exit on a loaded machine. The water conducts only (flow = "none"):
# a 1 mm cell is too coarse for the flow's boundary layer, which thaw refuses. (A run with the flow
# on is interrupted between the same steps; no test here signals one yet.)
for sig in TERM INT; do
  printf '%s\n' "${grid/output_interval_s = 30.0/output_interval_s = 30.0
cell_size_m = 0.001
flow = \"none\"
max_step_s = 0.01}" > "$work/grid_signal.toml"
  rm -rf "$work/grid_signal-out"
  "$thaw" simulate "$work/grid_signal.toml" --out "$work/grid_signal-out" -q 2> "$work/grid_signal.err" &
  pid=$!
  sleep 3
  start=$(date +%s%N)
  kill -$sig $pid
  wait $pid
  code=$?
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  [ $code -eq 130 ] || note "grid SIG$sig: exit code $code, expected 130: $(cat "$work/grid_signal.err")"
  [ $ms -lt 3000 ] || note "grid SIG$sig: took $ms ms to end"
  [ -e "$work/grid_signal-out" ] && note "grid SIG$sig: result folder written"
done
exit $fail
