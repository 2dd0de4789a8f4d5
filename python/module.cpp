// The `thaw._thaw` extension module: a thin face over thaw_sim, thaw_render, thaw_mesh and the
// pipeline for the pure-Python package python/thaw/ (which holds the public API). Nothing here
// computes: every call goes to the library function the command line calls.
#include <pybind11/pybind11.h>

#include "python/bindings.h"
#include "thaw_version.h"

PYBIND11_MODULE(_thaw, m) {
  m.doc() = "thaw's C++ libraries (use the `thaw` package, not this module)";
  m.attr("__version__") = THAW_VERSION_STRING;
  thaw::python::bind_errors(m);
  thaw::python::bind_scenario(m);
  thaw::python::bind_result(m);
  thaw::python::bind_render(m);
  thaw::python::bind_run(m);
}
