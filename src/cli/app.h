#pragma once
// The CLI11 application both executables share (src/cli/main.cpp, the launcher, and
// src/cli/main_full.cpp, every command): its description and version flag, and the one place
// where a command's outcome becomes an exit code (0 done, 2 user error, 3 internal error, 130
// interrupted). Must not know any command: those register themselves (commands.h).
#include <CLI/CLI.hpp>

namespace thaw::cli {

/// The top-level app with the description shown by --help and the --version flag.
void describe_app(CLI::App& app);

/// Parses argv and runs the chosen command; catches every error once and prints it as one line.
/// Installs the SIGINT/SIGTERM handlers first. Returns the process exit code.
int run_app(CLI::App& app, int argc, char** argv);

}  // namespace thaw::cli
