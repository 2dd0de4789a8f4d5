#pragma once
// The parts of the `thaw._thaw` extension module (python/module.cpp puts them together): each
// binds one face of the libraries. The public API, its docstrings and the pure-Python parts
// (Scenario, the TOML writer, the exception classes) are in python/thaw/.
#include <pybind11/pybind11.h>

namespace thaw::python {

/// Exception translation: thaw::UserError -> thaw.UserError, thaw::Interrupted ->
/// KeyboardInterrupt, other C++ exceptions -> thaw.InternalError (errors.cpp).
void bind_errors(pybind11::module_& m);
/// SimScenario (a checked sim::Scenario) and its parsers (scenario_binding.cpp).
void bind_scenario(pybind11::module_& m);
/// Result (a sim::SimulationResult), simulate() and mesh() (result_binding.cpp).
void bind_result(pybind11::module_& m);
/// render() (render_binding.cpp).
void bind_render(pybind11::module_& m);
/// run(): thaw run's pipeline (run_binding.cpp).
void bind_run(pybind11::module_& m);

}  // namespace thaw::python
