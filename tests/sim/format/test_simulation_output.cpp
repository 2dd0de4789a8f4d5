// The result folder's guard (sim/format/simulation_output.h, foreign_entry): what may be replaced.
#include "sim/format/simulation_output.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace thaw::sim {
namespace {

namespace fs = std::filesystem;

// Found by the bad-input sweep's review: `thaw simulate --out DIR` replaced DIR as a whole, so a
// folder of one's own given by mistake (`--out .`) lost every file in it.
TEST(SimulationOutput, OnlyAResultFolderOrAnEmptyOneMayBeReplaced) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_simulation_output_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  EXPECT_EQ(foreign_entry(dir), std::nullopt);  // missing
  fs::create_directories(dir);
  EXPECT_EQ(foreign_entry(dir), std::nullopt);  // empty
  for (const char* own : {"interfaces.csv", "summary.json"}) std::ofstream(dir / own).close();
  for (const char* own : {"profiles", "fields", "mesh", "mesh.partial", "mesh.tmp-123-4"})
    fs::create_directories(dir / own);
  EXPECT_EQ(foreign_entry(dir), std::nullopt);  // a previous result, meshed
  std::ofstream(dir / "notes.txt").close();
  EXPECT_EQ(foreign_entry(dir), "notes.txt");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw::sim
