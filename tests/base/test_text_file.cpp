#include "base/text_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace thaw {
namespace {

namespace fs = std::filesystem;

// One folder per test and process (ctest -j runs tests of this binary side by side).
fs::path scratch(const std::string& test) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_text_file_" + test + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string problem_of(const fs::path& path, std::uintmax_t max_bytes = 0) {
  try {
    read_text_file(path, "a TOML file", max_bytes);
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), path.string());
    return e.problem();
  }
  return "no error";
}

TEST(TextFile, ReadsTheWholeFileByteForByte) {
  const fs::path dir = scratch("reads");
  const std::string text("a = 1\n\0b\xff\n", 10);
  std::ofstream(dir / "a.toml", std::ios::binary) << text;
  EXPECT_EQ(read_text_file(dir / "a.toml", "a TOML file"), text);
  std::ofstream(dir / "empty.toml", std::ios::binary).close();
  EXPECT_EQ(read_text_file(dir / "empty.toml", "a TOML file"), "");
  fs::remove_all(dir);
}

TEST(TextFile, MissingDirectoryAndEmptyNameAreNamed) {
  const fs::path dir = scratch("missing");
  EXPECT_EQ(problem_of(dir / "no_such.toml"), "no such file");
  EXPECT_EQ(problem_of(dir), "is a directory, expected a TOML file");
  EXPECT_EQ(problem_of(""), "no such file");
  fs::remove_all(dir);
}

// A named pipe without a writer would block the open for ever, /dev/zero would never end: both
// are refused from their type, before they are opened.
TEST(TextFile, DevicesAndPipesAreRefusedWithoutOpeningThem) {
  const fs::path dir = scratch("pipes");
  ASSERT_EQ(::mkfifo((dir / "fifo.toml").c_str(), 0600), 0);
  EXPECT_EQ(problem_of(dir / "fifo.toml"), "is not a regular file, expected a TOML file");
  EXPECT_EQ(problem_of("/dev/zero"), "is not a regular file, expected a TOML file");
  fs::remove_all(dir);
}

// A 3 GB file given by mistake is refused from its size, before anything is allocated (the
// sparse file costs no disk).
TEST(TextFile, AFileAboveTheLimitIsRefusedFromItsSize) {
  const fs::path dir = scratch("limit");
  { std::ofstream(dir / "big.toml", std::ios::binary) << std::string(101, 'x'); }
  EXPECT_EQ(problem_of(dir / "big.toml", 100).rfind("is 9.63e-05 MiB, more than the", 0), 0u)
      << problem_of(dir / "big.toml", 100);
  EXPECT_EQ(read_text_file(dir / "big.toml", "a TOML file", 101).size(), 101u);
  fs::resize_file(dir / "big.toml", std::uintmax_t(3) << 30);
  const std::string problem = problem_of(dir / "big.toml", kMaxTomlFileBytes);
  EXPECT_EQ(problem, "is 3.07e+03 MiB, more than the 64 MiB accepted for a TOML file");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw
