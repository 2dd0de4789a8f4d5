// Tests of extract_grid_surfaces (src/mesh/grid_surface.h), the raw marching-tetrahedra surfaces
// before remeshing: closed, consistently oriented, classified by region, nested by level.
#include "src/mesh/grid_surface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "src/mesh/surface_remesher.h"
#include "tests/src/mesh/grid_field_samples.h"

namespace thaw::mesh {
namespace {

using namespace thaw::mesh::testing;

sim::GridField shell(double hole_y) {
  // A 1 cm sphere of ice with a 6 mm cavity; a vertical bore of radius 2 mm from y = hole_y up.
  return sample_cartesian([](double x, double y, double z) { return std::hypot(x, y, z) - 0.005; },
                          [hole_y](double x, double y, double z) {
                            return std::min(std::hypot(x, y, z) - 0.003,
                                            std::max(std::hypot(x, z) - 0.002, hole_y - y));
                          },
                          0.006, 0.0005, 3);
}

TEST(GridSurface, SealedCavityGivesTwoClosedSurfacesOrientedOutOfTheirSolids) {
  const sim::GridField f = shell(1.0);  // bore above the grid: sealed
  const NodeLattice ice = NodeLattice::from_ice_fraction(f, 0),
                    water = NodeLattice::from_water_fraction(f);
  const GridSurfaces s = extract_grid_surfaces(ice, water);
  EXPECT_EQ(s.cavities, 1);
  EXPECT_GT(s.cavity_water_fraction, 0.9);
  // Closed, manifold, no self-intersection, each component enclosing a positive volume: the
  // outer surface out of the ice, the inner one out of the water (into the ice).
  EXPECT_EQ(check_closed_oriented_components(s.outer), "");
  EXPECT_EQ(check_closed_oriented_components(s.inner), "");
  EXPECT_GT(enclosed_volume(s.outer), enclosed_volume(s.inner));
}

TEST(GridSurface, BoreReachingTheCavityOpensItToTheOutside) {
  const sim::GridField f = shell(0.0);  // bore from the centre up through the top
  const NodeLattice ice = NodeLattice::from_ice_fraction(f, 0),
                    water = NodeLattice::from_water_fraction(f);
  const GridSurfaces s = extract_grid_surfaces(ice, water);
  EXPECT_EQ(s.cavities, 0);
  EXPECT_TRUE(s.inner.faces.empty());
  EXPECT_EQ(check_closed_oriented_components(s.outer), "");
}

TEST(GridSurface, LowerLevelsEncloseMoreIce) {
  const sim::GridField f = shell(1.0);
  const NodeLattice ice = NodeLattice::from_ice_fraction(f, 0),
                    water = NodeLattice::from_water_fraction(f);
  double previous = 0;
  for (float level : {0.8f, 0.5f, 0.2f}) {
    const GridSurfaces s = extract_grid_surfaces(ice, water, level);
    const double v = enclosed_volume(s.outer) - enclosed_volume(s.inner);
    EXPECT_GT(v, previous) << level;  // superlevel sets are nested
    previous = v;
  }
}

}  // namespace
}  // namespace thaw::mesh
