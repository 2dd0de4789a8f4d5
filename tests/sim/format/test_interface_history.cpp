// The result folder's readers (sim/format/interface_history.h) on files that are not files: each is
// a UserError naming the file (thaw mesh, inspect and run read these).
#include "sim/format/interface_history.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "base/error.h"

namespace thaw::sim {
namespace {

namespace fs = std::filesystem;

template <typename Read>
std::string problem_of(Read read, const fs::path& path) {
  try {
    read(path);
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), path.string());
    return e.problem();
  }
  return "no error";
}

// Found by the bad-input sweep (tests/src/cli/bad_input_sweep.sh): a folder named summary.json
// ended `thaw mesh` with exit 3, "internal error: basic_filebuf::underflow error reading the
// file: Is a directory".
TEST(InterfaceHistory, FoldersDevicesAndMissingFilesAreNamed) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_interface_history_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "summary.json");
  fs::create_directories(dir / "interfaces.csv");
  const auto summary = [](const fs::path& p) { read_shell_geometry(p); };
  const auto csv = [](const fs::path& p) { read_interfaces_csv(p); };
  EXPECT_EQ(problem_of(summary, dir / "summary.json"), "is a directory, expected a JSON file");
  EXPECT_EQ(problem_of(csv, dir / "interfaces.csv"), "is a directory, expected a CSV file");
  EXPECT_EQ(problem_of(summary, "/dev/zero"), "is not a regular file, expected a JSON file");
  EXPECT_EQ(problem_of(csv, dir / "none.csv"), "no such file");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw::sim
