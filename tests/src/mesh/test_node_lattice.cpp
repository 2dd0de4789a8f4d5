// Tests of NodeLattice (src/mesh/node_lattice.h): the air border, cell-centred nodes of a 3D
// field, the revolution of an axisymmetric field, and the binomial smoothing's invariants.
#include "src/mesh/node_lattice.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thaw::mesh {
namespace {

sim::GridField cartesian(int n, double h) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  f.cells = {n, n, n};
  f.origin_m = {-0.5 * n * h, -0.5 * n * h, -0.5 * n * h};
  f.spacing_m = h;
  f.temperature_c.assign(f.cell_count(), 0.0f);
  f.ice_fraction.assign(f.cell_count(), 1.0f);
  f.water_fraction.assign(f.cell_count(), 0.0f);
  return f;
}

TEST(NodeLattice, CartesianNodesAreCellCentresInsideAnAirBorder) {
  sim::GridField f = cartesian(4, 0.001);
  f.ice_fraction[f.index(1, 2, 3)] = 0.25f;
  const NodeLattice l = NodeLattice::from_ice_fraction(f, 0);
  EXPECT_EQ(l.nodes(), (std::array<int, 3>{6, 6, 6}));
  EXPECT_EQ(l.value(0, 0, 0), 0.0f);
  EXPECT_EQ(l.value(5, 3, 3), 0.0f);
  EXPECT_EQ(l.value(2, 3, 4), 0.25f);  // cell (1, 2, 3) shifted by the border
  const auto p = l.position(2, 3, 4);  // its centre
  EXPECT_NEAR(p[0], f.origin_m[0] + 1.5 * 0.001, 1e-15);
  EXPECT_NEAR(p[2], f.origin_m[2] + 3.5 * 0.001, 1e-15);
}

TEST(NodeLattice, AxisymmetricFieldIsRevolvedAboutTheYAxis) {
  // A solid cylinder of radius 5 h: fraction 1 for the first 5 rings, 0 beyond.
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::axisymmetric;
  f.cells = {8, 4, 1};
  f.spacing_m = 0.001;
  f.origin_m = {0, -0.002, 0};
  f.temperature_c.assign(f.cell_count(), 0.0f);
  f.ice_fraction.assign(f.cell_count(), 0.0f);
  f.water_fraction.assign(f.cell_count(), 0.0f);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) f.ice_fraction[f.index(i, j, 0)] = 1.0f;
  const NodeLattice l = NodeLattice::from_ice_fraction(f, 0);
  EXPECT_EQ(l.nodes(), (std::array<int, 3>{18, 6, 18}));
  for (int k = 1; k < 17; ++k)
    for (int i = 1; i < 17; ++i) {
      const auto p = l.position(i, 2, k);
      const double r = std::hypot(p[0], p[2]) / 0.001;  // in cells
      const float v = l.value(i, 2, k);
      if (r < 4.5) {
        EXPECT_EQ(v, 1.0f) << r;
      }  // up to the last full ring's centre
      if (r > 5.5) {
        EXPECT_EQ(v, 0.0f) << r;
      }  // from the first empty ring's centre
      if (r > 4.5 && r < 5.5) {
        EXPECT_NEAR(v, 5.5 - r, 1e-6) << r;
      }  // linear in between
    }
  // Symmetric about the axis: the lattice is symmetric under x -> -x and z -> -z.
  EXPECT_EQ(l.value(3, 2, 7), l.value(14, 2, 7));
  EXPECT_EQ(l.value(3, 2, 7), l.value(3, 2, 10));
}

TEST(NodeLattice, SmoothingKeepsTheBorderAirAndTheInteriorOfAUniformBlock) {
  const sim::GridField f = cartesian(8, 0.001);
  const NodeLattice l = NodeLattice::from_ice_fraction(f, 1);
  EXPECT_EQ(l.value(0, 4, 4), 0.0f);
  EXPECT_FLOAT_EQ(l.value(4, 4, 4), 1.0f);   // [1 2 1]/4 of a constant is the constant
  EXPECT_FLOAT_EQ(l.value(1, 4, 4), 0.75f);  // next to the border: (0 + 2 + 1) / 4
}

}  // namespace
}  // namespace thaw::mesh
