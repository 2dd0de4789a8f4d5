#pragma once
// Sub-command registration: each sub-command lives in its own command_<name>.cpp, parses its
// arguments with CLI11 and calls into a library. Argument parsing and help text only.
#include <CLI/CLI.hpp>

namespace thaw::cli {

// One line per sub-command, in the order shown by --help.
void register_simulate(CLI::App& app);   ///< thaw simulate (command_simulate.cpp)
void register_mesh(CLI::App& app);       ///< thaw mesh (command_mesh.cpp)
void register_render(CLI::App& app);     ///< thaw render (command_render.cpp)
void register_inspect(CLI::App& app);    ///< thaw inspect (command_inspect.cpp)
void register_materials(CLI::App& app);  ///< thaw materials (command_materials.cpp)
void register_run(CLI::App& app);        ///< thaw run (command_run.cpp)
void register_gui(CLI::App& app);        ///< thaw gui (command_gui.cpp)

}  // namespace thaw::cli
