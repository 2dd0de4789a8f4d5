#include "src/mesh/mesh_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "base/error.h"
#include "base/number_text.h"

namespace thaw::mesh {

void validate(const MeshOptions& o) {
  auto positive = [](const char* name, double v) {
    if (!std::isfinite(v) || !(v > 0))
      throw UserError("", name, "must be a finite number > 0, got " + shortest_text(v));
  };
  auto non_negative = [](const char* name, double v) {
    if (!std::isfinite(v) || v < 0)
      throw UserError("", name,
                      "must be a finite number >= 0 (0 = automatic), got " + shortest_text(v));
  };
  non_negative("edge_length_m", o.edge_length_m);
  if (o.edge_length_m > 0 && o.edge_length_m < kMinEdgeLengthM)
    throw UserError("", "edge_length_m",
                    "must be 0 (automatic) or at least " + shortest_text(kMinEdgeLengthM) +
                        " m, got " + shortest_text(o.edge_length_m));
  non_negative("distance_m", o.distance_m);
  non_negative("scene_radius_m", o.scene_radius_m);
  positive("relative_distance", o.relative_distance);
  positive("relative_error_bound", o.relative_error_bound);
  if (!std::isfinite(o.min_radius_m) || o.min_radius_m < 0)
    throw UserError("", "min_radius_m",
                    "must be a finite number >= 0, got " + std::to_string(o.min_radius_m));
  if (!std::isfinite(o.angle_deg) || !(o.angle_deg > 0) || o.angle_deg > 30)
    throw UserError("", "angle_deg",
                    "must be in (0, 30] (CGAL guarantees termination only up to 30), got " +
                        std::to_string(o.angle_deg));
  if (o.triangles < 0 || (o.triangles > 0 && o.triangles < 50) ||
      o.triangles > kMaxTrianglesPerSurface)
    throw UserError("", "triangles",
                    "must be 0 (unused) or in [50, 5e7], got " + std::to_string(o.triangles));
  // CLI11 saturates 99999999999999999999 to 2^63 - 1: a budget above the per-surface limit is a
  // typo, not a setting.
  if (o.max_triangles < 0 || o.max_triangles > kMaxTrianglesPerSurface)
    throw UserError("", "max_triangles",
                    "must be 0 (none) or at most 5e7, got " + std::to_string(o.max_triangles));
  if (o.jobs < 0 || o.jobs > 4096)
    throw UserError("", "jobs", "must be in [0, 4096], got " + std::to_string(o.jobs));
  if (o.relative_error_bound > 1e-2)
    throw UserError("", "relative_error_bound",
                    "must be <= 1e-2, got " + std::to_string(o.relative_error_bound));
}

namespace {
// The automatic edge length and distance for a scene of radius R: a 640 x 640 render that frames
// the whole shell (diameter 2R over ~500 px) has pixels of ~R / 250; the distance R / 1000 is a
// quarter pixel and the edge R / 12 about ten pixels (2.5 mm and 30 um for R = 3 cm).
double auto_edge(double scene_radius) {
  return scene_radius / 12;
}
double auto_distance(double scene_radius) {
  return 1e-3 * scene_radius;
}
double scene_of(const ShellShape& shape, const MeshOptions& o) {
  return o.scene_radius_m > 0 ? o.scene_radius_m : shape.bounding_radius();
}
double edge_of(const ShellShape& shape, const MeshOptions& o) {
  return o.edge_length_m > 0 ? o.edge_length_m : auto_edge(scene_of(shape, o));
}
}  // namespace

MeshOptions resolve_scene(MeshOptions o, double scene_radius_m) {
  o.scene_radius_m = scene_radius_m;
  if (o.edge_length_m == 0) o.edge_length_m = auto_edge(scene_radius_m);
  if (o.distance_m == 0) o.distance_m = auto_distance(scene_radius_m);
  return o;
}

MeshOptions resolve_triangle_target(MeshOptions o, double largest_area_m2) {
  if (o.triangles <= 0 || !(largest_area_m2 > 0)) return o;
  // N = 1.32 A / size^2 with size = edge / sqrt(3)  =>  edge = sqrt(3 * 1.32 * A / N).
  o.edge_length_m = std::sqrt(3.0 * 1.32 * largest_area_m2 / static_cast<double>(o.triangles));
  if (!o.keep_distance) {
    // A facet no larger than the size bound deviates from a sphere of radius R by at most
    // size^2 / (2R); with R >= size that is <= size / 2, so distance = size never binds on
    // surfaces whose curvature radius exceeds the facet size.
    o.distance_m = o.edge_length_m / std::sqrt(3.0);
    o.relative_distance = 1.0;
    o.distance_relaxed = true;
  }
  return o;
}

SurfaceCriteria criteria_for(const ShellShape& shape, const MeshOptions& o, double max_distance_m) {
  SurfaceCriteria c;
  c.facet_angle_deg = o.angle_deg;
  const double distance = o.distance_m > 0 ? o.distance_m : auto_distance(scene_of(shape, o));
  c.facet_size_m = edge_of(shape, o) / std::sqrt(3.0);
  c.facet_distance_m = std::min(distance, o.relative_distance * shape.accuracy_length());
  if (max_distance_m > 0) c.facet_distance_m = std::min(c.facet_distance_m, max_distance_m);
  if (o.max_triangles > 0) {
    // Beyond size^2 / (2 radius) the distance bound no longer changes anything.
    // Relaxing helps only if the count without any distance bound fits the budget.
    const double budget = static_cast<double>(o.max_triangles);
    const double no_effect =
        c.facet_size_m * c.facet_size_m / (2 * std::max(shape.radius_m, 1e-300));
    SurfaceCriteria loosest = c;
    loosest.facet_distance_m = std::max(c.facet_distance_m, no_effect);
    if (estimate_triangles(shape, loosest) <= budget)
      while (estimate_triangles(shape, c) > budget && c.facet_distance_m < no_effect)
        c.facet_distance_m *= 1.25;
  }
  return c;
}

double estimate_triangles(const ShellShape& s, const SurfaceCriteria& c) {
  const double r = s.radius_m, a = 2 * s.core_half_size_m;
  const double rc = std::min(c.facet_size_m, std::sqrt(2 * r * c.facet_distance_m));
  if (!(rc > 0)) return std::numeric_limits<double>::infinity();
  if (s.geometry != sim::Geometry::planar) return 1.32 * s.area() / (rc * rc);
  const double flat = 2 * a * a, curved = s.area() - flat;
  const double rf = std::min(c.facet_size_m, 2 * r);
  return 1.32 * (curved / (rc * rc) + flat / (rf * rf));
}

void check_triangle_count(const ShellShape& s, const SurfaceCriteria& c) {
  const double n = estimate_triangles(s, c);
  if (n <= kMaxTrianglesPerSurface) return;
  // The size bound alone (no distance bound): does the edge length already ask for too many?
  SurfaceCriteria size_only = c;
  size_only.facet_distance_m = std::numeric_limits<double>::infinity();
  const bool edge = estimate_triangles(s, size_only) > kMaxTrianglesPerSurface;
  char count[32];
  std::snprintf(count, sizeof count, "%.2g", n);
  throw UserError(
      "", edge ? "edge_length_m" : "distance_m",
      std::string(edge ? "the edge length " + shortest_text(c.facet_size_m * std::sqrt(3.0)) + " m"
                       : "the distance bound " + shortest_text(c.facet_distance_m) + " m") +
          " gives about " + count + " triangles on a surface of radius " +
          shortest_text(s.radius_m) + " m, more than the " + "5e7 a surface may have; use a " +
          (edge ? "longer edge" : "larger distance") + " or a triangle target (triangles)");
}

bool too_thin_to_mesh(const ShellShape& s, const MeshOptions& o) {
  if (o.max_triangles <= 0 || s.geometry != sim::Geometry::planar) return false;
  const double a = 2 * s.core_half_size_m;
  const double rf = std::min(edge_of(s, o) / std::sqrt(3.0), 2 * s.radius_m);
  return 1.32 * 2 * a * a / (rf * rf) > static_cast<double>(o.max_triangles);
}

nlohmann::ordered_json to_json(const MeshOptions& o) {
  nlohmann::ordered_json j;
  j["scene_radius_m"] = o.scene_radius_m;
  j["edge_length_m"] = o.edge_length_m;
  j["triangles"] = o.triangles;
  j["angle_deg"] = o.angle_deg;
  j["distance_m"] = o.distance_m;
  j["relative_distance"] = o.relative_distance;
  j["distance_relaxed_for_triangle_target"] = o.distance_relaxed;
  j["min_radius_m"] = o.min_radius_m;
  j["max_triangles"] = o.max_triangles;
  j["normals"] = o.normals;
  j["relative_error_bound"] = o.relative_error_bound;
  j["reuse_similar_surfaces"] = o.reuse_similar;
  // jobs is deliberately absent: it does not change the output (byte-identical either way).
  return j;
}

std::string describe(const MeshOptions& o) {
  char buf[256];
  std::snprintf(
      buf, sizeof buf,
      "scene radius %.3g mm, edge %.3g mm, angle >= %.3g deg, distance <= %.3g um (and <= %.3g x "
      "size)%s, at most %ld triangles per surface%s",
      o.scene_radius_m * 1e3, o.edge_length_m * 1e3, o.angle_deg, o.distance_m * 1e6,
      o.relative_distance,
      o.triangles > 0 ? (", target " + std::to_string(o.triangles) + " triangles").c_str() : "",
      o.max_triangles, o.normals ? ", normals" : "");
  return buf;
}

}  // namespace thaw::mesh
