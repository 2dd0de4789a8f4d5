// thaw: the one executable. Sub-commands register themselves on the CLI11 app; user errors
// (thaw::UserError) are caught here, once, and printed as one line with exit code 2; SIGINT and
// SIGTERM end the command at its next safe point with one line and exit code 130.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "src/cli/commands.h"
#include "src/common/error.h"
#include "src/common/interrupt.h"
#include "thaw_version.h"

int main(int argc, char** argv) {
  CLI::App app{
      "thaw: simulate a hollow ice shell full of water as it melts (Stefan problem) and render "
      "every step with refraction through air | ice | water."};
  app.set_version_flag("--version", std::string("thaw ") + THAW_VERSION_STRING);
  app.require_subcommand(1);
  thaw::cli::register_simulate(app);
  thaw::cli::register_mesh(app);
  thaw::cli::register_render(app);
  thaw::cli::register_inspect(app);
  thaw::cli::register_materials(app);
  thaw::cli::register_run(app);
  thaw::cli::register_gui(app);
  thaw::install_interrupt_handlers();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const thaw::Interrupted& e) {
    std::fprintf(stderr, "\nthaw: %s\n", e.what());
    return thaw::kInterruptedExitCode;
  } catch (const thaw::UserError& e) {
    std::fprintf(stderr, "thaw: error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "thaw: error: out of memory\n");
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "thaw: internal error: %s\n",
                 thaw::escape_control_characters(e.what()).c_str());
    return 3;
  }
  return 0;
}
