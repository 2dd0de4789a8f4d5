// Boundaries per face and bodies all water (issue 24 item 3; sim/format/scenario_file.h,
// sim/scenario/scenario_rules.h): [outer_boundary.faces.NAME] tables for the faces the body has,
// each a whole [outer_boundary] table echoed in summary.json; [shape] fill = "water"; and their
// bad input, each one line naming the file, the key and the problem.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "base/error.h"
#include "sim/format/scenario_file.h"

namespace thaw::sim {
namespace {

/// A 3D ice box (or `outer`) with `extra` appended (more tables).
std::string box(const std::string& extra,
                const std::string& outer = "{ kind = \"box\", size_m = [0.02, 0.02, 0.02] }") {
  return "[simulation]\ngeometry = \"3d\"\nduration_s = 60.0\noutput_interval_s = 30.0\n"
         "[shape]\nouter = " +
         outer + "\n[ice]\ninitial_temperature_c = -5.0\n[outer_boundary]\nkind = \"insulated\"\n" +
         extra;
}

std::string error_of(const std::string& text) {
  try {
    parse_scenario_string(text, "faces.toml");
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find("faces.toml"), std::string::npos) << what;
    return what;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return "";
}

TEST(ScenarioFaces, FacesParseAndEcho) {
  const Scenario s = parse_scenario_string(
      box("[outer_boundary.faces.x_min]\nkind = \"temperature\"\ntemperature_c = -1.0\n"
          "[outer_boundary.faces.y_max]\nkind = \"convective\"\ntemperature_c = 20.0\n"
          "heat_transfer_coefficient_w_m2k = 15.0\n"),
      "faces.toml");
  EXPECT_EQ(s.outer_kind, OuterBoundary::insulated);
  ASSERT_EQ(s.outer_faces.size(), 2u);
  const auto face = [&](const std::string& name) {
    for (const FaceBoundary& f : s.outer_faces)
      if (f.face == name) return f.spec;
    ADD_FAILURE() << name;
    return OuterBoundarySpec{};
  };
  EXPECT_EQ(face("x_min").kind, OuterBoundary::temperature);
  EXPECT_EQ(face("x_min").temperature_c, -1.0);
  EXPECT_EQ(face("y_max").kind, OuterBoundary::convective);
  EXPECT_EQ(face("y_max").heat_transfer_coefficient_w_m2k, 15.0);
  const nlohmann::json j = scenario_to_json(s);
  EXPECT_EQ(j["outer_boundary"]["kind"], "insulated");
  EXPECT_EQ(j["outer_boundary"]["faces"]["x_min"]["temperature_c"], -1.0);
  EXPECT_EQ(j["outer_boundary"]["faces"]["y_max"]["heat_transfer_coefficient_w_m2k"], 15.0);
  // cylinders: top, bottom, side; any other body: surface
  EXPECT_NO_THROW(
      parse_scenario_string(box("[outer_boundary.faces.side]\nkind = \"flux\"\nflux_w_m2 = 100.0\n",
                                "{ kind = \"cylinder\", radius_m = 0.01, height_m = 0.02 }"),
                            "faces.toml"));
  EXPECT_NO_THROW(parse_scenario_string(
      box("[outer_boundary.faces.surface]\nkind = \"flux\"\nflux_w_m2 = 100.0\n",
          "{ kind = \"sphere\", radius_m = 0.01 }"),
      "faces.toml"));
  // no faces: summary.json as before
  EXPECT_FALSE(
      scenario_to_json(parse_scenario_string(box(""), "faces.toml"))["outer_boundary"].contains(
          "faces"));
}

TEST(ScenarioFaces, AFaceTheBodyDoesNotHaveIsRefused) {
  const std::string top = "[outer_boundary.faces.top]\nkind = \"insulated\"\n";
  EXPECT_NE(error_of(box(top)).find("a box body has no face 'top' (its faces: x_min, x_max, "
                                    "y_min, y_max, z_min, z_max)"),
            std::string::npos);
  const std::string x = "[outer_boundary.faces.x_min]\nkind = \"insulated\"\n";
  EXPECT_NE(error_of(box(x, "{ kind = \"cylinder\", radius_m = 0.01, height_m = 0.02 }"))
                .find("a cylinder body has no face 'x_min' (its faces: top, bottom, side)"),
            std::string::npos);
  EXPECT_NE(error_of(box(top, "{ kind = \"sphere\", radius_m = 0.01 }"))
                .find("a sphere body has no face 'top' (its faces: surface)"),
            std::string::npos);
  // misspelt key inside a face's table, a face's own bad value named by its key
  EXPECT_NE(error_of(box("[outer_boundary.faces.x_min]\nkind = \"insulated\"\ntemprature_c = 1\n"))
                .find("temprature_c"),
            std::string::npos);
  EXPECT_NE(error_of(box("[outer_boundary.faces.x_min]\nkind = \"convective\"\ntemperature_c = "
                         "20.0\nheat_transfer_coefficient_w_m2k = -3.0\n"))
                .find("outer_boundary.faces.x_min.heat_transfer_coefficient_w_m2k"),
            std::string::npos);
  // the 1D geometries have one outer surface
  EXPECT_NE(error_of("[simulation]\ngeometry = \"sphere\"\nduration_s = 60.0\noutput_interval_s = "
                     "30.0\n[shell]\ninner_radius_m = 0.01\nouter_radius_m = 0.02\n[water]\n"
                     "initial_temperature_c = 5.0\n[ice]\ninitial_temperature_c = -5.0\n"
                     "[outer_boundary]\nkind = \"insulated\"\n" +
                     top)
                .find("faces"),
            std::string::npos);
}

TEST(ScenarioFaces, FillWater) {
  const std::string water = "[water]\ninitial_temperature_c = 10.0\n";
  const std::string text =
      "[simulation]\ngeometry = \"3d\"\nduration_s = 60.0\noutput_interval_s = 30.0\n"
      "[shape]\nouter = { kind = \"box\", size_m = [0.02, 0.02, 0.02] }\nfill = \"water\"\n" +
      water +
      "[outer_boundary]\nkind = \"insulated\"\n[outer_boundary.faces.x_min]\nkind = "
      "\"temperature\"\ntemperature_c = 10.0\n";
  // no [ice] needed; a face held above the melting point is fine on a body that does not drain
  const Scenario s = parse_scenario_string(text, "faces.toml");
  EXPECT_TRUE(s.shape.fill_water);
  EXPECT_EQ(scenario_to_json(s)["shape"]["fill"], "water");
  // with a cavity; an unknown fill; without [water]
  std::string cavity = text;
  cavity.insert(cavity.find("fill"), "cavity = { kind = \"sphere\", radius_m = 0.005 }\n");
  EXPECT_NE(error_of(cavity).find("shape.fill"), std::string::npos);
  std::string bucket = text;
  bucket.replace(bucket.find("\"water\"\n"), 7, "\"bucket\"");
  EXPECT_NE(error_of(bucket).find("unknown fill 'bucket' (expected ice or water)"),
            std::string::npos);
  std::string dry = text;
  dry.erase(dry.find(water), water.size());
  EXPECT_NE(error_of(dry).find("water"), std::string::npos);
}

}  // namespace
}  // namespace thaw::sim
