#include "src/mesh/grid_mesher.h"

#include <algorithm>
#include <numbers>
#include <string>
#include <vector>

#include "base/check.h"
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

// Whether `f` holds water sealed from the outside by the solver's own rule
// (sim/grid/cavity_drain.h): a cell is open when less than half of it is ice, the outside is the
// open cells 6-connected to the material-free cells of the grid's border (the axis of an
// axisymmetric grid is no border) that are not a cavity's (at least as much water as ice: the
// solver drains every other cell in or next to the outside each step, so in a field such water
// is a cavity's), and an enclosed open cell holding water is a sealed cavity (melt inside the
// ice, in cells at least half ice, is not: after break-through such cells hold ~1e-6 of water).
// Until the solver's break_through the film must show the cavity closed and full, after it open
// (the water an open shell holds as a cup is not sealed).
bool holds_sealed_water(const sim::GridField& f) {
  const bool axi = f.geometry == sim::GridField::Geometry::axisymmetric;
  const int nx = f.cells[0], ny = f.cells[1], nz = f.cells[2];
  std::vector<char> outside(f.cell_count(), 0);
  std::vector<std::size_t> queue;
  auto open = [&](std::size_t c) { return f.ice_fraction[c] < 0.5f; };
  auto cavity = [&](std::size_t c) {
    return f.water_fraction[c] > 0 && f.water_fraction[c] >= f.ice_fraction[c];
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool border =
            (!axi && (i == 0 || k == 0 || k == nz - 1)) || i == nx - 1 || j == 0 || j == ny - 1;
        const std::size_t c = f.index(i, j, k);
        if (border && f.ice_fraction[c] == 0 && f.water_fraction[c] == 0) {
          outside[c] = 1;
          queue.push_back(c);
        }
      }
  const std::size_t sx = 1, sy = static_cast<std::size_t>(nx),
                    sz = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t c = queue[head];
    const int i = static_cast<int>(c % sy), j = static_cast<int>((c / sy) % ny),
              k = static_cast<int>(c / sz);
    auto visit = [&](bool inside, std::size_t nb) {
      if (inside && !outside[nb] && open(nb) && !cavity(nb)) {
        outside[nb] = 1;
        queue.push_back(nb);
      }
    };
    visit(i > 0, c - sx);
    visit(i + 1 < nx, c + sx);
    visit(j > 0, c - sy);
    visit(j + 1 < ny, c + sy);
    visit(k > 0, c - sz);
    visit(k + 1 < nz, c + sz);
  }
  // Each body of enclosed water is sealed unless it touches the outside where the wall is gone
  // (an ice-free cell of it beside an ice-free outside cell): then it is water held in an open
  // cup, whose free surface meets the air (sim/grid/cavity_drain.h).
  auto ice_free = [&](std::size_t c) { return f.ice_fraction[c] < 1e-3f; };
  auto water = [&](std::size_t c) { return !outside[c] && open(c) && f.water_fraction[c] > 0.01f; };
  std::vector<char> seen(f.cell_count(), 0);
  for (std::size_t start = 0; start < f.cell_count(); ++start) {
    if (seen[start] || !water(start)) continue;
    bool touches_air = false;
    queue.assign(1, start);
    seen[start] = 1;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t c = queue[head];
      const int i = static_cast<int>(c % sy), j = static_cast<int>((c / sy) % ny),
                k = static_cast<int>(c / sz);
      auto visit = [&](bool inside, std::size_t nb) {
        if (!inside) return;
        if (outside[nb] && ice_free(nb) && ice_free(c)) touches_air = true;
        if (!seen[nb] && water(nb)) {
          seen[nb] = 1;
          queue.push_back(nb);
        }
      };
      visit(i > 0, c - sx);
      visit(i + 1 < nx, c + sx);
      visit(j > 0, c - sy);
      visit(j + 1 < ny, c + sy);
      visit(k > 0, c - sz);
      visit(k + 1 < nz, c + sz);
    }
    if (!touches_air) return true;
  }
  return false;
}

// The level of the extracted isosurface: 1/2, unless
//  - the field holds sealed water (holds_sealed_water) but the lattice at 1/2 opens the cavity
//    (a wall the lattice resolves with every value below 1/2: block averages, an axisymmetric
//    field revolved): then the highest level that seals it (bisection in [0.05, 1/2]); the film
//    must not open the shell before the solver does;
//  - the ice enclosed (outer minus inner volume) falls short of the field's ice volume by more
//    than the interpolation error can explain (0.0858 h per unit area, docs/mesh.md): then thin
//    walls of partly melted cells (every fraction below 1/2 across them) would vanish from the
//    film although the solver still has their ice, and the level is lowered further (bisection;
//    the enclosed volume grows as the level falls) until the surfaces enclose the field's ice
//    volume, never so low that the number of sealed cavities changes (a lower level first
//    sealed the fresh hole of a broken-through shell, and the film opened one frame late).
GridSurfaces extract_with_field_volume(const NodeLattice& ice, const NodeLattice& water,
                                       const sim::GridField& field, bool sealed, float& level) {
  level = 0.5f;
  GridSurfaces s = extract_grid_surfaces(ice, water, level);
  if (sealed && s.cavities == 0) {
    float lo = 0.05f, hi = 0.5f;
    if (extract_grid_surfaces(ice, water, lo).cavities > 0) {
      for (int it = 0; it < 7; ++it) {  // level to 0.45 / 2^7 = 0.004
        const float mid = 0.5f * (lo + hi);
        (extract_grid_surfaces(ice, water, mid).cavities > 0 ? lo : hi) = mid;
      }
      level = lo;
      s = extract_grid_surfaces(ice, water, level);
    }
  }
  const double target = field_ice_volume(field);
  const double slack = 0.0858 * field.spacing_m * (surface_area(s.outer) + surface_area(s.inner));
  if (target - ice_between(s) <= slack) return s;
  float lo = 0.05f, hi = level;
  for (int it = 0; it < 7; ++it) {
    const float mid = 0.5f * (lo + hi);
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
  // Fields come from the solver or through read_grid_field, which refuses such headers as the
  // user's error; here they would overflow or collapse the lattice (SIGFPE, SIGSEGV, OOM).
  const auto header = sim::find_header_problem(fine);
  const std::string why = header ? header->field + ": " + header->problem : std::string();
  THAW_CHECK(!header, why.c_str());
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
  // The block average is used only where it shows what the field shows: at level 1/2, with the
  // solver's topology (a sealed cavity stays sealed). A wall thinner than two cells averages
  // below 1/2 and would need a lowered level, which made the thinning shell lumpy and opened it
  // in the film up to three frames before the solver's break_through (hollow_cube.toml at
  // 1458 s): such steps are extracted from the cells themselves.
  const bool sealed = holds_sealed_water(fine);
  GridMeshResult r;
  float level = 0.5f;
  GridSurfaces s;
  auto extract = [&](const sim::GridField& field) {
    const NodeLattice ice = NodeLattice::from_ice_fraction(field, o.smoothing_passes);
    const NodeLattice water = NodeLattice::from_water_fraction(field);
    level = 0.5f;
    s = o.match_field_volume ? extract_with_field_volume(ice, water, field, sealed, level)
                             : extract_grid_surfaces(ice, water, level);
  };
  if (coarsened) extract(coarse);
  if (!coarsened || level != 0.5f || (s.cavities > 0) != sealed) extract(fine);
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
