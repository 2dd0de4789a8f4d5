#include "base/atomic_file.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "tests/base/file_size_limit.h"

namespace thaw {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  fs::path p =
      fs::temp_directory_path() / ("thaw_test_atomic_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, WritesAndLeavesNoTemporary) {
  const fs::path dir = scratch("write");
  write_file_atomic(dir / "a.txt", "hello");
  EXPECT_EQ(read(dir / "a.txt"), "hello");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, UncommittedLeavesOldContentAndNoTemporary) {
  const fs::path dir = scratch("abort");
  write_file_atomic(dir / "a.txt", "old");
  {
    AtomicOutputFile out(dir / "a.txt");
    out.stream() << "new but interrupted";
  }
  EXPECT_EQ(read(dir / "a.txt"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, UnwritableDirectoryIsAUserError) {
  EXPECT_THROW(write_file_atomic("/nonexistent_dir_thaw/x.txt", "x"), UserError);
}

TEST(StagingDirectory, ReplacesOnlyOnCommit) {
  const fs::path dir = scratch("stage");
  const fs::path out = dir / "result";
  {
    StagingDirectory stage(out);
    write_file_atomic(stage.path() / "f.txt", "1");
    EXPECT_FALSE(fs::exists(out));
  }
  EXPECT_FALSE(fs::exists(out));  // not committed: nothing half-written appears
  {
    StagingDirectory stage(out);
    write_file_atomic(stage.path() / "f.txt", "2");
    stage.commit();
  }
  EXPECT_EQ(read(out / "f.txt"), "2");
  {
    StagingDirectory stage(out);
    write_file_atomic(stage.path() / "g.txt", "3");
    stage.commit();
  }
  EXPECT_FALSE(fs::exists(out / "f.txt"));
  EXPECT_EQ(read(out / "g.txt"), "3");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

// Issue 12: a write that fails inside a staged folder (disk full) names the file as it would be
// once committed, never the temporary folder.
TEST(StagingDirectory, ErrorsNameTheFinalPathNotTheTemporary) {
  const fs::path dir = scratch("final_name");
  {
    StagingDirectory staging(dir / "out");
    EXPECT_EQ(final_name(staging.path() / "sub" / "a.txt"), dir / "out" / "sub" / "a.txt");
    EXPECT_EQ(final_name(staging.path()), dir / "out");
    EXPECT_EQ(final_name(dir / "elsewhere.txt"), dir / "elsewhere.txt");
    {
      StagingDirectory inner(staging.path() / "mesh");  // staged inside a staged folder
      EXPECT_EQ(final_name(inner.path() / "m.obj"), dir / "out" / "mesh" / "m.obj");
    }
    const testing::FileSizeLimit full_disk(16);
    try {
      write_file_atomic(staging.path() / "big.txt", std::string(1000, 'x'));
      FAIL() << "no error";
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), (dir / "out" / "big.txt").string());
      EXPECT_EQ(e.problem(), "write failed (disk full or I/O error)");
    }
  }
  EXPECT_EQ(final_name(dir / ("out.tmp-" + std::to_string(::getpid()) + "-0") / "x"),
            dir / ("out.tmp-" + std::to_string(::getpid()) + "-0") / "x");  // none live now
  fs::remove_all(dir);
}

TEST(StagingDirectory, TargetThatIsAFileIsAUserError) {
  const fs::path dir = scratch("stagefile");
  write_file_atomic(dir / "f", "x");
  EXPECT_THROW(StagingDirectory(dir / "f"), UserError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw

namespace thaw {
namespace {
TEST(AtomicFile, StaleTemporariesOfDeadProcessesAreRemoved) {
  const std::filesystem::path dir = scratch("stale");
  std::filesystem::create_directories(dir / "sub" / "x.tmp-999999999-1");  // no such process
  std::ofstream(dir / "sub" / "x.tmp-999999999-1" / "inner") << "partial";
  std::ofstream(dir / "m.json.tmp-999999999-0") << "partial";
  const std::string live = "n.json.tmp-" + std::to_string(::getpid()) + "-0";
  std::ofstream(dir / live) << "being written";
  std::ofstream(dir / "keep.json") << "done";
  // Names that are not temporary_sibling()'s are the user's: kept whatever follows ".tmp-".
  for (const char* name : {"notes.tmp-old", "a.tmp-12", "b.tmp-12-", "c.tmp--3", "d.tmp-0x1-2",
                           "e.tmp-999999999-1.bak"})
    std::ofstream(dir / name) << "user's";
  EXPECT_EQ(remove_stale_temporaries(dir), 2);
  for (const char* name : {"notes.tmp-old", "a.tmp-12", "b.tmp-12-", "c.tmp--3", "d.tmp-0x1-2",
                           "e.tmp-999999999-1.bak"})
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  EXPECT_TRUE(std::filesystem::exists(dir / live));
  EXPECT_TRUE(std::filesystem::exists(dir / "keep.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "m.json.tmp-999999999-0"));
  EXPECT_FALSE(std::filesystem::exists(dir / "sub" / "x.tmp-999999999-1"));
  std::filesystem::remove_all(dir);
}

// A killed process whose parent has not reaped it (a zombie: under mpirun killed first, a rank's
// parent is init, which in a container may never reap it) writes nothing more: its temporaries
// are stale too. The child here exits at once and stays a zombie until waitpid below.
TEST(AtomicFile, StaleTemporariesOfZombieProcessesAreRemoved) {
  const std::filesystem::path dir = scratch("zombie");
  std::filesystem::create_directories(dir);
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  // Wait until it is a zombie (state 'Z' in /proc/PID/stat), at most 5 s.
  for (int i = 0; i < 5000; ++i) {
    std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
    std::string line;
    std::getline(stat, line);
    const auto paren = line.rfind(')');
    if (paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] == 'Z') break;
    ::usleep(1000);
  }
  const std::string zombie = "melt.mp4.tmp-" + std::to_string(child) + "-28";
  std::ofstream(dir / zombie) << "half an encode";
  EXPECT_EQ(remove_stale_temporaries(dir), 1);
  EXPECT_FALSE(std::filesystem::exists(dir / zombie));
  int status = 0;
  ::waitpid(child, &status, 0);
  std::filesystem::remove_all(dir);
}
}  // namespace
}  // namespace thaw
