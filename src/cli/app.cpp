// The shared top-level app and its exit codes (app.h).
#include "src/cli/app.h"

#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "base/error.h"
#include "base/interrupt.h"
#include "thaw_version.h"

namespace thaw::cli {

void describe_app(CLI::App& app) {
  app.description(
      "thaw: simulate a hollow ice shell full of water as it melts (Stefan problem) and render "
      "every step with refraction through air | ice | water.");
  app.set_version_flag("--version", std::string("thaw ") + THAW_VERSION_STRING);
  app.require_subcommand(1);
}

namespace {

// "render " when the mistake was in `thaw render ...`, so the hint names the right help page.
std::string help_path(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return sub->get_name() + " ";
  return "";
}

// `thaw bogus`: CLI11 would only say that a subcommand is required; name the word and the choices.
std::string unknown_command(const CLI::App& app, int argc, char** argv) {
  if (!app.get_subcommands().empty() || argc < 2 || argv[1][0] == '-') return "";
  std::string known;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    known += (known.empty() ? "" : ", ") + sub->get_name();
  return "unknown command \"" + std::string(argv[1]) + "\"; the commands: " + known;
}

// `--width ""` or an empty positional: CLI11 takes an empty value as "not given" and runs with
// the default. Every option that takes a value refuses an empty one, naming the option.
void forbid_empty_values(CLI::App& app) {
  const CLI::Validator non_empty(
      [](std::string& value) { return value.empty() ? std::string("must not be empty") : ""; }, "",
      "NonEmpty");
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_size_max() > 0) opt->check(non_empty);
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    forbid_empty_values(*sub);
}

}  // namespace

int run_app(CLI::App& app, int argc, char** argv) {
  thaw::install_interrupt_handlers();
  forbid_empty_values(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0: CLI11 prints them. A real command-line
    // mistake is user input like any other: one line on stderr, exit code 2.
    if (e.get_exit_code() == 0) return app.exit(e);
    const std::string unknown = unknown_command(app, argc, argv);
    const std::string problem = unknown.empty() ? e.what() : unknown;
    std::fprintf(stderr, "thaw: error: %s (see thaw %s--help)\n",
                 thaw::escape_control_characters(problem).c_str(), help_path(app).c_str());
    return 2;
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
