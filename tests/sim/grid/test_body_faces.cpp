// The faces of a grid body (sim/grid/body_faces.h) and conditions held per face: the split of a
// surface cell between faces by its normal, a box with one face heated and the rest insulated
// (the heat enters through that face alone, and boundary_heat.csv says so), and a body all water
// that freezes from one cold face.
#include "sim/grid/body_faces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "sim/format/scenario_file.h"
#include "sim/simulate.h"

namespace thaw::sim {
namespace {

TEST(BodyFaces, NamesAndWeights) {
  EXPECT_EQ(body_face_names(ShapeKind::box).size(), 6u);
  EXPECT_EQ(body_face_names(ShapeKind::cylinder),
            (std::vector<std::string>{"top", "bottom", "side"}));
  EXPECT_EQ(body_face_names(ShapeKind::obj), std::vector<std::string>{"surface"});
  // a flat face of a box: all of it; an edge at 45 degrees: half to each face; a corner: thirds
  FaceWeights w = body_face_weights(ShapeKind::box, {-2, 0, 0}, false, 3);
  EXPECT_EQ(w[0], 1.0);
  w = body_face_weights(ShapeKind::box, {0.5, -0.5, 0}, false, 3);
  EXPECT_EQ(w[1], 0.5);
  EXPECT_EQ(w[2], 0.5);
  w = body_face_weights(ShapeKind::box, {1, 1, 1}, false, 0);
  EXPECT_NEAR(w[1] + w[3] + w[5], 1.0, 1e-15);
  EXPECT_EQ(w[1], w[5]);
  // no normal: the fallback face
  EXPECT_EQ(body_face_weights(ShapeKind::box, {0, 0, 0}, false, 4)[4], 1.0);
  // cylinder: the ends by n_y, the side by the horizontal part (axisymmetric: n_r)
  w = body_face_weights(ShapeKind::cylinder, {3, 4, 0}, true, 2);
  EXPECT_NEAR(w[0], 4.0 / 7.0, 1e-15);
  EXPECT_NEAR(w[2], 3.0 / 7.0, 1e-15);
  w = body_face_weights(ShapeKind::cylinder, {3, -4, 4}, false, 2);
  EXPECT_NEAR(w[1], 4.0 / 9.0, 1e-15);
  EXPECT_NEAR(w[2], 5.0 / 9.0, 1e-15);
  // the face of a point: by the largest direction against the half sizes
  ShapeSpec b;
  b.kind = ShapeKind::box;
  b.size_m = {0.04, 0.02, 0.02};
  EXPECT_EQ(body_face_of_point(b, {0.015, 0.009, 0}, false), 3);   // y_max: 0.9 > 0.75
  EXPECT_EQ(body_face_of_point(b, {-0.019, 0.009, 0}, false), 0);  // x_min: 0.95 > 0.9
}

/// boundary_heat.csv's rows of a 3D ice box whose faces have conditions of their own.
std::map<std::string, double> heat_by_face(const std::string& faces, double seconds,
                                           SimulationResult* out = nullptr) {
  const std::string text =
      "[simulation]\ngeometry = \"3d\"\nduration_s = " + std::to_string(seconds) +
      "\noutput_interval_s = " + std::to_string(seconds) +
      "\ncell_size_m = 0.001\n[shape]\nouter = { kind = \"box\", size_m = [0.012, 0.010, "
      "0.008] }\n[ice]\ninitial_temperature_c = -5.0\n[outer_boundary]\nkind = \"insulated\"\n" +
      faces;
  const Scenario sc = parse_scenario_string(text, "faces.toml");
  SimulationResult r = simulate(sc, output_times(sc));
  std::map<std::string, double> heat;
  for (std::size_t f = 0; f < r.boundary_faces.size(); ++f)
    heat[r.boundary_faces[f]] = r.boundary_heat_j.back()[f] - r.boundary_heat_j.front()[f];
  // the faces' heat is the energy balance's
  double sum = 0;
  for (const auto& [face, q] : heat) sum += q;
  EXPECT_NEAR(sum, r.snapshots.back().heat_in_j, 1e-12 * std::abs(sum) + 1e-300);
  if (out) *out = std::move(r);
  return heat;
}

TEST(BodyFaces, OneHeatedFaceOfAnInsulatedBoxTakesAllTheHeat) {
  const std::map<std::string, double> q =
      heat_by_face("[outer_boundary.faces.x_max]\nkind = \"flux\"\nflux_w_m2 = 2000.0\n", 20.0);
  // 2000 W/m^2 on the 10 x 8 mm face for 20 s: 3.2 J; the grid's face area estimate (the
  // gradient of the material fraction over the cells) within a cell's share of its edges
  EXPECT_NEAR(q.at("x_max"), 2000.0 * 0.010 * 0.008 * 20.0, 0.15 * 3.2);
  for (const char* insulated : {"x_min", "y_min", "y_max", "z_min", "z_max"})
    EXPECT_LT(std::abs(q.at(insulated)), 1e-12 * q.at("x_max")) << insulated;
}

TEST(BodyFaces, AWaterBodyFreezesFromItsColdFace) {
  const std::string text =
      "[simulation]\ngeometry = \"3d\"\nduration_s = 120.0\noutput_interval_s = 60.0\n"
      "flow = \"none\"\n"
      "cell_size_m = 0.001\n[shape]\nouter = { kind = \"box\", size_m = [0.010, 0.010, 0.010] "
      "}\nfill = \"water\"\n[water]\ninitial_temperature_c = 1.0\n[outer_boundary]\nkind = "
      "\"insulated\"\n[outer_boundary.faces.x_min]\nkind = \"temperature\"\ntemperature_c = "
      "-10.0\n";
  const Scenario sc = parse_scenario_string(text, "water.toml");
  const SimulationResult r = simulate(sc, output_times(sc));
  ASSERT_EQ(r.snapshots.size(), 3u);  // no early end: the body had no ice to lose
  EXPECT_EQ(r.snapshots.front().ice_volume_m3, 0.0);
  EXPECT_GT(r.snapshots.back().ice_volume_m3, 0.0);
  // the ice grows on the cold x_min side: the cells next to x_min hold more ice than those
  // next to x_max
  const GridField& f = r.fields.back();
  double near = 0, far = 0;
  for (int k = 0; k < f.cells[2]; ++k)
    for (int j = 0; j < f.cells[1]; ++j) {
      near += f.ice_fraction[f.index(2, j, k)];
      far += f.ice_fraction[f.index(f.cells[0] - 3, j, k)];
    }
  EXPECT_GT(near, 0);
  EXPECT_EQ(far, 0);
  for (const Snapshot& s : r.snapshots) EXPECT_LT(s.energy_balance_error, 1e-8);
  // the heat left through x_min only
  EXPECT_LT(r.boundary_heat_j.back()[0], 0);
}

}  // namespace
}  // namespace thaw::sim
