#include "base/output_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace thaw {
namespace {

namespace fs = std::filesystem;

std::string problem_of(const fs::path& path, std::initializer_list<std::string_view> ext) {
  try {
    check_output_file(path, ext);
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), path.string());
    return e.problem();
  }
  return "";
}

// Found by the bad-input sweep (tests/src/cli/bad_input_sweep.sh): `thaw inspect SIMDIR --pvd
// SIMDIR/interfaces.csv` replaced the simulation's own interfaces.csv with a ParaView file, and
// --screenshot x.jpg wrote a PNG named x.jpg. Names are checked before any work.
TEST(OutputFile, ExtensionFolderAndParentAreChecked) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_output_file_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "shot.png");
  std::ofstream(dir / "a_file").close();
  EXPECT_EQ(problem_of(dir / "x.PNG", {".png"}), "");
  EXPECT_EQ(problem_of(dir / "new/x.png", {".png"}), "");  // the caller creates or refuses it
  EXPECT_EQ(problem_of(dir / "interfaces.csv", {".pvd"}),
            "unsupported output format '.csv' (expected .pvd)");
  EXPECT_EQ(problem_of(dir / "x", {".png", ".pfm", ".exr"}),
            "unsupported output format '' (expected .png, .pfm or .exr)");
  EXPECT_EQ(problem_of(dir / "x.jpg", {".png", ".exr"}),
            "unsupported output format '.jpg' (expected .png or .exr)");
  EXPECT_EQ(problem_of(dir / "shot.png", {".png"}), "is a directory");
  std::string expected = "'";  // built in steps: GCC 12's false -Wrestrict (bug 105651)
  expected += (dir / "a_file").string();
  expected += "' is not a directory";
  EXPECT_EQ(problem_of(dir / "a_file" / "x.png", {".png"}), expected);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw
