// The shared top-level app and its exit codes (app.h).
#include "src/cli/app.h"

#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "src/common/error.h"
#include "src/common/interrupt.h"
#include "thaw_version.h"

namespace thaw::cli {

void describe_app(CLI::App& app) {
  app.description(
      "thaw: simulate a hollow ice shell full of water as it melts (Stefan problem) and render "
      "every step with refraction through air | ice | water.");
  app.set_version_flag("--version", std::string("thaw ") + THAW_VERSION_STRING);
  app.require_subcommand(1);
}

int run_app(CLI::App& app, int argc, char** argv) {
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

}  // namespace thaw::cli
