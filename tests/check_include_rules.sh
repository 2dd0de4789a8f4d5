#!/usr/bin/env bash
# Keeps the architecture honest (docs/architecture.md, STYLE.md) with folder rules only: the
# arrows point down, cli/gui -> pipeline -> {sim, render, mesh, inspect} -> base, and a core is its
# folder minus format/ (no TOML, no JSON). Heavy dependencies stay in one folder each: CGAL in
# src/mesh, VTK in src/inspect and src/gui, Qt in src/gui, OpenVDB in src/pipeline/handoff_vdb.cpp.
set -u
root=${1:?usage: check_include_rules.sh REPO_ROOT}
cd "$root"
fail=0
inc='^\s*#\s*include\s*[<"]'
# files_of <folder> [core]: the folder's sources; with "core", without its format/ subfolders.
files_of() {
  if [ "${2:-}" = core ]; then
    find "$1" \( -name '*.h' -o -name '*.cpp' \) -not -path '*/format/*' | sort
  else
    find "$1" \( -name '*.h' -o -name '*.cpp' \) | sort
  fi
}
check() { # $1 description, $2 file list, $3 forbidden include regex
  local hits
  hits=$(echo "$2" | xargs -r grep -nE "$inc($3)" 2>/dev/null)
  if [ -n "$hits" ]; then echo "violation: $1"; echo "$hits"; fail=1; fi
}
all_but() { # the sources of every top folder except those named
  local folders="base sim render src/mesh src/inspect src/pipeline src/cli src/gui python" f out=""
  for f in $folders; do case " $* " in *" $f "*) ;; *) out+="$(files_of "$f")"$'\n' ;; esac; done
  echo "$out"
}
formats='toml\+\+/|toml\.h|nlohmann/|base/format/|sim/format/|render/format/'

# Arrows point down: nothing climbs into src/, and sim and render never see each other.
check "base includes a folder above it" "$(files_of base)" "(sim|render|src)/"
check "sim includes render/ or src/" "$(files_of sim)" "(render|src)/"
check "render includes sim/ or src/" "$(files_of render)" "(sim|src)/"
check "mesh or inspect include sim/ beyond sim/format" "$(files_of src/mesh; files_of src/inspect)" \
  "sim/(grid|scenario|shape|stefan1d|reference|simulate)"
check "a library or a command includes python/ (the Python module is on top, like the CLI)" \
  "$(all_but python)" "python/"
check "mesh and inspect include each other (they share base/work_farm.h)" \
  "$(files_of src/inspect)" "src/mesh/"
check "mesh and inspect include each other (they share base/work_farm.h)" \
  "$(files_of src/mesh)" "src/inspect/"
check "a library includes src/gui" "$(files_of src/mesh; files_of src/inspect; files_of src/pipeline)" "src/gui/"
hits=$(files_of src/cli | xargs grep -nE "$inc"'src/gui/' 2>/dev/null | grep -v 'src/gui/gui.h')
if [ -n "$hits" ]; then echo "violation: src/cli includes more of src/gui than its Qt-free gui.h"; echo "$hits"; fail=1; fi

# A core is its folder minus format/: no TOML or JSON, directly or through a format header.
for core in base sim render; do
  check "the core of $core/ includes a file format (TOML/JSON)" "$(files_of $core core)" "$formats"
done

# One folder per heavy dependency.
check "CGAL outside src/mesh" "$(all_but src/mesh)" "CGAL/"
check "VTK outside src/inspect and src/gui" "$(all_but src/inspect src/gui)" "vtk"
check "Qt outside src/gui" "$(all_but src/gui)" "(Q[A-Z][A-Za-z]*|Qt[A-Za-z]*/|QVTK[A-Za-z]*)(\.h)?>"
vdb=$( (all_but; ) | grep -v '^src/pipeline/handoff_vdb.cpp$')
check "OpenVDB outside src/pipeline/handoff_vdb.cpp" "$vdb" "openvdb/"

if [ $fail -ne 0 ]; then echo "include rules: FAILED"; exit 1; fi
echo "include rules: OK"
