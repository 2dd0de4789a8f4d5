#include "sim/grid/grid_rules.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/number_text.h"
#include "sim/grid/grid_field.h"

namespace thaw::sim {

const char* to_string(GridGeometry grid) {
  switch (grid) {
    case GridGeometry::none:
      return "";
    case GridGeometry::axisymmetric:
      return "axisymmetric";
    case GridGeometry::cartesian3d:
      return "3d";
  }
  return "?";
}

namespace {

/// Numbers in messages: the shortest text that reads back as the same double.
std::string num(double v) {
  return shortest_text(v);
}

std::string vec(const std::array<double, 3>& v) {
  std::string out = "[";
  for (int a = 0; a < 3; ++a) out += (a ? ", " : "") + num(v[a]);
  return out + "]";
}

/// Sizes of one shape; key is "shape.outer" or "shape.cavity".
std::optional<GridRuleProblem> size_problem(const ShapeSpec& s, const std::string& key) {
  auto positive = [&](const char* name, double v) -> std::optional<GridRuleProblem> {
    if (!(v > 0) || !std::isfinite(v))
      return GridRuleProblem{key + "." + name, "must be positive (got " + num(v) + ")"};
    return std::nullopt;
  };
  for (double c : s.center_m)
    if (!std::isfinite(c)) return GridRuleProblem{key + ".center_m", "must be finite"};
  switch (s.kind) {
    case ShapeKind::sphere:
      return positive("radius_m", s.radius_m);
    case ShapeKind::cylinder:
      if (auto p = positive("radius_m", s.radius_m)) return p;
      return positive("height_m", s.height_m);
    case ShapeKind::box: {
      for (double v : s.size_m)
        if (!(v > 0) || !std::isfinite(v))
          return GridRuleProblem{key + ".size_m",
                                 "every edge must be positive (got " + vec(s.size_m) + ")"};
      const double smallest = std::min({s.size_m[0], s.size_m[1], s.size_m[2]});
      if (!(s.edge_radius_m >= 0) || !(s.edge_radius_m <= 0.5 * smallest))
        return GridRuleProblem{key + ".edge_radius_m",
                               "must be in [0, half the smallest edge = " + num(0.5 * smallest) +
                                   " m] (got " + num(s.edge_radius_m) + ")"};
      return std::nullopt;
    }
    case ShapeKind::obj:
      if (!(s.scale > 0) || !std::isfinite(s.scale))
        return GridRuleProblem{key + ".scale", "must be positive (got " + num(s.scale) + ")"};
      for (double c : s.translate_m)
        if (!std::isfinite(c)) return GridRuleProblem{key + ".translate_m", "must be finite"};
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<GridRuleProblem> axisymmetric_problem(const ShapeSpec& s, const std::string& key) {
  if (s.kind != ShapeKind::sphere && s.kind != ShapeKind::cylinder)
    return GridRuleProblem{
        key + ".kind", std::string("geometry = \"axisymmetric\" accepts only spheres and vertical "
                                   "cylinders centred on the y axis (got ") +
                           to_string(s.kind) + "); use geometry = \"3d\""};
  if (s.center_m[0] != 0 || s.center_m[2] != 0)
    return GridRuleProblem{key + ".center_m",
                           "must lie on the vertical y axis (x = z = 0) for geometry = "
                           "\"axisymmetric\" (got " +
                               vec(s.center_m) + ")"};
  return std::nullopt;
}

/// A body larger than the largest the scenario rules accept (100 m,
/// sim/scenario/scenario_rules.cpp) or reaching beyond the bounds of a field
/// (sim/grid/grid_field.h): named by its OBJ file (whose coordinates are metres too) or by its
/// table.
std::optional<GridRuleProblem> body_extent_problem(const SignedDistance& d, const ShapeSpec& spec,
                                                   const std::string& key) {
  const auto lo = d.lower(), hi = d.upper();
  for (int a = 0; a < 3; ++a) {
    const double size = hi[a] - lo[a], reach = std::max(std::abs(lo[a]), std::abs(hi[a]));
    if (size <= kMaxFieldSpacingM && reach <= kMaxFieldCoordinateM) continue;
    std::string what;
    if (spec.kind == ShapeKind::obj) what.append("(").append(spec.file).append(") ");
    what.append("spans [").append(num(lo[a])).append(", ").append(num(hi[a]));
    what.append("] m along ").push_back("xyz"[a]);
    if (spec.kind == ShapeKind::obj) what.append(" after scale and translate_m");
    what.append("; a body is at most ").append(num(kMaxFieldSpacingM));
    what.append(" m across and within ").append(num(kMaxFieldCoordinateM));
    what.append(" m of the origin (lengths are in metres)");
    return GridRuleProblem{spec.kind == ShapeKind::obj ? key + ".file" : key, what};
  }
  return std::nullopt;
}

double largest_extent(const SignedDistance& d) {
  const auto lo = d.lower(), hi = d.upper();
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

}  // namespace

SignedDistance make_signed_distance(const ShapeSpec& spec, const std::string& key) {
  if (spec.kind != ShapeKind::obj) return SignedDistance(spec);
  auto mesh = std::make_shared<const ObjMesh>(
      read_obj_mesh(spec.file, spec.scale, spec.translate_m, "", key + ".file"));
  return SignedDistance(spec, std::move(mesh));
}

double thinnest_wall_m(const SignedDistance& outer, const SignedDistance* cavity) {
  if (!cavity) {
    const auto lo = outer.lower(), hi = outer.upper();
    return 0.5 * std::min({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }
  double wall = std::numeric_limits<double>::infinity();
  for (const auto& p : cavity->surface_samples(1500)) wall = std::min(wall, -outer(p));
  return wall;
}

namespace {
/// min(largest extent / cells across, thinnest wall / kDefaultWallCells), and with the water
/// flowing (cavity_extent > 0) at most its thermal boundary layer / kMinBoundaryLayerCells.
double default_cell(const Scenario& s, double extent, double wall, double cavity_extent) {
  const double across = s.grid == GridGeometry::axisymmetric ? kDefaultCellsAcrossAxisymmetric
                                                             : kDefaultCellsAcross3d;
  double cell = std::min(extent / across, wall / kDefaultWallCells);
  if (s.natural_convection && cavity_extent > 0)
    cell = std::min(cell,
                    cavity_flow_scale(s, cavity_extent).boundary_layer_m / kMinBoundaryLayerCells);
  return cell;
}
}  // namespace

flow::FluidModel fluid_model_of(const Materials& m) {
  flow::FluidModel f;
  f.density = m.water_density_model == Materials::DensityModel::linear
                  ? flow::FluidModel::Density::linear
                  : flow::FluidModel::Density::water;
  if (f.density == flow::FluidModel::Density::linear)
    f.reference_density_kg_m3 = m.water_density_kg_m3;
  f.expansion_per_k = m.water_expansion_per_k;
  f.reference_temperature_c = m.melting_point_c;
  f.viscosity_pa_s = m.water_viscosity_pa_s;
  return f;
}

FlowScale water_flow_scale(const Scenario& s, double extent_m, double tm, double tw) {
  const flow::FluidModel fluid = fluid_model_of(s.materials);
  // The buoyancy's spread over [T_m, T_water], sampled, with the density maximum when inside.
  double lo = fluid.buoyancy_m_s2(tm), hi = lo;
  const auto take = [&](double t) {
    lo = std::min(lo, fluid.buoyancy_m_s2(t));
    hi = std::max(hi, fluid.buoyancy_m_s2(t));
  };
  for (int k = 1; k <= 64; ++k) take(tm + (tw - tm) * k / 64.0);
  if (fluid.density == flow::FluidModel::Density::water &&
      (flow::kWaterDensityMaxTemperatureC - tm) * (flow::kWaterDensityMaxTemperatureC - tw) < 0)
    take(flow::kWaterDensityMaxTemperatureC);
  const double nu = fluid.kinematic_viscosity_m2_s(0.5 * (tm + tw));
  const double alpha = s.materials.water_conductivity_w_mk / s.materials.water_heat_capacity();
  FlowScale f;
  f.length_m = extent_m;
  f.rayleigh = (hi - lo) * extent_m * extent_m * extent_m / (nu * alpha);
  f.boundary_layer_m = f.rayleigh > 0 ? extent_m * std::pow(f.rayleigh, -0.25)
                                      : std::numeric_limits<double>::infinity();
  return f;
}

FlowScale cavity_flow_scale(const Scenario& s, double cavity_extent_m) {
  return water_flow_scale(s, cavity_extent_m, s.materials.melting_point_c,
                          s.water_initial_temperature_c);
}

double smallest_max_step_s(const Materials& m, double cell_m) {
  const double alpha = std::max(m.ice_conductivity_w_mk / m.ice_heat_capacity(),
                                m.water_conductivity_w_mk / m.water_heat_capacity());
  return cell_m * cell_m / alpha * (kStepTemperatureChangeK / kWidestTemperatureSpanK);
}

double effective_cell_size_m(const Scenario& s) {
  if (s.cell_size_m > 0) return s.cell_size_m;
  const SignedDistance outer = make_signed_distance(s.shape.outer, "shape.outer");
  std::optional<SignedDistance> cavity;
  if (s.shape.cavity) cavity = make_signed_distance(*s.shape.cavity, "shape.cavity");
  return default_cell(s, largest_extent(outer), thinnest_wall_m(outer, cavity ? &*cavity : nullptr),
                      cavity ? largest_extent(*cavity) : 0.0);
}

std::optional<GridRuleProblem> find_grid_problem(const Scenario& s) {
  if (s.grid == GridGeometry::none) return std::nullopt;
  if (!(s.max_step_s > 0) || !std::isfinite(s.max_step_s))
    return GridRuleProblem{"simulation.max_step_s",
                           "must be positive (got " + num(s.max_step_s) + ")"};
  if (!(s.cell_size_m >= 0) || !std::isfinite(s.cell_size_m))
    return GridRuleProblem{"simulation.cell_size_m",
                           "must be positive (got " + num(s.cell_size_m) + ")"};
  if (auto p = size_problem(s.shape.outer, "shape.outer")) return p;
  if (s.shape.cavity)
    if (auto p = size_problem(*s.shape.cavity, "shape.cavity")) return p;
  if (s.grid == GridGeometry::axisymmetric) {
    if (auto p = axisymmetric_problem(s.shape.outer, "shape.outer")) return p;
    if (s.shape.cavity)
      if (auto p = axisymmetric_problem(*s.shape.cavity, "shape.cavity")) return p;
  }
  std::optional<SignedDistance> outer, cavity;
  try {
    outer = make_signed_distance(s.shape.outer, "shape.outer");
    if (s.shape.cavity) cavity = make_signed_distance(*s.shape.cavity, "shape.cavity");
  } catch (const UserError& e) {
    return GridRuleProblem{e.where(), e.problem()};
  }
  // Before the cells: a body of 1e308 m (one OBJ vertex far out) asked for "inf cells" of
  // simulation.cell_size_m, a key the file may not hold (issue 27); name the body instead.
  if (auto p = body_extent_problem(*outer, s.shape.outer, "shape.outer")) return p;
  if (cavity)
    if (auto p = body_extent_problem(*cavity, *s.shape.cavity, "shape.cavity")) return p;
  const double wall = thinnest_wall_m(*outer, cavity ? &*cavity : nullptr);
  if (cavity && !(wall > 0))
    return GridRuleProblem{"shape.cavity",
                           "must lie strictly inside the outer body, but it reaches " + num(-wall) +
                               " m outside its surface (or touches it)"};
  const double extent = largest_extent(*outer);
  const double cell = s.cell_size_m > 0
                          ? s.cell_size_m
                          : default_cell(s, extent, wall, cavity ? largest_extent(*cavity) : 0.0);
  if (wall < kMinWallCells * cell) {
    std::string message = s.cell_size_m > 0 ? "(" + num(cell) + " m) is too coarse: "
                                            : "the default cell size is too coarse: ";
    message += cavity ? "the thinnest wall is " : "the thinnest half-thickness of the body is ";
    message += num(wall) + " m = " + num(std::floor(wall / cell * 100) / 100) + " cells, at least ";
    message +=
        num(kMinWallCells) + " are needed (use cell_size_m <= " + num(wall / kMinWallCells) + ")";
    return GridRuleProblem{"simulation.cell_size_m", message};
  }
  const auto lo = outer->lower(), hi = outer->upper();
  double cells = 1;
  if (s.grid == GridGeometry::axisymmetric)
    cells = (std::max(std::abs(lo[0]), std::abs(hi[0])) / cell + 3) * ((hi[1] - lo[1]) / cell + 5);
  else
    for (int a = 0; a < 3; ++a) cells *= (hi[a] - lo[a]) / cell + 5;
  if (cells > kMaxGridCells)
    return GridRuleProblem{"simulation.cell_size_m", "(" + num(cell) + " m) needs " +
                                                         num(std::round(cells)) +
                                                         " cells, more than the limit of " +
                                                         num(kMaxGridCells) + "; use larger cells"};
  if (const double floor_s = smallest_max_step_s(s.materials, cell); s.max_step_s < floor_s) {
    std::string message = "(" + num(s.max_step_s) + " s) is below the smallest useful step for ";
    message += num(cell) + " m cells, " + num(floor_s);
    message += " s (the time heat takes to diffuse across one cell / ";
    message += num(kWidestTemperatureSpanK);
    message += "): shorter steps add nothing but their number";
    return GridRuleProblem{"simulation.max_step_s", message};
  }
  if (s.shape.fill_water && s.shape.cavity)
    return GridRuleProblem{"shape.fill",
                           "\"water\" makes the whole body water, which cannot hold a cavity "
                           "(remove shape.cavity, or fill = \"ice\")"};
  if ((s.shape.cavity || s.shape.fill_water) &&
      s.water_initial_temperature_c < s.materials.melting_point_c)
    return GridRuleProblem{"water.initial_temperature_c",
                           "(" + num(s.water_initial_temperature_c) +
                               " C) is below the melting point: supercooled water is not modelled"};
  if (s.natural_convection && (cavity || s.shape.fill_water)) {
    // The water's temperature span: from the ice's melting point to the cavity's water, or
    // over the water and the faces that hold a temperature when the body is all water.
    double lo = s.water_initial_temperature_c, hi = lo;
    const auto take = [&](double t) { lo = std::min(lo, t), hi = std::max(hi, t); };
    if (cavity) take(s.materials.melting_point_c);
    const auto holds = [](OuterBoundary k) {
      return k == OuterBoundary::temperature || k == OuterBoundary::convective ||
             k == OuterBoundary::air;
    };
    if (!cavity) {
      // liquid water is never below the melting point: a colder face freezes it instead
      const double tm = s.materials.melting_point_c;
      if (holds(s.outer_kind)) take(std::max(s.outer_temperature_c, tm));
      for (const FaceBoundary& f : s.outer_faces)
        if (holds(f.spec.kind)) take(std::max(f.spec.temperature_c, tm));
    }
    const FlowScale flow = water_flow_scale(s, cavity ? largest_extent(*cavity) : extent, lo, hi);
    if (flow.boundary_layer_m < kMinBoundaryLayerCells * cell) {
      std::string message = s.cell_size_m > 0 ? "(" + num(cell) + " m) is too coarse for the flow: "
                                              : "the default cell size (" + num(cell) +
                                                    " m) is too coarse for the flow: ";
      message += "the water's thermal boundary layer is about " + num(flow.boundary_layer_m);
      message += " m (L Ra^-1/4, Ra = " + num(std::round(flow.rayleigh)) + " over the water's ";
      message += num(flow.length_m) + " m) and needs at least " + num(kMinBoundaryLayerCells);
      message += " cells across it: use cell_size_m <= " +
                 num(flow.boundary_layer_m / kMinBoundaryLayerCells) + " (or flow = \"none\")";
      return GridRuleProblem{"simulation.cell_size_m", message};
    }
  }
  return std::nullopt;
}

}  // namespace thaw::sim
