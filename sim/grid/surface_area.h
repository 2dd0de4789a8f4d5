#pragma once
// The material | air surface area in each cell of the grid solver, from the gradient of the
// material fraction (|grad m| V, the mean of Youngs' and the plain central differences), so
// that the heated area of a round body is not the stair-step area of its cells; handed on to
// the cells open to the outside air, with a floor for sub-cell remnants, and scaled to the
// area half a step ahead while the surface recedes. Reads m and which cells are exposed;
// writes only its own arrays. Knows nothing of heat, Newton or draining rules.
#include <vector>

#include "sim/grid/block_team.h"
#include "sim/grid/grid_mesh.h"

namespace thaw::sim {

class SurfaceArea {
 public:
  /// `m`: the cells' material fractions; `exposed`: cell open to the outside air or next to it.
  SurfaceArea(const GridMesh& mesh, const std::vector<double>& m, const std::vector<char>& exposed);

  /// Material | air area assigned to each cell [m^2].
  const std::vector<double>& area() const { return surface_area; }
  /// The areas for the step of size dt about to be taken, if the surface moved or the areas
  /// were taken ahead (leader, before the step's coefficients).
  void prepare_step(BlockTeam& team, double dt);
  /// After an accepted step of size dt that drained drained_m3 of material (> 0 if anything
  /// drained): the mean recession speed, and whether the next step must recompute (serial).
  void after_step(bool drained, double drained_m3, double dt);
  /// The areas of the fractions as they are (lead_m = 0), or with the surface moved lead_m
  /// along its normal.
  void update(BlockTeam& team, double lead_m = 0);

 private:
  void midpoint(BlockTeam& team, double dt);
  /// How much of a handed-on share cell c takes relative to its neighbours: its volume on the
  /// axisymmetric grid (rings grow with the radius), 1 on the uniform 3D grid. By count alone,
  /// a ring next to the axis took as much of a neighbour's area, and so of the surface heat, as
  /// a ring three to five times its size: per volume it melted faster, and a sphere ablating
  /// under a uniform flux grew a dimple at its poles (0.5 mm deep, 4 cells, after 600 s at
  /// 0.125 mm cells), its total area estimate drifting 2.7 % high (docs/validation.md).
  double share_weight(long c) const { return m_mesh.axisymmetric ? m_mesh.vol[c] : 1.0; }
  void area_gradient(long c, int i, int j, int k);
  void area_share_of(long c, int i, int j, int k);
  void area_final(long c, int i, int j, int k);
  double gradient_area(long c, int i, int j, int k) const;
  double central_gradient(int i, int j, int k) const;
  template <class At>
  double gradient_area_at(long c, At&& at) const;
  double remnant_area(long c, int i, int j, int k, double a) const;
  bool backed_by_bulk(long c, int i, int j, int k) const;

  const GridMesh& m_mesh;
  const std::vector<double>& m;
  const std::vector<char>& exposed;
  const int nx, ny, nz;
  const double dx;                                 ///< cell edge [m]
  std::vector<double> surface_area;                ///< material | air area of the cell [m^2]
  std::vector<double> area_g, area_w, area_share;  ///< update's work arrays
  /// m with the surface moved half a step ahead (update)
  std::vector<double> m_moved;
  /// The fractions whose gradient gives the surface area: m itself, or m_moved.
  const double* m_geo = nullptr;
  double recession_m_s = 0;  ///< mean speed of the draining surface in the last step [m/s]
  bool area_stale = false;   ///< the surface moved, or the area was taken ahead: recompute
  bool area_ahead = false;   ///< the current area was taken ahead of the fractions
};

}  // namespace thaw::sim
