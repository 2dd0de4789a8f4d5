#include "sim/shape/obj_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "base/edge_topology.h"
#include "base/error.h"
#include "base/obj_reader.h"
#include "base/point3.h"

namespace thaw::sim {

namespace {

using V3 = meshio::Point3;
using meshio::cross, meshio::dot, meshio::norm, meshio::sub;

/// Squared distance from p to triangle abc (Ericson, "Real-Time Collision Detection", 5.1.5).
double triangle_distance2(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto d2_to = [&](const V3& q) {
    const V3 d = sub(p, q);
    return dot(d, d);
  };
  if (d1 <= 0 && d2 <= 0) return d2_to(a);
  const V3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return d2_to(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return d2_to({a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]});
  }
  const V3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return d2_to(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return d2_to({a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return d2_to({b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])});
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return d2_to(
      {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w});
}

/// Solid angle of triangle abc seen from p (Van Oosterom & Strackee 1983), signed.
double solid_angle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 x = sub(a, p), y = sub(b, p), z = sub(c, p);
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = dot(x, cross(y, z));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(y, z) * lx + dot(z, x) * ly;
  return 2 * std::atan2(num, den);
}

}  // namespace

double ObjMesh::signed_distance(const V3& p) const {
  double best = std::numeric_limits<double>::infinity(), winding = 0;
  for (const auto& t : triangles) {
    const V3 &a = vertices[t[0]], &b = vertices[t[1]], &c = vertices[t[2]];
    best = std::min(best, triangle_distance2(p, a, b, c));
    winding += solid_angle(p, a, b, c);
  }
  const double d = std::sqrt(best);
  return winding / (4 * std::numbers::pi) > 0.5 ? -d : d;
}

double ObjMesh::volume() const {
  double v = 0;
  for (const auto& t : triangles) v += dot(vertices[t[0]], cross(vertices[t[1]], vertices[t[2]]));
  return v / 6;
}

ObjMesh read_obj_mesh(const std::filesystem::path& file, double scale, const V3& translate_m,
                      const std::string& scenario, const std::string& key) {
  const std::string name = file.string();
  auto fail = [&](const std::string& problem) {
    throw UserError(scenario, key, "OBJ file '" + name + "': " + problem);
  };
  // The one strict OBJ reader (base/obj_reader.h): its problems, named by line, under the scenario's key.
  meshio::TriangleMesh obj;
  try {
    obj = meshio::read_obj(file);
  } catch (const UserError& e) {
    fail((e.where().empty() ? "" : e.where() + ": ") + e.problem());
  }
  ObjMesh mesh;
  mesh.vertices.reserve(obj.vertices.size());
  for (const V3& v : obj.vertices)
    mesh.vertices.push_back({v[0] * scale + translate_m[0], v[1] * scale + translate_m[1],
                             v[2] * scale + translate_m[2]});
  if (obj.vertices.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    fail("has more than 2^31 vertices");
  for (std::size_t f = 0; f < obj.triangles.size(); ++f) {
    const auto& t = obj.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      fail("triangle " + std::to_string(f + 1) + " is degenerate (repeated vertex)");
    mesh.triangles.push_back(
        {static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  }
  if (mesh.triangles.size() < 4)
    fail("needs a closed surface (at least 4 triangles), found " +
         std::to_string(mesh.triangles.size()));
  // Closed, edge-manifold and consistently oriented: every edge used by exactly two triangles,
  // once in each direction (linear-time edge hash, base/edge_topology.h).
  const meshio::EdgeTopology topo = meshio::edge_topology(obj.vertices, obj.triangles);
  if (topo.non_manifold_edges > 0 || topo.inconsistent_edges > 0)
    fail("not manifold or inconsistently oriented: " +
         std::to_string(topo.non_manifold_edges + topo.inconsistent_edges) +
         " edges are used by more than two faces or twice in the same direction");
  if (topo.boundary_edges > 0)
    fail("not closed: " + std::to_string(topo.boundary_edges) + " edges border only one face");
  const double v = mesh.volume();
  if (!(v > 0))
    fail(
        "encloses a negative or zero volume: faces must be ordered counter-clockwise seen from "
        "outside");
  mesh.lower = mesh.upper = mesh.vertices[mesh.triangles[0][0]];
  for (const auto& t : mesh.triangles)
    for (int i : t)
      for (int a = 0; a < 3; ++a) {
        mesh.lower[a] = std::min(mesh.lower[a], mesh.vertices[i][a]);
        mesh.upper[a] = std::max(mesh.upper[a], mesh.vertices[i][a]);
      }
  return mesh;
}

}  // namespace thaw::sim
