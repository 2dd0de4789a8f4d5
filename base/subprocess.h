#pragma once
// Running external programs (ffmpeg, ffprobe, xvfb-run) without a shell: argv is passed as is,
// so file names with spaces or quotes are safe. Knows nothing about the programs it runs.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace thaw {

struct ProcessResult {
  int exit_code = -1;  ///< exit status; 128 + signal number if killed by a signal
  std::string output;  ///< captured stdout + stderr (last 64 KiB)
};

/// Full path of `name` found on PATH, or nullopt.
std::optional<std::filesystem::path> find_executable(const std::string& name);

/// Runs argv[0] (looked up on PATH) with the given arguments, waits, and captures its output.
/// Throws thaw::UserError if the program cannot be started at all, thaw::Interrupted (after the
/// child has ended) if SIGINT or SIGTERM arrived meanwhile (base/interrupt.h).
ProcessResult run_process(const std::vector<std::string>& argv);

}  // namespace thaw
