#include "src/pipeline/run_manifest.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "src/pipeline/content_hash.h"

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

fs::path scratch_file(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_test_manifest_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

TEST(ContentHash, DistinguishesContentAndBoundaries) {
  EXPECT_EQ(ContentHash().add("abc").hex(), ContentHash().add("abc").hex());
  EXPECT_NE(ContentHash().add("ab").add("c").hex(), ContentHash().add("a").add("bc").hex());
  EXPECT_NE(ContentHash().add(1.0).hex(), ContentHash().add(1.0000000000000002).hex());
  EXPECT_EQ(ContentHash().hex().size(), 16u);
}

TEST(RunManifest, ResumesItemsUnderTheSameInputs) {
  const fs::path file = scratch_file("resume.json");
  {
    RunManifest m(file);
    EXPECT_FALSE(m.begin_stage("render", "h1"));
    m.mark_item_done("render", "frame_000000");
  }
  RunManifest again(file);  // as after a kill: only what was saved survives
  EXPECT_FALSE(again.begin_stage("render", "h1"));
  EXPECT_TRUE(again.item_done("render", "frame_000000"));
  EXPECT_FALSE(again.item_done("render", "frame_000001"));
  again.mark_stage_complete("render");
  EXPECT_TRUE(RunManifest(file).begin_stage("render", "h1"));
}

TEST(RunManifest, AnItemsNoteIsItsSecondLineAndDoesNotChangeWhetherItIsDone) {
  const fs::path file = scratch_file("note.json");
  fs::remove_all(file.parent_path() / "run_items");
  RunManifest m(file);
  m.begin_stage("render", "h1");
  m.mark_item_done("render", "frame_000003", "rank 1 wall_s 0.500 cpu_s 0.980");
  EXPECT_TRUE(RunManifest(file).item_done("render", "frame_000003"));
  std::ifstream in(file.parent_path() / "run_items" / "render" / "frame_000003");
  std::string hash, note, rest;
  ASSERT_TRUE(std::getline(in, hash) && std::getline(in, note));
  EXPECT_EQ(hash, "h1");
  EXPECT_EQ(note, "rank 1 wall_s 0.500 cpu_s 0.980");
  EXPECT_FALSE(std::getline(in, rest));
}

TEST(RunManifest, ChangedInputsForgetTheStage) {
  const fs::path file = scratch_file("changed.json");
  RunManifest m(file);
  m.begin_stage("mesh", "a");
  m.mark_item_done("mesh", "step_000001");
  m.mark_stage_complete("mesh");
  EXPECT_FALSE(m.begin_stage("mesh", "b"));
  EXPECT_FALSE(m.item_done("mesh", "step_000001"));
  EXPECT_EQ(RunManifest(file).stage_hash("mesh"), "b");
}

TEST(RunManifest, ItemsOfProcessesSharingTheRunAreAllKept) {
  // Two processes (MPI ranks, Slurm array tasks) load the manifest, then mark different items:
  // neither may lose the other's.
  const fs::path file = scratch_file("shared.json");
  fs::remove_all(file.parent_path() / "run_items");
  RunManifest leader(file);
  leader.begin_stage("render", "h1");
  RunManifest a(file), b(file);
  a.mark_item_done("render", "frame_000000");
  b.mark_item_done("render", "frame_000001");
  RunManifest after(file);
  EXPECT_TRUE(after.item_done("render", "frame_000000"));
  EXPECT_TRUE(after.item_done("render", "frame_000001"));
  EXPECT_FALSE(after.is_complete("render", "h1"));
  after.mark_stage_complete("render");
  EXPECT_TRUE(RunManifest(file).is_complete("render", "h1"));
  EXPECT_FALSE(RunManifest(file).is_complete("render", "h2"));
  // Items finished under other inputs are forgotten, also when the inputs change back (an
  // output may have been rewritten in between); --force forgets everything.
  after.begin_stage("render", "h2");
  EXPECT_FALSE(after.item_done("render", "frame_000000"));
  after.mark_item_done("render", "frame_000000");
  after.begin_stage("render", "h1");
  EXPECT_FALSE(after.item_done("render", "frame_000000"));
  after.mark_item_done("render", "frame_000001");
  after.clear();
  after.begin_stage("render", "h1");
  EXPECT_FALSE(after.item_done("render", "frame_000001"));
}

TEST(RunManifest, UnparsableFileMeansRedoEverything) {
  const fs::path file = scratch_file("corrupt.json");
  std::ofstream(file) << "{ not json";
  RunManifest m(file);
  EXPECT_FALSE(m.begin_stage("simulate", "x"));
}

}  // namespace
}  // namespace thaw::pipeline
