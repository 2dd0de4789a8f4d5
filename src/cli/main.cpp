// thaw: the one command users run. `simulate`, `render` and `materials` need only the plain
// sim/ and render/ libraries and run here; every other command (mesh, inspect, run, gui, and
// --help / --version) is handed, arguments unchanged, to libexec/thaw-full next to this
// executable, which links VTK, CGAL, Qt and MPI. Why: loading those ~115 shared libraries costs
// every process ~0.07 s of CPU before main (docs/benchmarks.md), a fifth of a small render.
// The user sees one program: same help, same messages, same exit codes (app.h).
#include <unistd.h>
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "base/interrupt.h"
#include "src/cli/app.h"
#include "src/cli/commands.h"

namespace {

using Register = void (*)(CLI::App&);

// The commands this executable runs itself; their libraries load no VTK, CGAL, Qt or MPI.
Register light_command(std::string_view name) {
  if (name == "simulate") return thaw::cli::register_simulate;
  if (name == "render") return thaw::cli::register_render;
  if (name == "materials") return thaw::cli::register_materials;
  return nullptr;
}

// Replaces this process by thaw-full with the same arguments; returns only on failure.
int exec_full(char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) {
    std::fprintf(stderr, "thaw: internal error: cannot locate this executable: %s\n",
                 ec.message().c_str());
    return 3;
  }
  const std::string full = (self.parent_path() / "libexec" / "thaw-full").string();
  thaw::hold_interrupt_signals();  // until thaw-full has its handlers (interrupt.h)
  ::execv(full.c_str(), argv);
  std::fprintf(stderr, "thaw: internal error: cannot start %s: %s\n", full.c_str(),
               std::strerror(errno));
  return 3;
}

}  // namespace

int main(int argc, char** argv) {
  const Register light = argc > 1 ? light_command(argv[1]) : nullptr;
  if (light == nullptr) return exec_full(argv);
  CLI::App app;
  thaw::cli::describe_app(app);
  light(app);
  return thaw::cli::run_app(app, argc, argv);
}
