// `mpirun -np N thaw run` (THAW_MPI, src/pipeline/run_ranks_mpi.cpp) on the tiny scenario: the
// frames and film equal a single-process run's byte for byte, a run killed under MPI resumes with
// another number of ranks, and a bad option under MPI is still one error line with exit code 2.
// More ranks than this machine's cores (--oversubscribe), so the dynamic hand-out is exercised.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "src/common/subprocess.h"
#include "src/pipeline/film_encoder.h"

extern char** environ;

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

const fs::path kThaw = fs::path(THAW_BINARY_DIR) / "thaw";
const fs::path kTiny = fs::path(THAW_SOURCE_DIR) / "tests/src/pipeline/data/tiny.toml";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::map<std::string, std::string> frames_of(const fs::path& out) {
  std::map<std::string, std::string> frames;
  for (const auto& e : fs::directory_iterator(out / "frames"))
    frames[e.path().filename()] = read_file(e.path());
  return frames;
}

class ThawRunMpi : public ::testing::Test {
 protected:
  void SetUp() override {
    // mpirun refuses to run as root without these (CI and developers run as root here); the
    // shared-memory transport's single-copy mode fails in containers.
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    ::setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 1);
    m_dir = fs::temp_directory_path() /
            ("thaw_test_mpi_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  static std::vector<std::string> mpirun(int ranks, std::vector<std::string> thaw_args) {
    std::vector<std::string> args{THAW_MPIEXEC, "--oversubscribe", "-np", std::to_string(ranks),
                                  kThaw.string()};
    args.insert(args.end(), thaw_args.begin(), thaw_args.end());
    return args;
  }
  /// A heavier tiny scenario (6 frames of 200x200 at 9 samples) so a kill lands mid-render.
  fs::path heavy_scenario() const {
    std::string text = read_file(kTiny);
    const auto swap = [&](const std::string& from, const std::string& to) {
      text.replace(text.find(from), from.size(), to);
    };
    swap("frames = 4", "frames = 6");
    swap("width = 64", "width = 200");
    swap("height = 64", "height = 200");
    swap("samples_per_pixel = 1", "samples_per_pixel = 9");
    const fs::path p = m_dir / "heavy.toml";
    std::ofstream(p) << text;
    return p;
  }
  fs::path m_dir;
};

TEST_F(ThawRunMpi, ThreeRanksGiveTheSingleProcessRunByteForByte) {
  const fs::path single = m_dir / "single", farmed = m_dir / "farmed";
  ASSERT_EQ(run_process({kThaw.string(), "run", kTiny.string(), "--out", single.string(), "-q"})
                .exit_code,
            0);
  const auto r =
      run_process(mpirun(3, {"run", kTiny.string(), "--out", farmed.string(), "-j", "1"}));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // One summary (the leader's), whole frames from every rank, the leader's film.
  std::size_t summaries = 0;
  for (auto p = r.output.find("thaw run: "); p != std::string::npos;
       p = r.output.find("thaw run: ", p + 1))
    ++summaries;
  EXPECT_EQ(summaries, 1u) << r.output;
  EXPECT_NE(r.output.find("render: 4/4 done"), std::string::npos) << r.output;
  EXPECT_EQ(frames_of(farmed), frames_of(single));
  EXPECT_EQ(read_file(farmed / "melt.mp4"), read_file(single / "melt.mp4"));
  EXPECT_EQ(count_video_frames(farmed / "melt.mp4"), 4);
  for (const auto& e : fs::recursive_directory_iterator(farmed))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(ThawRunMpi, KilledUnderMpiResumesWithAnotherNumberOfRanks) {
  const fs::path scenario = heavy_scenario();
  const fs::path reference = m_dir / "reference", killed = m_dir / "killed";
  ASSERT_EQ(
      run_process({kThaw.string(), "run", scenario.string(), "--out", reference.string(), "-q"})
          .exit_code,
      0);

  // mpirun and its ranks in a process group of their own, killed together as a crash would.
  const auto args =
      mpirun(3, {"run", scenario.string(), "--out", killed.string(), "-q", "-j", "1"});
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawnp(&pid, argv[0], nullptr, &attr, argv.data(), environ), 0);
  posix_spawnattr_destroy(&attr);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(killed / "frames/frame_000001.png") &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(-pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
  EXPECT_FALSE(fs::exists(killed / "melt.mp4"));

  const auto resumed = run_process(mpirun(2, {"run", scenario.string(), "--out", killed.string()}));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("simulate: up to date"), std::string::npos) << resumed.output;
  EXPECT_EQ(frames_of(killed), frames_of(reference));
  EXPECT_EQ(count_video_frames(killed / "melt.mp4"), 6);
  for (const auto& e : fs::recursive_directory_iterator(killed))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(ThawRunMpi, BadOptionUnderMpiIsOneErrorLine) {
  const auto r = run_process(
      mpirun(3, {"run", kTiny.string(), "--out", (m_dir / "never").string(), "--frames", "9-12"}));
  EXPECT_NE(r.exit_code, 0);
  std::size_t lines = 0;
  for (auto p = r.output.find("thaw: error"); p != std::string::npos;
       p = r.output.find("thaw: error", p + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << r.output;
  EXPECT_NE(r.output.find("--frames: the film has frames 0-3"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(m_dir / "never"));
}

}  // namespace
}  // namespace thaw::pipeline
