#include "src/inspect/mesh_report.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkMassProperties.h>
#include <vtkMeshQuality.h>
#include <vtkNew.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "base/check.h"
#include "base/edge_topology.h"
#include "base/error.h"
#include "base/obj_reader.h"
#include "base/point3.h"
#include "src/inspect/vtk_messages.h"
#include "src/inspect/vtk_polydata.h"

namespace thaw::inspect {
namespace {

using Vec3 = meshio::Point3;
using meshio::cross, meshio::dot, meshio::norm, meshio::sub;

struct QualityStats {
  double min = 0, mean = 0, max = 0;
};

/// Per-triangle quality from vtkMeshQuality (measure set by `configure`).
template <class Configure>
QualityStats mesh_quality(vtkPolyData* poly, Configure configure) {
  vtkNew<vtkMeshQuality> quality;
  quality->SetInputData(poly);
  configure(quality.Get());
  quality->Update();
  vtkDataArray* values = quality->GetOutput()->GetCellData()->GetArray("Quality");
  QualityStats stats;
  if (values == nullptr || values->GetNumberOfTuples() == 0) return stats;
  stats.min = std::numeric_limits<double>::infinity();
  stats.max = -stats.min;
  double sum = 0;
  const vtkIdType n = values->GetNumberOfTuples();
  for (vtkIdType i = 0; i < n; ++i) {
    const double q = values->GetTuple1(i);
    stats.min = std::min(stats.min, q);
    stats.max = std::max(stats.max, q);
    sum += q;
  }
  stats.mean = sum / static_cast<double>(n);
  return stats;
}

using Triangles = std::vector<std::array<std::int64_t, 3>>;

/// Indices in range and finite coordinates, or a UserError naming the triangle or vertex.
void check_indices_and_coordinates(const TriangleMesh& mesh, const std::string& source) {
  const auto nv = static_cast<std::int64_t>(mesh.vertices.size());
  if (mesh.triangles.empty()) throw UserError(source, "", "empty mesh: no triangles");
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (const std::int64_t i : mesh.triangles[f])
      if (i < 0 || i >= nv)
        throw UserError(
            source, "triangle " + std::to_string(f + 1),
            "vertex index " + std::to_string(i + 1) + " out of range 1.." + std::to_string(nv));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (const double c : mesh.vertices[v])
      if (!std::isfinite(c))
        throw UserError(source, "vertex " + std::to_string(v + 1), "non-finite coordinate");
}

/// Vertex records whose position repeats another's: vertex ids sorted by position, equal
/// neighbours counted. Exact equality is the right test: a mesher that shares vertices writes
/// each position once.
std::int64_t duplicate_vertices(const TriangleMesh& mesh) {
  std::vector<std::int64_t> order(mesh.vertices.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::int64_t a, std::int64_t b) { return mesh.vertices[a] < mesh.vertices[b]; });
  std::int64_t duplicates = 0;
  for (std::size_t k = 1; k < order.size(); ++k)
    if (mesh.vertices[order[k]] == mesh.vertices[order[k - 1]]) ++duplicates;
  return duplicates;
}

/// The triangles split by use: `topology` (every triangle with three distinct corners) and
/// `quality` (those of them with non-zero area). Triangles with a repeated corner have no edges of
/// their own worth counting; zero-area triangles with distinct corners stay in the topology but
/// not in the quality statistics. Both kinds count as degenerate.
struct SortedTriangles {
  Triangles topology, quality;
  std::int64_t degenerate = 0;
};
SortedTriangles sort_triangles(const TriangleMesh& mesh) {
  SortedTriangles out;
  out.topology.reserve(mesh.triangles.size());
  out.quality.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++out.degenerate;
      continue;
    }
    out.topology.push_back(t);
    const Vec3 e0 = sub(mesh.vertices[t[1]], mesh.vertices[t[0]]);
    const Vec3 e1 = sub(mesh.vertices[t[2]], mesh.vertices[t[1]]);
    const Vec3 e2 = sub(mesh.vertices[t[0]], mesh.vertices[t[2]]);
    const double longest2 = std::max({dot(e0, e0), dot(e1, e1), dot(e2, e2)});
    // |e0 x e1| = 2A = L_max h; below 1e-12 L_max^2 the smallest angle is under ~1e-12 rad,
    // i.e. the triangle is flat to within a few thousand ulps of double precision.
    if (norm(cross(e0, e1)) <= 1e-12 * longest2) {
      ++out.degenerate;
      continue;
    }
    out.quality.push_back(t);
  }
  return out;
}

/// Edges, boundary / non-manifold / inconsistent counts, components and edge lengths in linear
/// time (a hash table of edges: base/edge_topology.h). vtkFeatureEdges is not used: it is
/// quadratic in the triangles around an edge and runs out of memory beyond ~850k vertices.
void add_topology(const TriangleMesh& mesh, const Triangles& topo, MeshReport& r) {
  const meshio::EdgeTopology topology = meshio::edge_topology(mesh.vertices, topo);
  r.edges = topology.edges;
  r.boundary_edges = topology.boundary_edges;
  r.non_manifold_edges = topology.non_manifold_edges;
  r.inconsistent_edges = topology.inconsistent_edges;
  r.components = topology.components;
  r.min_edge_m = topology.min_edge_m;
  r.mean_edge_m = topology.mean_edge_m;
  r.max_edge_m = topology.max_edge_m;
  r.closed = r.boundary_edges == 0 && r.non_manifold_edges == 0;
  r.consistently_oriented = r.inconsistent_edges == 0;
}

/// Bounding box of the vertices the topology uses, the unused vertex records and V - E + F.
void add_extent(const TriangleMesh& mesh, const Triangles& topo, MeshReport& r) {
  const auto nv = static_cast<std::int64_t>(mesh.vertices.size());
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : topo)
    for (const std::int64_t i : t) used[i] = 1;
  std::int64_t used_vertices = 0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  r.bbox_min = {inf, inf, inf};
  r.bbox_max = {-inf, -inf, -inf};
  for (std::int64_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++used_vertices;
    for (int c = 0; c < 3; ++c) {
      r.bbox_min[c] = std::min(r.bbox_min[c], mesh.vertices[v][c]);
      r.bbox_max[c] = std::max(r.bbox_max[c], mesh.vertices[v][c]);
    }
  }
  if (used_vertices == 0) r.bbox_min = r.bbox_max = {0, 0, 0};
  r.unused_vertices = nv - used_vertices;
  r.euler_characteristic = used_vertices - r.edges + static_cast<std::int64_t>(topo.size());
}

/// Signed volume by the divergence theorem, sum of tetrahedra (origin, a, b, c): independent of
/// the origin only for a closed surface, positive when the normals (right-hand rule) point out;
/// then the orientation verdict.
void add_signed_volume(const TriangleMesh& mesh, const Triangles& topo, MeshReport& r) {
  long double signed6 = 0;
  for (const auto& t : topo)
    signed6 += dot(mesh.vertices[t[0]], cross(mesh.vertices[t[1]], mesh.vertices[t[2]]));
  r.signed_volume_m3 = static_cast<double>(signed6 / 6);
  if (r.closed && r.consistently_oriented) r.outward = r.signed_volume_m3 > 0;
}

/// Volume and area (vtkMassProperties) over the topology's triangles, then the angle and aspect
/// statistics (vtkMeshQuality) over the non-degenerate ones.
void add_vtk_measures(const TriangleMesh& mesh, const SortedTriangles& sorted, MeshReport& r) {
  // VTK's complaints about a degenerate mesh (vtkMassProperties' coloured, time-stamped
  // "Unpredicted situation" line at coordinates of 1e308, issue 27) never reach the terminal: the
  // report's own rows say what is wrong with the mesh.
  silence_vtk_output();
  vtkSmartPointer<vtkPolyData> poly;
  if (!sorted.topology.empty()) {
    poly = to_polydata(mesh.vertices, sorted.topology);
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(poly);
    mass->Update();
    r.volume_m3 = mass->GetVolume();
    r.area_m2 = mass->GetSurfaceArea();
  }
  if (sorted.quality.empty()) return;
  // Usually nothing is degenerate and the topology's data set serves as it is.
  if (sorted.quality.size() != sorted.topology.size())
    poly = to_polydata(mesh.vertices, sorted.quality);
  const QualityStats min_angle =
      mesh_quality(poly, [](vtkMeshQuality* q) { q->SetTriangleQualityMeasureToMinAngle(); });
  const QualityStats max_angle =
      mesh_quality(poly, [](vtkMeshQuality* q) { q->SetTriangleQualityMeasureToMaxAngle(); });
  const QualityStats aspect =
      mesh_quality(poly, [](vtkMeshQuality* q) { q->SetTriangleQualityMeasureToAspectRatio(); });
  r.min_angle_deg = min_angle.min;
  r.mean_min_angle_deg = min_angle.mean;
  r.max_angle_deg = max_angle.max;
  r.mean_aspect_ratio = aspect.mean;
  r.max_aspect_ratio = aspect.max;
}

}  // namespace

MeshReport inspect_mesh(const TriangleMesh& mesh, const std::string& source) {
  MeshReport r;
  r.source = source;
  r.vertices = static_cast<std::int64_t>(mesh.vertices.size());
  r.triangles = static_cast<std::int64_t>(mesh.triangles.size());
  check_indices_and_coordinates(mesh, source);
  r.duplicate_vertices = duplicate_vertices(mesh);
  const SortedTriangles sorted = sort_triangles(mesh);
  r.degenerate_triangles = sorted.degenerate;
  add_topology(mesh, sorted.topology, r);
  add_extent(mesh, sorted.topology, r);
  add_signed_volume(mesh, sorted.topology, r);
  add_vtk_measures(mesh, sorted, r);
  return r;
}

MeshReport inspect_obj(const std::filesystem::path& path) {
  return inspect_mesh(meshio::read_obj(path), path.string());
}

nlohmann::ordered_json to_json(const MeshReport& r) {
  nlohmann::ordered_json j;
  j["file"] = r.source;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["edges"] = r.edges;
  j["boundary_edges"] = r.boundary_edges;
  j["non_manifold_edges"] = r.non_manifold_edges;
  j["inconsistent_edges"] = r.inconsistent_edges;
  j["duplicate_vertices"] = r.duplicate_vertices;
  j["unused_vertices"] = r.unused_vertices;
  j["degenerate_triangles"] = r.degenerate_triangles;
  j["components"] = r.components;
  j["euler_characteristic"] = r.euler_characteristic;
  j["closed"] = r.closed;
  j["consistently_oriented"] = r.consistently_oriented;
  j["outward"] = r.outward ? nlohmann::ordered_json(*r.outward) : nlohmann::ordered_json(nullptr);
  j["volume_m3"] = r.volume_m3;
  j["signed_volume_m3"] = r.signed_volume_m3;
  j["area_m2"] = r.area_m2;
  j["bounding_box"] = {{"min", r.bbox_min}, {"max", r.bbox_max}};
  j["min_edge_m"] = r.min_edge_m;
  j["mean_edge_m"] = r.mean_edge_m;
  j["max_edge_m"] = r.max_edge_m;
  j["min_angle_deg"] = r.min_angle_deg;
  j["mean_min_angle_deg"] = r.mean_min_angle_deg;
  j["max_angle_deg"] = r.max_angle_deg;
  j["mean_aspect_ratio"] = r.mean_aspect_ratio;
  j["max_aspect_ratio"] = r.max_aspect_ratio;
  return j;
}

std::string format_table(const MeshReport& r) {
  std::string out;
  char buf[256];
  auto row = [&](const char* name, const std::string& value, const char* note = "") {
    std::snprintf(buf, sizeof buf, "  %-24s %s%s\n", name, value.c_str(), note);
    out += buf;
  };
  auto num = [](double v, const char* fmt = "%.6g") {
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return std::string(b);
  };
  auto count = [](std::int64_t v) { return std::to_string(v); };
  auto flag = [](std::int64_t v) { return v == 0 ? "" : "   <-- problem"; };
  out += r.source + "\n";
  row("vertices", count(r.vertices));
  row("triangles", count(r.triangles));
  row("edges", count(r.edges));
  row("boundary edges", count(r.boundary_edges), flag(r.boundary_edges));
  row("non-manifold edges", count(r.non_manifold_edges), flag(r.non_manifold_edges));
  row("inconsistent edges", count(r.inconsistent_edges), flag(r.inconsistent_edges));
  row("duplicate vertices", count(r.duplicate_vertices), flag(r.duplicate_vertices));
  row("unused vertices", count(r.unused_vertices));
  row("degenerate triangles", count(r.degenerate_triangles), flag(r.degenerate_triangles));
  row("components", count(r.components));
  row("Euler characteristic", count(r.euler_characteristic), "   (2 for a sphere)");
  row("closed", r.closed ? "yes" : "no");
  row("consistently oriented", r.consistently_oriented ? "yes" : "no");
  row("outward", r.outward ? (*r.outward ? "yes" : "no (inside out)") : "undefined");
  row("volume", num(r.volume_m3) + " m^3");
  row("signed volume", num(r.signed_volume_m3) + " m^3");
  row("area", num(r.area_m2) + " m^2");
  row("bounding box min",
      num(r.bbox_min[0]) + " " + num(r.bbox_min[1]) + " " + num(r.bbox_min[2]) + " m");
  row("bounding box max",
      num(r.bbox_max[0]) + " " + num(r.bbox_max[1]) + " " + num(r.bbox_max[2]) + " m");
  row("edge length min/mean/max",
      num(r.min_edge_m) + " / " + num(r.mean_edge_m) + " / " + num(r.max_edge_m) + " m");
  row("angle min/mean-min/max", num(r.min_angle_deg, "%.2f") + " / " +
                                    num(r.mean_min_angle_deg, "%.2f") + " / " +
                                    num(r.max_angle_deg, "%.2f") + " deg");
  row("aspect ratio mean/max",
      num(r.mean_aspect_ratio, "%.3f") + " / " + num(r.max_aspect_ratio, "%.3f"));
  return out;
}

}  // namespace thaw::inspect
