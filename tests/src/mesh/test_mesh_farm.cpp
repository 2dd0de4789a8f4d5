// MeshFarm (src/mesh/mesh_farm.h), this process's threads: every item exactly once, each text at
// its item's index, done() once per item, for any thread count; and staging on the leader, whose
// path or failure reaches every process.
#include "src/mesh/mesh_farm.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.h"

namespace thaw::mesh {
namespace {

TEST(MeshFarm, EveryItemOnceWithItsTextAtItsIndex) {
  for (const int threads : {1, 2, 3}) {
    std::vector<std::atomic<int>> calls(37);
    long done = 0;
    const std::vector<std::string> texts = this_process_farm().run(
        37, threads,
        [&](long k) {
          ++calls[static_cast<std::size_t>(k)];
          return "item " + std::to_string(k);
        },
        [&] { ++done; });
    ASSERT_EQ(texts.size(), 37u);
    for (long k = 0; k < 37; ++k) {
      EXPECT_EQ(calls[static_cast<std::size_t>(k)], 1) << k;
      EXPECT_EQ(texts[static_cast<std::size_t>(k)], "item " + std::to_string(k));
    }
    EXPECT_EQ(done, 37);
  }
}

TEST(MeshFarm, NoItemsNoCalls) {
  EXPECT_TRUE(this_process_farm().run(0, 2, [](long) { return std::string("x"); }, {}).empty());
  EXPECT_TRUE(this_process_farm().leader());
  EXPECT_EQ(this_process_farm().share("path"), "path");
}

/// A process that is not the leader, hearing `word` from it.
class Follower final : public MeshFarm {
 public:
  explicit Follower(std::string word) : m_word(std::move(word)) {}
  bool leader() const override { return false; }
  std::string share(const std::string&) override { return m_word; }

 private:
  std::string m_word;
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
  // Another process hears the leader's path, or its failure as its own UserError.
  Follower told("+/shared/run/sim/mesh.tmp-1");
  std::optional<StagingDirectory> none;
  EXPECT_EQ(stage_on_leader(told, none, dir / "mesh"), "/shared/run/sim/mesh.tmp-1");
  EXPECT_FALSE(none);
  Follower failed("-cannot create output directory");
  try {
    stage_on_leader(failed, none, dir / "mesh");
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create output directory"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace thaw::mesh
