#!/usr/bin/env bash
# Keeps the architecture honest (STYLE.md): CGAL only in src/mesh, VTK only in src/inspect,
# sim/ and render/ never include each other (nor CGAL/VTK), src/common includes no other folder.
set -u
root=${1:?usage: check_include_rules.sh REPO_ROOT}
cd "$root"
fail=0
check() { # $1 description, $2 folders to scan, $3 forbidden include regex
  local hits
  hits=$(grep -rnE "^\s*#\s*include\s*[<\"]($3)" $2 --include='*.h' --include='*.cpp' 2>/dev/null)
  if [ -n "$hits" ]; then echo "violation: $1"; echo "$hits"; fail=1; fi
}
check "CGAL outside src/mesh" "sim render src/common src/inspect src/pipeline src/cli" "CGAL/"
check "VTK outside src/inspect" "sim render src/common src/mesh src/pipeline src/cli" "vtk"
check "sim includes render" "sim" "render/"
check "render includes sim" "render" "sim/"
check "sim/render include src/ beyond common" "sim render" "src/(mesh|inspect|pipeline|cli)/"
check "common includes a higher folder" "src/common" "(sim|render|src/mesh|src/inspect|src/pipeline|src/cli)/"
hits=$(grep -rnE '^\s*#\s*include\s*["<]sim/' src/mesh src/inspect --include='*.h' --include='*.cpp' 2>/dev/null | grep -vE '["<]sim/io/')
if [ -n "$hits" ]; then echo "violation: mesh/inspect include more of sim than its I/O"; echo "$hits"; fail=1; fi
if [ $fail -ne 0 ]; then echo "include rules: FAILED"; exit 1; fi
echo "include rules: OK"
