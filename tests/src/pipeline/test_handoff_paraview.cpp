// The ParaView state of the hand-off (src/pipeline/handoff_paraview.h): valid Python (parsed by
// this machine's python3: ParaView's own Python cannot be installed beside the build's VTK, see
// docs/handoff.md), and the water's velocity shown (Glyph on fields.pvd's velocity_m_s) exactly
// when the run flows.
#include "src/pipeline/handoff_paraview.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

TEST(HandoffParaview, VelocityGlyphsOnlyForRunsThatFlowAndTheStateParsesAsPython) {
  const fs::path dir =
      fs::path(THAW_BINARY_DIR) / "test-tmp" / "handoff_paraview" / std::to_string(::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  render::CameraDescription c;
  c.position = {0.1, 0.2, 0.3};
  for (bool velocity : {false, true}) {
    const fs::path state = dir / (velocity ? "flow.py" : "still.py");
    write_paraview_state(state, c, 640, 480, velocity);
    const std::string text = read_text(state);
    EXPECT_NE(text.find("PVDReader(registrationName='meshes.pvd'"), std::string::npos);
    const bool glyphs =
        text.find("Glyph(registrationName='velocity', Input=fields") != std::string::npos;
    EXPECT_EQ(glyphs, velocity);
    EXPECT_EQ(text.find("['CELLS', 'velocity_m_s']") != std::string::npos, velocity);
    // Python's own parser: no syntax error in either state
    const std::string parse =
        "python3 -c \"import ast, sys; ast.parse(open(sys.argv[1]).read())\" " + state.string();
    EXPECT_EQ(std::system(parse.c_str()), 0) << text;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw::pipeline
