#include "sim/grid/grid_builder.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "base/check.h"
#include "sim/boundary/scenario_air.h"
#include "sim/grid/body_faces.h"
#include "sim/grid/grid_rules.h"

namespace thaw::sim {

namespace {

/// Sub-samples per axis in a cell that the surface may cut (4^3 in 3D, 4^2 in (r, y)).
constexpr int kSamples = 4;
/// Fractions below this are dropped (initial state only: the same limit as the solver's remnants).
constexpr double kMinFraction = 1e-3;

/// Fraction of the cell [lo, lo + s]^3 (axisymmetric: the ring [lo_r, lo_r + s] x [lo_y, ..])
/// inside `d`; `centre_distance` decides cells the surface cannot reach.
double inside_fraction(const SignedDistance& d, bool exact, bool axisymmetric,
                       const std::array<double, 3>& lo, double s) {
  const std::array<double, 3> c{lo[0] + 0.5 * s, lo[1] + 0.5 * s,
                                axisymmetric ? 0.0 : lo[2] + 0.5 * s};
  const double dc = d(c);
  const double reach = (axisymmetric ? std::sqrt(0.5) : std::sqrt(0.75)) * s;
  if (dc <= -reach) return 1;
  if (dc >= reach) return 0;
  if (!exact) return std::clamp(0.5 - dc / s, 0.0, 1.0);  // OBJ: a ramp across the cell
  double inside = 0, total = 0;
  for (int a = 0; a < kSamples; ++a)
    for (int b = 0; b < kSamples; ++b)
      for (int e = 0; e < (axisymmetric ? 1 : kSamples); ++e) {
        const double x = lo[0] + (a + 0.5) * s / kSamples, y = lo[1] + (b + 0.5) * s / kSamples;
        const double z = axisymmetric ? 0.0 : lo[2] + (e + 0.5) * s / kSamples;
        const double w = axisymmetric ? x : 1.0;  // ring volume grows with r
        total += w;
        if (d({x, y, z}) < 0) inside += w;
      }
  return inside / total;
}

/// Diameter of the sphere holding the problem's material volume (ice and water) [m].
double volume_equivalent_diameter_m(const GridProblem& g) {
  const double dx = g.spacing_m;
  const bool axisymmetric = g.geometry == GridField::Geometry::axisymmetric;
  double volume = 0;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        const std::size_t c = (static_cast<std::size_t>(k) * g.cells[1] + j) * g.cells[0] +
                              static_cast<std::size_t>(i);
        const double cell = axisymmetric
                                ? 2 * std::numbers::pi * (g.origin_m[0] + (i + 0.5) * dx) * dx * dx
                                : dx * dx * dx;
        volume += g.material_fraction[c] * cell;
      }
  return std::cbrt(6 * volume / std::numbers::pi);
}

}  // namespace

/// Block of kBlock^3 cells (kBlock^2 in (r, y)) whose fractions are all 0 or all 1 when its
/// centre's distance exceeds the block's half-diagonal plus a cell's reach (signed distances
/// are 1-Lipschitz): the expensive OBJ distance is then evaluated once per block, not per cell.
constexpr int kBlock = 4;

/// 1: block entirely inside, 0: entirely outside, -1: mixed (evaluate its cells).
int block_state(const SignedDistance& d, bool axisymmetric, const std::array<double, 3>& lo,
                double s) {
  const double half = 0.5 * kBlock * s;
  const std::array<double, 3> c{lo[0] + half, lo[1] + half, axisymmetric ? 0.0 : lo[2] + half};
  const double margin = (axisymmetric ? std::sqrt(2.0) : std::sqrt(3.0)) * (half + 0.5 * s);
  const double dc = d(c);
  return dc <= -margin ? 1 : (dc >= margin ? 0 : -1);
}

void shape_fractions(const Scenario& sc, const GridProblem& g, std::vector<double>& ice,
                     std::vector<double>& water) {
  const SignedDistance outer = make_signed_distance(sc.shape.outer, "shape.outer");
  std::optional<SignedDistance> cavity;
  if (sc.shape.cavity) cavity = make_signed_distance(*sc.shape.cavity, "shape.cavity");
  const bool axisymmetric = g.geometry == GridField::Geometry::axisymmetric;
  const long nx = g.cells[0], ny = g.cells[1], nz = g.cells[2], n = nx * ny * nz;
  ice.assign(static_cast<std::size_t>(n), 0.0);
  water.assign(static_cast<std::size_t>(n), 0.0);
  const bool outer_exact = sc.shape.outer.kind != ShapeKind::obj;
  const bool cavity_exact = !sc.shape.cavity || sc.shape.cavity->kind != ShapeKind::obj;
  const long bx = (nx + kBlock - 1) / kBlock, by = (ny + kBlock - 1) / kBlock,
             bz = (nz + kBlock - 1) / kBlock;
  const double s = g.spacing_m;
#pragma omp parallel for schedule(dynamic, 1)
  for (long b = 0; b < bx * by * bz; ++b) {
    const long i0 = (b % bx) * kBlock, j0 = ((b / bx) % by) * kBlock, k0 = (b / (bx * by)) * kBlock;
    auto corner = [&](long i, long j, long k) {
      return std::array<double, 3>{g.origin_m[0] + static_cast<double>(i) * s,
                                   g.origin_m[1] + static_cast<double>(j) * s,
                                   g.origin_m[2] + static_cast<double>(k) * s};
    };
    const int outer_state = block_state(outer, axisymmetric, corner(i0, j0, k0), s);
    const int cavity_state = cavity ? block_state(*cavity, axisymmetric, corner(i0, j0, k0), s) : 0;
    for (long k = k0; k < std::min(nz, k0 + kBlock); ++k)
      for (long j = j0; j < std::min(ny, j0 + kBlock); ++j)
        for (long i = i0; i < std::min(nx, i0 + kBlock); ++i) {
          const long c = i + nx * (j + ny * k);
          const auto lo = corner(i, j, k);
          const double a = outer_state >= 0
                               ? outer_state
                               : inside_fraction(outer, outer_exact, axisymmetric, lo, s);
          double w = 0;
          if (cavity)
            w = cavity_state >= 0 ? cavity_state
                                  : inside_fraction(*cavity, cavity_exact, axisymmetric, lo, s);
          // slivers go to the other material, so no air appears inside the body
          const double body = a < kMinFraction ? 0.0 : a;
          if (sc.shape.fill_water) {  // all water: no ice at t = 0
            water[c] = body;
            ice[c] = 0;
            continue;
          }
          w = std::min(body, w);
          if (w < kMinFraction) w = 0;
          if (body - w < kMinFraction) w = body;
          water[c] = w;
          ice[c] = body - w;
        }
  }
}

GridProblem build_grid_problem(const Scenario& sc) {
  THAW_CHECK(sc.grid != GridGeometry::none && !find_grid_problem(sc),
             "build_grid_problem needs a valid grid scenario");
  GridProblem g;
  g.geometry = sc.grid == GridGeometry::axisymmetric ? GridField::Geometry::axisymmetric
                                                     : GridField::Geometry::cartesian3d;
  const double s = effective_cell_size_m(sc);
  g.spacing_m = s;
  const SignedDistance outer = make_signed_distance(sc.shape.outer, "shape.outer");
  const auto lo = outer.lower(), hi = outer.upper();
  // A grid symmetric about the body's bounding-box centre, padded with air on every side
  // (axisymmetric: from the axis outwards).
  for (int a = 0; a < 3; ++a) {
    const int inner = static_cast<int>(std::ceil((hi[a] - lo[a]) / s - 1e-9));
    g.cells[a] = inner + 2 * kAirPaddingCells;
    g.origin_m[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * g.cells[a] * s;
  }
  if (g.geometry == GridField::Geometry::axisymmetric) {
    g.cells[0] = static_cast<int>(std::ceil(hi[0] / s - 1e-9)) + kAirPaddingCells;
    g.origin_m[0] = 0;
    g.cells[2] = 1;
    g.origin_m[2] = 0;
  }
  std::vector<double> ice, water;
  shape_fractions(sc, g, ice, water);
  const Materials& m = sc.materials;
  g.materials = m;
  const double h_ice = enthalpy_of_temperature(m, sc.ice_initial_temperature_c, false);
  const double h_water = enthalpy_of_temperature(m, sc.water_initial_temperature_c, true);
  g.material_fraction.resize(ice.size());
  g.enthalpy_j_m3.resize(ice.size());
  for (std::size_t c = 0; c < ice.size(); ++c) {
    const double f = ice[c] + water[c];
    g.material_fraction[c] = std::min(f, 1.0);
    g.enthalpy_j_m3[c] = f > 0 ? (ice[c] * h_ice + water[c] * h_water) / f : 0.0;
  }
  // Each cell's face of the body, by its centre's direction from the body's centre.
  const bool axisymmetric = g.geometry == GridField::Geometry::axisymmetric;
  g.face_shape = sc.shape.outer.kind;
  g.face_of_cell.assign(ice.size(), 0);
  if (body_face_names(g.face_shape).size() > 1)
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i)
          g.face_of_cell[(static_cast<std::size_t>(k) * g.cells[1] + j) * g.cells[0] + i] =
              body_face_of_point(sc.shape.outer,
                                 {g.origin_m[0] + (i + 0.5) * s, g.origin_m[1] + (j + 0.5) * s,
                                  axisymmetric ? 0.0 : g.origin_m[2] + (k + 0.5) * s},
                                 axisymmetric);
  g.surface_kind = sc.outer_kind;
  g.surface_temperature_c = sc.outer_temperature_c;
  g.heat_transfer_coefficient_w_m2k = sc.heat_transfer_coefficient_w_m2k;
  g.flux_w_m2 = sc.flux_w_m2;
  if (sc.outer_kind == OuterBoundary::air) g.air = scenario_air(sc);
  if (!sc.outer_faces.empty()) {
    const SurfaceCondition body{g.surface_kind, g.surface_temperature_c,
                                g.heat_transfer_coefficient_w_m2k, g.flux_w_m2, g.air};
    const std::vector<std::string> names = body_face_names(g.face_shape);
    g.face_conditions.assign(names.size(), body);
    for (const FaceBoundary& f : sc.outer_faces) {
      const auto at = std::find(names.begin(), names.end(), f.face);
      THAW_CHECK(at != names.end(), "the rules accept only the body's faces");
      const Scenario own = with_outer_boundary(sc, f.spec);
      SurfaceCondition& c = g.face_conditions[static_cast<std::size_t>(at - names.begin())];
      c = {own.outer_kind, own.outer_temperature_c, own.heat_transfer_coefficient_w_m2k,
           own.flux_w_m2, own.outer_kind == OuterBoundary::air ? scenario_air(own) : Air{}};
    }
  }
  bool air = sc.outer_kind == OuterBoundary::air;
  for (const SurfaceCondition& c : g.face_conditions) air = air || c.kind == OuterBoundary::air;
  if (air) g.air_diameter_m = volume_equivalent_diameter_m(g);
  // A body all water is held by its faces (a container's walls): nothing drains from it.
  g.drain = !sc.shape.fill_water;
  g.flow = sc.natural_convection;
  g.fluid = fluid_model_of(m);
  g.max_step_s = sc.max_step_s;
  g.end_time_s = sc.duration_s;
  return g;
}

}  // namespace thaw::sim
