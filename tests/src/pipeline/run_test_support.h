#pragma once
// What the end-to-end tests of `thaw run` share (test_pipeline.cpp, test_pipeline_mpi.cpp): the
// binary and the tiny scenario, reading outputs back, scenario variants, a per-test temporary
// folder, and a run killed mid-render the way a crash would kill it. Written once here.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

extern char** environ;

namespace thaw::pipeline::test {

namespace fs = std::filesystem;

inline const fs::path kThaw = fs::path(THAW_BINARY_DIR) / "thaw";
inline const fs::path kTiny = fs::path(THAW_SOURCE_DIR) / "tests/src/pipeline/data/tiny.toml";

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every file under `dir` (relative path -> bytes); `dir` = OUT/frames gives the frames.
inline std::map<std::string, std::string> files_under(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return files;
}

inline std::map<std::string, std::string> frames_of(const fs::path& out) {
  return files_under(out / "frames");
}

/// tiny.toml with each `from` replaced by its `to` (each must occur), written to DIR/NAME.
inline fs::path tiny_variant(const fs::path& dir,
                             const std::vector<std::pair<std::string, std::string>>& edits,
                             const std::string& name = "scenario.toml") {
  std::string text = read_file(kTiny);
  for (const auto& [from, to] : edits) {
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    if (pos != std::string::npos) text.replace(pos, from.size(), to);
  }
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

/// A heavier tiny scenario (6 frames of 200x200 at 9 samples) so a kill lands mid-render.
inline fs::path heavy_scenario(const fs::path& dir) {
  return tiny_variant(dir,
                      {{"frames = 4", "frames = 6"},
                       {"width = 64", "width = 200"},
                       {"height = 64", "height = 200"},
                       {"samples_per_pixel = 1", "samples_per_pixel = 9"}},
                      "heavy.toml");
}

/// Every file and folder at the top of run folder `out` is named in docs/user-guide.md's table
/// of outputs as `DIR/NAME (issue 27: docs that cannot drift).
inline void expect_user_guide_lists(const fs::path& out) {
  const std::string guide = read_file(fs::path(THAW_SOURCE_DIR) / "docs/user-guide.md");
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(guide.find("`DIR/" + e.path().filename().string()), std::string::npos)
        << "docs/user-guide.md's table does not list " << e.path().filename();
}

/// No temporary (".tmp-") file or folder is left anywhere under `dir`.
inline void expect_no_temporaries(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

/// Sends `signal_number` to every running process with `out` in its command line until none is
/// left (at most 30 s). OpenMPI puts each rank in a process group of its own: killing mpirun's
/// group leaves the ranks running (they even finish the run), so a crash of the whole job must
/// reach them too. Zombies (an empty /proc/PID/cmdline) count as gone.
inline void signal_processes_naming(const fs::path& out, int signal_number) {
  const std::string needle = out.string();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  for (;;) {
    bool found = false;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator("/proc", ec)) {
      const std::string name = e.path().filename().string();
      if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
      std::ifstream in(e.path() / "cmdline", std::ios::binary);
      const std::string cmdline((std::istreambuf_iterator<char>(in)), {});
      if (cmdline.find(needle) == std::string::npos) continue;
      found = true;
      ::kill(static_cast<pid_t>(std::stol(name)), signal_number);
    }
    if (!found || std::chrono::steady_clock::now() > deadline) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

/// Starts `args` (argv[0] searched on PATH) in a process group of its own, waits until
/// OUT/frames/frame_000001.png exists (at most 120 s), sends `signal_number` to the group (or to
/// the process only, if `group` is false) and returns the wait status. Its standard error goes to
/// `stderr_file` if one is given.
inline int signal_once_a_frame_is_written(const std::vector<std::string>& args, const fs::path& out,
                                          int signal_number, bool group,
                                          const fs::path& stderr_file = {}) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stderr_file.empty())
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_file.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  EXPECT_EQ(rc, 0) << args[0];
  if (rc != 0) return -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(out / "frames/frame_000001.png") &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(group ? -pid : pid, signal_number);
  if (group) signal_processes_naming(out, signal_number);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

/// A fresh temporary folder per test: m_dir = TMP/PREFIX_PID_TESTNAME, removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  explicit TempDirTest(std::string prefix) : m_prefix(std::move(prefix)) {}
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            (m_prefix + "_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  std::string m_prefix;
  fs::path m_dir;
};

}  // namespace thaw::pipeline::test
