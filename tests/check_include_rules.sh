#!/usr/bin/env bash
# Keeps the architecture honest (STYLE.md): CGAL only in src/mesh, VTK only in src/inspect and
# src/gui (its 3D view), Qt only in src/gui, sim/ and render/ never include each other (nor
# CGAL/VTK/Qt), src/common includes no other folder, src/meshio (the mesh files, a plain library
# like src/common) includes only src/common, src/cli sees src/gui only through gui.h, and the
# cores of common, meshio, sim and render include no TOML or JSON.
set -u
root=${1:?usage: check_include_rules.sh REPO_ROOT}
cd "$root"
fail=0
check() { # $1 description, $2 folders to scan, $3 forbidden include regex
  local hits
  hits=$(grep -rnE "^\s*#\s*include\s*[<\"]($3)" $2 --include='*.h' --include='*.cpp' 2>/dev/null)
  if [ -n "$hits" ]; then echo "violation: $1"; echo "$hits"; fail=1; fi
}
check "CGAL outside src/mesh" "sim render src/common src/meshio src/inspect src/pipeline src/cli src/gui" "CGAL/"
check "VTK outside src/inspect and src/gui" "sim render src/common src/meshio src/mesh src/pipeline src/cli" "vtk"
check "OpenVDB outside src/pipeline/handoff_vdb.cpp" "sim render src/common src/meshio src/mesh src/inspect src/cli src/gui src/pipeline/*.h" "openvdb/"
hits=$(grep -lrE '^\s*#\s*include\s*[<"]openvdb/' src/pipeline --include='*.cpp' 2>/dev/null | grep -v 'src/pipeline/handoff_vdb.cpp')
if [ -n "$hits" ]; then echo "violation: OpenVDB outside src/pipeline/handoff_vdb.cpp"; echo "$hits"; fail=1; fi
check "sim includes render" "sim" "render/"
check "render includes sim" "render" "sim/"
check "Qt outside src/gui" "sim render src/common src/meshio src/mesh src/inspect src/pipeline src/cli" "(Q[A-Z][A-Za-z]*|Qt[A-Za-z]*/|QVTK[A-Za-z]*)(\.h)?>"
check "sim/render include src/ beyond common" "sim render" "src/(mesh|inspect|pipeline|cli|gui)/"
check "common includes a higher folder" "src/common" "(sim|render|src/mesh|src/meshio|src/inspect|src/pipeline|src/cli|src/gui)/"
check "meshio includes more than src/common" "src/meshio" "(sim|render|src/mesh|src/inspect|src/pipeline|src/cli|src/gui)/"
check "a library includes src/gui" "src/mesh src/inspect src/pipeline" "src/gui/"
hits=$(grep -rnE '^\s*#\s*include\s*["<]src/gui/' src/cli --include='*.h' --include='*.cpp' 2>/dev/null | grep -v 'src/gui/gui.h')
if [ -n "$hits" ]; then echo "violation: src/cli includes more of src/gui than its Qt-free gui.h"; echo "$hits"; fail=1; fi
hits=$(grep -rnE '^\s*#\s*include\s*["<]sim/' src/mesh src/inspect --include='*.h' --include='*.cpp' 2>/dev/null | grep -vE '["<]sim/io/')
if [ -n "$hits" ]; then echo "violation: mesh/inspect include more of sim than its I/O"; echo "$hits"; fail=1; fi
# The liftable cores (README "Layout"): thaw_common_core, thaw_meshio_core, thaw_sim_core and
# thaw_render_core include no TOML or JSON, directly or through the file-format layers' headers.
# Every file of a folder is core except the file layer's, listed here as in the CMakeLists.
formats="toml\+\+/|toml\.h|nlohmann/|src/common/toml_table\.h|src/common/json_error\.h|src/meshio/mesh_manifest\.h|sim/scenario/scenario_file\.h|sim/io/simulation_output\.h|render/scene/scene_parser\.h|render/media/medium_parser\.h|render/media/medium_library\.h"
core_files() { # $1 folder, $2 regex of its file-layer files
  find "$1" \( -name '*.h' -o -name '*.cpp' \) | grep -vE "$2" | sort
}
check_core() { # $1 description, $2 folder, $3 regex of its file-layer files
  local hits
  hits=$(core_files "$2" "$3" | xargs grep -nE "^\s*#\s*include\s*[<\"]($formats)" 2>/dev/null)
  if [ -n "$hits" ]; then echo "violation: $1 includes a file format (TOML/JSON)"; echo "$hits"; fail=1; fi
}
check_core "thaw_common_core" src/common "src/common/(toml_table|json_error)\.|\.in$"
check_core "thaw_meshio_core" src/meshio "src/meshio/mesh_manifest\."
check_core "thaw_sim_core" sim "sim/scenario/scenario_file\.|sim/io/(simulation_output|interface_history|grid_field)\.cpp"
check_core "thaw_render_core" render "render/scene/scene_parser\.|render/media/(medium_parser|medium_library)\."

if [ $fail -ne 0 ]; then echo "include rules: FAILED"; exit 1; fi
echo "include rules: OK"
