// stage_on_leader (src/mesh/mesh_farm.h): the leader stages the output folder, and its path or
// its failure (as it was: a user error keeps its file) reaches every process. The farm itself:
// tests/base/test_work_farm.cpp.
#include "src/mesh/mesh_farm.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <deque>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.h"

namespace thaw::mesh {
namespace {

/// A process that is not the leader, hearing `words` from it in turn.
class Follower final : public WorkFarm {
 public:
  explicit Follower(std::deque<std::string> words) : m_words(std::move(words)) {}
  bool leader() const override { return false; }
  std::string share(const std::string&) override {
    const std::string word = m_words.front();
    m_words.pop_front();
    return word;
  }

 private:
  std::deque<std::string> m_words;
};

TEST(MeshFarm, StagingFailureReachesEveryProcess) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("thaw_test_mesh_farm_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {  // the leader stages and says where
    std::optional<StagingDirectory> staging;
    const auto path = stage_on_leader(this_process_farm(), staging, dir / "mesh");
    ASSERT_TRUE(staging);
    EXPECT_EQ(path, staging->path());
    EXPECT_TRUE(std::filesystem::is_directory(path));
  }
  std::ofstream(dir / "file") << "x";  // a file where the folder's parent should be
  std::optional<StagingDirectory> staging;
  EXPECT_THROW(stage_on_leader(this_process_farm(), staging, dir / "file" / "mesh"), UserError);
  // Another process hears that the leader staged, then where.
  Follower told({"", "/shared/run/sim/mesh.tmp-1"});
  std::optional<StagingDirectory> none;
  EXPECT_EQ(stage_on_leader(told, none, dir / "mesh"), "/shared/run/sim/mesh.tmp-1");
  EXPECT_FALSE(none);
  // Or the leader's failure, thrown there as it was on the leader.
  Follower failed({Outcome::user("run/sim/mesh", "", "cannot create output directory").to_text()});
  try {
    stage_on_leader(failed, none, dir / "mesh");
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "run/sim/mesh");
    EXPECT_EQ(e.problem(), "cannot create output directory");
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace thaw::mesh
