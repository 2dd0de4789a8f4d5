// Tests of base/format/mesh_manifest: a manifest as src/mesh writes it is read back; every kind of
// bad manifest is one UserError naming the key, without the JSON library's exception text.
#include "base/format/mesh_manifest.h"

#include <gtest/gtest.h>

#include "base/error.h"

namespace thaw::meshio {
namespace {

const std::string kGood = R"({"format": "thaw-mesh/1",
 "geometry": {"geometry": "cylinder", "length_m": 0.05, "frame": "capsules"},
 "steps": [
  {"step": 0, "time_s": 0, "inner_radius_m": 0.01, "outer_radius_m": 0.02,
   "inner": "step_000000_inner.obj", "outer": "step_000000_outer.obj",
   "inner_triangles": 100, "outer_triangles": 200, "inner_exact_volume_m3": 1e-6},
  {"step": 3, "time_s": 12.5, "inner_radius_m": 0, "outer_radius_m": 0.015,
   "inner": null, "outer": "step_000003_outer.obj", "inner_triangles": 0,
   "outer_triangles": 150, "inner_reason": "no liquid core left"}]})";

std::string error_of(const std::string& text) {
  try {
    parse_mesh_manifest(text, "manifest.json");
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "manifest.json");
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
    return e.where() + ": " + e.problem();
  }
  return "";
}

std::string replaced(const std::string& from, const std::string& to) {
  std::string s = kGood;
  s.replace(s.find(from), from.size(), to);
  return s;
}

TEST(MeshManifest, ReadsWhatTheMesherWrites) {
  const MeshManifestFile m = parse_mesh_manifest(kGood, "manifest.json");
  EXPECT_EQ(m.geometry, "cylinder");
  EXPECT_EQ(m.length_m, 0.05);
  ASSERT_EQ(m.steps.size(), 2u);
  EXPECT_EQ(m.steps[1].step, 3);
  EXPECT_EQ(m.steps[1].time_s, 12.5);
  EXPECT_FALSE(m.steps[1].inner);
  EXPECT_EQ(*m.steps[1].outer, "step_000003_outer.obj");
  EXPECT_EQ(m.steps[0].outer_triangles, 200);
  EXPECT_EQ(*m.steps[0].inner_exact_volume_m3, 1e-6);
  EXPECT_FALSE(m.steps[0].outer_exact_volume_m3);
}

TEST(MeshManifest, BadManifestsNameTheKey) {
  EXPECT_EQ(error_of("{\"format\": "),
            ": malformed JSON: parse error at line 1, column 12: syntax error while "
            "parsing value - "
            "unexpected end of input; expected '[', '{', or a literal");
  EXPECT_EQ(error_of("[1]"), ": expected a JSON object");
  EXPECT_EQ(error_of(replaced("thaw-mesh/1", "thaw-mesh/2")),
            "format: expected \"thaw-mesh/1\", got \"thaw-mesh/2\"");
  EXPECT_EQ(error_of(replaced("\"time_s\": 12.5", "\"time_s\": \"x\"")),
            "steps[1].time_s: expected a number, got string");
  EXPECT_EQ(error_of(replaced("\"time_s\": 12.5", "\"time_s\": -1")),
            "steps[1].time_s: must be finite and >= 0, got -1");
  EXPECT_EQ(error_of(replaced("\"step\": 3", "\"step\": 0")),
            "steps[1].step: steps must be increasing (0 after 0)");
  EXPECT_EQ(error_of(replaced("\"step\": 3", "\"step\": 1.5")),
            "steps[1].step: expected an integer >= 0, got 1.5");
  EXPECT_EQ(error_of(replaced("\"inner\": null,", "")), "steps[1].inner: missing");
  EXPECT_EQ(error_of(replaced("step_000003_outer.obj", "../../etc/passwd")),
            "steps[1].outer: '../../etc/passwd' is not a plain file name in the mesh folder");
  EXPECT_EQ(error_of(replaced("\"cylinder\"", "\"torus\"")),
            "geometry.geometry: expected sphere, cylinder, planar or grid, got \"torus\"");
  EXPECT_EQ(error_of(replaced("\"outer_triangles\": 150", "\"outer_triangles\": -150")),
            "steps[1].outer_triangles: expected an integer >= 0, got -150");
}

TEST(MeshManifest, MissingFileAndDirectory) {
  EXPECT_THROW(read_mesh_manifest("/nonexistent/manifest.json"), UserError);
  try {
    read_mesh_manifest(THAW_SOURCE_DIR);
    ADD_FAILURE();
  } catch (const UserError& e) {
    EXPECT_EQ(e.problem(), "is a directory, expected a mesh manifest");
  }
}

}  // namespace
}  // namespace thaw::meshio
