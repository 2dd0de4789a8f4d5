// A failure on rank 1 of `mpirun -np 2` keeps its kind on the way to the leader's one error line
// (base/outcome.h): an internal error exits 3 as an internal error, a bad input exits 2 naming
// its file and key, whichever path carried it between the ranks (rank_failure_main.cpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "base/subprocess.h"

namespace {

struct Ended {
  int exit_code;
  std::string output;
};

Ended two_ranks(const std::string& kind, const std::string& path, int on_rank = 1) {
  // mpirun refuses to run as root without these (CI and developers run as root here); the
  // shared-memory transport's single-copy mode fails in containers.
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  ::setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 1);
  const auto r =
      thaw::run_process({THAW_MPIEXEC, "--oversubscribe", "-np", "2", THAW_RANK_FAILURE, "fail",
                         "--kind", kind, "--path", path, "--on-rank", std::to_string(on_rank)});
  return {r.exit_code, r.output};
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto p = text.find(part); p != std::string::npos; p = text.find(part, p + 1)) ++n;
  return n;
}

TEST(RankFailureMpi, InternalErrorOnRankOneExitsThreeAsAnInternalError) {
  for (const char* path : {"every", "coarse", "fine"}) {
    const Ended r = two_ranks("internal", path);
    EXPECT_EQ(r.exit_code, 3) << path << "\n" << r.output;
    EXPECT_EQ(count(r.output, "thaw: internal error: an invariant broke on this rank"), 1u)
        << path << "\n"
        << r.output;
    EXPECT_EQ(count(r.output, "thaw: error"), 0u) << path << "\n" << r.output;
  }
}

TEST(RankFailureMpi, BadInputOnRankOneExitsTwoNamingTheFileAndKey) {
  for (const char* path : {"every", "coarse", "fine"}) {
    const Ended r = two_ranks("user", path);
    EXPECT_EQ(r.exit_code, 2) << path << "\n" << r.output;
    EXPECT_EQ(count(r.output, "thaw: error: rank1.toml: [film] fps: must be > 0 (got -1)"), 1u)
        << path << "\n"
        << r.output;
    EXPECT_EQ(count(r.output, "thaw: "), 1u) << path << "\n" << r.output;
  }
}

// The leader's own failure, heard by every rank: the same exit codes.
TEST(RankFailureMpi, LeadersFailureIsEveryRanksWithItsKind) {
  const Ended user = two_ranks("user", "leader", 0);
  EXPECT_EQ(user.exit_code, 2) << user.output;
  EXPECT_EQ(count(user.output, "thaw: error: rank1.toml: [film] fps:"), 1u) << user.output;
  const Ended internal = two_ranks("internal", "leader", 0);
  EXPECT_EQ(internal.exit_code, 3) << internal.output;
  EXPECT_EQ(count(internal.output, "thaw: internal error:"), 1u) << internal.output;
}

}  // namespace
