// thaw-full: every sub-command in one process (built as libexec/thaw-full). The `thaw` launcher
// (main.cpp) runs the light commands itself and hands the others to this program, which links
// VTK, CGAL, Qt and MPI. Run directly, it behaves exactly as `thaw`.
#include <CLI/CLI.hpp>

#include "src/cli/app.h"
#include "src/cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app;
  thaw::cli::describe_app(app);
  thaw::cli::register_simulate(app);
  thaw::cli::register_mesh(app);
  thaw::cli::register_render(app);
  thaw::cli::register_inspect(app);
  thaw::cli::register_materials(app);
  thaw::cli::register_run(app);
  thaw::cli::register_gui(app);
  return thaw::cli::run_app(app, argc, argv);
}
