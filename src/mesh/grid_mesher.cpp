#include "src/mesh/grid_mesher.h"

#include <algorithm>
#include <numbers>
#include <vector>

#include "src/mesh/grid_surface.h"
#include "src/mesh/node_lattice.h"
#include "src/mesh/surface_mesher.h"
#include "src/mesh/surface_remesher.h"
#include "src/mesh/taubin_smoothing.h"

namespace thaw::mesh {

namespace {
// The surface handed out: remeshed and smoothed if that passes the checks, else the
// marching-tetrahedra surface smoothed, else as extracted (closed, manifold and free of
// self-intersections by construction; still checked).
void finish(TriangleMesh& m, const GridMeshOptions& o, double edge, bool inner, std::string& note) {
  if (m.faces.empty()) return;
  const char* which = inner ? "inner" : "outer";
  auto smoothed = [&](TriangleMesh c) {
    if (o.taubin_passes > 0) {
      TaubinOptions t;
      t.passes = o.taubin_passes;
      taubin_smooth(c, t);
    }
    return c;
  };
  std::vector<TriangleMesh> candidates;
  if (o.remesh_iterations > 0)
    candidates.push_back(smoothed(remesh_isotropic(m, edge, o.remesh_iterations)));
  candidates.push_back(smoothed(m));
  candidates.push_back(m);
  std::string problem;
  for (TriangleMesh& c : candidates) {
    problem = check_closed_oriented_components(c);
    if (problem.empty()) {
      m = std::move(c);
      if (o.normals) set_angle_weighted_normals(m);
      return;
    }
    if (note.empty()) note = std::string(which) + ": " + problem;
  }
  throw MeshError(std::string(which) + " grid surface: " + problem);
}
}  // namespace

double cell_volume_m3(const sim::GridField& f, int i) {
  const double h3 = f.spacing_m * f.spacing_m * f.spacing_m;
  return f.geometry == sim::GridField::Geometry::cartesian3d ? h3
                                                             : std::numbers::pi * (2 * i + 1) * h3;
}

namespace {
double field_ice_volume(const sim::GridField& f) {
  double v = 0;
  for (int k = 0; k < f.cells[2]; ++k)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < f.cells[0]; ++i)
        v += f.ice_fraction[f.index(i, j, k)] * cell_volume_m3(f, i);
  return v;
}
double ice_between(const GridSurfaces& s) {
  return enclosed_volume(s.outer) - enclosed_volume(s.inner);
}

// The level of the extracted isosurface: 1/2, unless the ice enclosed at 1/2 falls short of the
// field's ice volume by more than the interpolation error can explain (0.0858 h per unit area,
// docs/mesh.md): then thin walls of partly melted cells (every fraction below 1/2 across them)
// would vanish from the film although the solver still has their ice, and the level is lowered
// (bisection in [0.05, 1/2]; the enclosed volume grows as the level falls) until the surfaces
// enclose the field's ice volume, never so low that the number of sealed cavities changes.
GridSurfaces extract_with_field_volume(const NodeLattice& ice, const NodeLattice& water,
                                       const sim::GridField& field, float& level) {
  level = 0.5f;
  GridSurfaces s = extract_grid_surfaces(ice, water, level);
  const double target = field_ice_volume(field);
  const double slack = 0.0858 * field.spacing_m * (surface_area(s.outer) + surface_area(s.inner));
  if (target - ice_between(s) <= slack) return s;
  float lo = 0.05f, hi = 0.5f;
  for (int it = 0; it < 7; ++it) {  // level to 0.45 / 2^7 = 0.004
    const float mid = 0.5f * (lo + hi);
    // A level so low that it seals the hole of a broken-through shell (fewer or more cavities
    // than at 1/2) is too low: the film must open when the solver's shell opens.
    const GridSurfaces x = extract_grid_surfaces(ice, water, mid);
    (ice_between(x) < target && x.cavities == s.cavities ? hi : lo) = mid;
  }
  level = hi;  // the lowest level tried that kept the topology and did not exceed the volume
  return extract_grid_surfaces(ice, water, level);
}
}  // namespace

sim::GridField coarsened_twice(const sim::GridField& f) {
  const bool axi = f.geometry == sim::GridField::Geometry::axisymmetric;
  sim::GridField c;
  c.geometry = f.geometry;
  c.spacing_m = 2 * f.spacing_m;
  c.origin_m = f.origin_m;
  c.time_s = f.time_s;
  c.cells = {(f.cells[0] + 1) / 2, (f.cells[1] + 1) / 2, axi ? 1 : (f.cells[2] + 1) / 2};
  c.temperature_c.assign(c.cell_count(), 0.0f);
  c.ice_fraction.assign(c.cell_count(), 0.0f);
  c.water_fraction.assign(c.cell_count(), 0.0f);
  std::vector<double> ice(c.cell_count(), 0.0), water(c.cell_count(), 0.0),
      temperature(c.cell_count(), 0.0);
  for (int k = 0; k < f.cells[2]; ++k)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < f.cells[0]; ++i) {
        const std::size_t n = f.index(i, j, k), m = c.index(i / 2, j / 2, axi ? 0 : k / 2);
        const double w = cell_volume_m3(f, i);
        ice[m] += w * f.ice_fraction[n];
        water[m] += w * f.water_fraction[n];
        temperature[m] += w * f.temperature_c[n];
      }
  // Divided by the whole coarse cell's volume: cells beyond the fine grid count as air (the
  // fine grid's own outside), so the total ice and water volumes are unchanged.
  for (int k = 0; k < c.cells[2]; ++k)
    for (int j = 0; j < c.cells[1]; ++j)
      for (int i = 0; i < c.cells[0]; ++i) {
        const std::size_t m = c.index(i, j, k);
        const double v = cell_volume_m3(c, i);
        c.ice_fraction[m] = static_cast<float>(std::min(1.0, ice[m] / v));
        c.water_fraction[m] = static_cast<float>(std::min(1.0 - c.ice_fraction[m], water[m] / v));
        c.temperature_c[m] = static_cast<float>(temperature[m] / v);
      }
  return c;
}

GridMeshResult mesh_grid_field(const sim::GridField& fine, const GridMeshOptions& o) {
  const double edge = o.edge_length_m > 0 ? o.edge_length_m : fine.spacing_m;
  // Edges of two cells or more cannot show the finest cells' detail: extracting on the
  // block-averaged field (an exact volume-fraction field at 2 h) gives a quarter of the
  // marching-tetrahedra triangles, which the remesher would otherwise have to collapse (measured
  // on the hollow cube, 0.83 mm cells, 2.5 mm edges: 92 k triangles remeshed in 0.65 s).
  // Halved again while the edge still spans two cells (a revolved axisymmetric field or fine
  // cells under coarse edges); each block average is again an exact volume-fraction field.
  sim::GridField coarse;
  bool coarsened = false;
  while (o.coarsen && edge >= 2 * (coarsened ? coarse.spacing_m : fine.spacing_m)) {
    coarse = coarsened_twice(coarsened ? coarse : fine);
    coarsened = true;
  }
  const sim::GridField& field = coarsened ? coarse : fine;
  const NodeLattice ice = NodeLattice::from_ice_fraction(field, o.smoothing_passes);
  const NodeLattice water = NodeLattice::from_water_fraction(field);
  GridMeshResult r;
  float level = 0.5f;
  GridSurfaces s = o.match_field_volume ? extract_with_field_volume(ice, water, field, level)
                                        : extract_grid_surfaces(ice, water, level);
  r.iso_level = level;
  r.cavities = s.cavities;
  r.cavity_water_fraction = s.cavity_water_fraction;
  finish(s.outer, o, edge, false, r.remesh_problem);
  finish(s.inner, o, edge, true, r.remesh_problem);
  r.outer = std::move(s.outer);
  r.inner = std::move(s.inner);
  return r;
}

}  // namespace thaw::mesh
