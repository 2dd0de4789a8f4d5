// `mpirun -np N thaw run` (THAW_MPI, src/pipeline/run_ranks_mpi.cpp) on the tiny scenario: the
// meshes, frames, film and inspect outputs equal a single-process run's byte for byte, a run killed
// under MPI resumes with another number of ranks, and a bad option under MPI is still one error
// line with exit code 2. More ranks than this machine's cores (--oversubscribe), so the dynamic
// hand-out is exercised.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "base/subprocess.h"
#include "src/pipeline/film_encoder.h"
#include "tests/src/pipeline/run_test_support.h"

namespace thaw::pipeline {
namespace {
using namespace test;

class ThawRunMpi : public TempDirTest {
 protected:
  ThawRunMpi() : TempDirTest("thaw_test_mpi") {
    // mpirun refuses to run as root without these (CI and developers run as root here); the
    // shared-memory transport's single-copy mode fails in containers.
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    ::setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 1);
  }
  static std::vector<std::string> mpirun(int ranks, std::vector<std::string> thaw_args) {
    std::vector<std::string> args{THAW_MPIEXEC, "--oversubscribe", "-np", std::to_string(ranks),
                                  kThaw.string()};
    args.insert(args.end(), thaw_args.begin(), thaw_args.end());
    return args;
  }
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
  // The meshes too: every rank meshed its share of the surfaces into the one folder.
  EXPECT_EQ(files_under(farmed / "sim/mesh"), files_under(single / "sim/mesh"));
  // And the inspect outputs: the ranks wrote their steps' .vtp into the leader's staged folder
  // and their world-space OBJs, the last rank drew the plot.
  const auto vtp = files_under(farmed / "meshes_vtp");
  EXPECT_EQ(vtp.size(), 8u);  // 4 steps x 2 surfaces
  EXPECT_EQ(vtp, files_under(single / "meshes_vtp"));
  EXPECT_EQ(read_file(farmed / "meshes.pvd"), read_file(single / "meshes.pvd"));
  EXPECT_EQ(files_under(farmed / "handoff"), files_under(single / "handoff"));
  EXPECT_EQ(read_file(farmed / "plot.png"), read_file(single / "plot.png"));
  EXPECT_NE(r.output.find("inspect: 4/4 done"), std::string::npos) << r.output;
  expect_no_temporaries(farmed);
}

TEST_F(ThawRunMpi, GridMeshStageOverThreeRanksGivesTheSingleProcessMeshes) {
  // A grid run meshes one step per item: the steps are spread over the ranks (issue 13).
  const fs::path cube = fs::path(THAW_SOURCE_DIR) / "tests/src/pipeline/data/tiny_cube.toml";
  const fs::path single = m_dir / "single", farmed = m_dir / "farmed";
  ASSERT_EQ(run_process({kThaw.string(), "run", cube.string(), "--out", single.string(), "--stage",
                         "simulate", "-q"})
                .exit_code,
            0);
  fs::copy(single, farmed, fs::copy_options::recursive);
  ASSERT_EQ(run_process({kThaw.string(), "run", cube.string(), "--out", single.string(), "--stage",
                         "mesh", "-q"})
                .exit_code,
            0);
  const auto r = run_process(
      mpirun(3, {"run", cube.string(), "--out", farmed.string(), "--stage", "mesh", "-j", "1"}));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto meshes = files_under(farmed / "sim/mesh");
  EXPECT_GT(meshes.size(), 2u);
  EXPECT_EQ(meshes, files_under(single / "sim/mesh"));
  EXPECT_NE(r.output.find("mesh: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" done in "), std::string::npos) << r.output;
  expect_no_temporaries(farmed);
}

TEST_F(ThawRunMpi, KilledUnderMpiResumesWithAnotherNumberOfRanks) {
  const fs::path scenario = heavy_scenario(m_dir);
  const fs::path reference = m_dir / "reference", killed = m_dir / "killed";
  ASSERT_EQ(
      run_process({kThaw.string(), "run", scenario.string(), "--out", reference.string(), "-q"})
          .exit_code,
      0);

  // mpirun and its ranks in a process group of their own, killed together as a crash would.
  const int status = signal_once_a_frame_is_written(
      mpirun(3, {"run", scenario.string(), "--out", killed.string(), "-q", "-j", "1"}), killed,
      SIGKILL, true);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run finished before it could be killed";
  EXPECT_FALSE(fs::exists(killed / "melt.mp4"));

  const auto resumed = run_process(mpirun(2, {"run", scenario.string(), "--out", killed.string()}));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("simulate: up to date"), std::string::npos) << resumed.output;
  EXPECT_EQ(frames_of(killed), frames_of(reference));
  EXPECT_EQ(count_video_frames(killed / "melt.mp4"), 6);
  expect_no_temporaries(killed);
}

TEST_F(ThawRunMpi, FramesUnderMpiMeshOnlyTheirStepsAndTheWholeRunCompletesThem) {
  // A 1D capsule series: every surface its own form, spread over the ranks; --frames meshes only
  // its frames' steps, and a later whole run (another number of processes) the rest.
  const fs::path cylinder =
      tiny_variant(m_dir, {{"geometry = \"sphere\"", "geometry = \"cylinder\""}}, "capsule.toml");
  const fs::path reference = m_dir / "reference", parts = m_dir / "parts";
  ASSERT_EQ(
      run_process({kThaw.string(), "run", cylinder.string(), "--out", reference.string(), "-q"})
          .exit_code,
      0);
  const auto some = run_process(
      mpirun(3, {"run", cylinder.string(), "--out", parts.string(), "--frames", "1-2", "-j", "1"}));
  ASSERT_EQ(some.exit_code, 0) << some.output;
  EXPECT_NE(some.output.find("selected frames' steps only"), std::string::npos) << some.output;
  EXPECT_FALSE(fs::exists(parts / "sim/mesh"));
  const auto rest =
      run_process({kThaw.string(), "run", cylinder.string(), "--out", parts.string()});
  ASSERT_EQ(rest.exit_code, 0) << rest.output;
  EXPECT_EQ(files_under(parts / "sim/mesh"), files_under(reference / "sim/mesh"));
  EXPECT_EQ(frames_of(parts), frames_of(reference));
  expect_no_temporaries(parts);
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
