// Scenarios for Python: SimScenario is a sim::Scenario checked by the same parser and rules as
// `thaw simulate` (sim/format/scenario_file.h), made from a file, from TOML text (what
// thaw.Scenario.from_dict and .with_ write) or from the built-in default. The document's text is
// kept by the Python side (thaw.Scenario), for thaw.run and for edits.
#include <filesystem>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <nlohmann/json.hpp>

#include "base/text_file.h"
#include "python/bindings.h"
#include "sim/format/scenario_file.h"
#include "sim/simulate.h"

namespace py = pybind11;

namespace thaw::python {

void bind_scenario(py::module_& m) {
  py::class_<sim::Scenario>(m, "SimScenario",
                            "The simulation part of a scenario, parsed and checked (sim::Scenario)")
      .def_readonly("source_name", &sim::Scenario::source_name)
      .def(
          "parameters_json", [](const sim::Scenario& s) { return sim::scenario_to_json(s).dump(); },
          "Every effective parameter as JSON text, keyed as in the scenario file (summary.json's "
          "\"parameters\")")
      .def(
          "output_times", [](const sim::Scenario& s) { return sim::output_times(s); },
          "The output times [s]: 0, interval, 2 interval, ..., duration_s")
      .def_property_readonly(
          "is_grid", [](const sim::Scenario& s) { return s.grid != sim::GridGeometry::none; });

  m.def(
      "load_scenario",
      [](const std::filesystem::path& path) {
        // Parsed as `thaw simulate FILE` parses it (same messages), then read as text.
        sim::Scenario scenario = sim::read_scenario_file(path);
        std::string text = read_text_file(path, "a TOML file", kMaxTomlFileBytes);
        return py::make_tuple(std::move(scenario), std::move(text));
      },
      py::arg("path"), "(SimScenario, text) of a scenario file; raises thaw.UserError");
  m.def(
      "parse_scenario",
      [](const std::string& text, const std::string& source_name) {
        return sim::parse_scenario_string(text, source_name);
      },
      py::arg("text"), py::arg("source_name"),
      "SimScenario of scenario TOML text; raises thaw.UserError naming source_name");
  m.def(
      "default_scenario",
      [] { return py::make_tuple(sim::default_scenario(), sim::default_scenario_text()); },
      "(SimScenario, text) of the built-in default scenario");
}

}  // namespace thaw::python
